// gaussian_blur, pass 2 of 2: the vertical half of the separable Gaussian (edge replicate), from
// the f32 texture of pass 1 to 8 bits by truncation. Also glass_blur's second pass.
#include "perturb/image/filter_rgb8.wgsl"
#include "perturb/image/filter_columns.wgsl"
