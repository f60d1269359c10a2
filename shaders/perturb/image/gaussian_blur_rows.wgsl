// gaussian_blur, pass 1 of 2: the horizontal half of a separable Gaussian (SciPy gaussian_filter,
// mode 'nearest' = edge replicate) into an f32 texture. Also the first pass of glass_blur's blurs.
#include "perturb/image/filter_rgb.wgsl"
#include "perturb/image/filter_rows.wgsl"
