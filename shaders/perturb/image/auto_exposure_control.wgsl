// auto_exposure, pass 3 (one invocation): the controller, mirrored by `control` in
// crates/perturb/src/image/auto_exposure.rs. The exposure·gain product that would have brought
// the metered mean to the target moves towards it by a first-order lag in log space
// (H ← H · (H*/H)^α, α = 1 − exp(−1/τ)); the exposure time takes it up to its maximum, analog
// gain the rest, each set in its register steps. The state stays on the GPU; the next frame's
// sensor pass reads it.

struct ExposureState {
    exposure_ms: f32,
    gain: f32,
    // The exposure·gain product the controller steers, before the register steps.
    steered_ms: f32,
    metered: f32,
}

struct Control {
    // x: target mean (linear), y: α, z: min exposure (ms), w: max exposure (ms)
    law: vec4<f32>,
    // x: max gain, y: exposure step (ms), z: gain step
    limits: vec4<f32>,
}

@group(0) @binding(0) var<storage, read_write> state: ExposureState;
@group(0) @binding(1) var<uniform> sums: vec4<f32>;
@group(0) @binding(2) var<uniform> control: Control;

@compute @workgroup_size(1)
fn main() {
    let metered = (sums.x + sums.y + sums.z) / (3.0 * sums.w);
    let applied = state.exposure_ms * state.gain;
    let wanted = clamp(
        applied * control.law.x / max(metered, 1e-4),
        control.law.z,
        control.law.w * control.limits.x,
    );
    let steered = state.steered_ms * exp(control.law.y * log(wanted / state.steered_ms));
    let exposure = in_steps(clamp(steered, control.law.z, control.law.w), control.limits.y);
    let gain = in_steps(clamp(steered / exposure, 1.0, control.limits.x), control.limits.z);
    state = ExposureState(exposure, gain, steered, metered);
}

// `value` rounded to a whole number of `step`s, halves up.
fn in_steps(value: f32, step: f32) -> f32 {
    return floor(value / step + 0.5) * step;
}
