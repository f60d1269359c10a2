#include "perturb/image/filter_rg.wgsl"
#include "perturb/image/filter_columns.wgsl"
