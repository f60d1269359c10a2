#include "perturb/image/filter_r.wgsl"
#include "perturb/image/filter_columns.wgsl"
