// auto_exposure, pass 1: the sensor model (driven by crates/perturb/src/image/auto_exposure.rs).
// Each channel of the rendered sRGB frame is a pixel's linear irradiance relative to the nominal
// exposure, where 1 fills the full well: photo-electrons Poisson(linear · full well · t / t_nominal)
// (exact sampler, common/rng.wgsl), read noise N(0, σ_read²) in electrons, saturation at the full
// well, conversion gain · analog gain to DN, rounding to the ADC's levels, clipping at its full
// scale, then back to sRGB rounded to 8 bits. The exposure and gain come from the controller's
// state (pass 3) of the previous frame.
#include "common/rng.wgsl"
#include "common/color.wgsl"
#include "perturb/image/pointwise_runs.wgsl"

struct Params {
    shot_key: vec4<u32>,
    read_key: vec4<u32>,
    // x: full well (e-), y: read noise (e- rms), z: ADC full scale (DN), w: nominal exposure (ms)
    sensor: vec4<f32>,
}

struct ExposureState {
    exposure_ms: f32,
    gain: f32,
    steered_ms: f32,
    metered: f32,
}

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> params: Params;
@group(0) @binding(3) var<uniform> state: ExposureState;

fn corrupt(p: vec2<u32>, x: vec3<f32>) -> vec3<f32> {
    let full_well = params.sensor.x;
    let dn_max = params.sensor.z;
    // Means beyond twice the full well saturate whatever the draw; capping them keeps the
    // sampler's rate bounded.
    let electrons_mean = min(
        srgb_to_linear(x) * (full_well * state.exposure_ms / params.sensor.w),
        vec3<f32>(2.0 * full_well),
    );
    let read = rng_normal3(params.read_key, vec4<u32>(p, 0u, 0u)) * params.sensor.y;
    let dn_per_electron = state.gain * dn_max / full_well;
    var dn: vec3<f32>;
    for (var channel = 0u; channel < 3u; channel++) {
        let shot = rng_poisson(params.shot_key, vec3<u32>(p, channel), electrons_mean[channel]);
        let electrons = clamp(shot + read[channel], 0.0, full_well);
        dn[channel] = min(floor(electrons * dn_per_electron + 0.5), dn_max);
    }
    return linear_to_srgb(dn / dn_max) + 0.5 / 255.0;
}
