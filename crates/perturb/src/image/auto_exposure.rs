//! auto_exposure: a camera whose exposure time and analog gain follow the scene's brightness with
//! a lag, imaging through a linear sensor model (EMVA 1288's: photons → electrons → DN).
//!
//! Each frame runs three passes on the GPU: the sensor model with the exposure and gain of the
//! controller's state (`auto_exposure.wgsl`), the mean linear brightness of the frame it wrote
//! (`auto_exposure_meter.wgsl`, a [`Reduction`]), and the controller updating its state for the
//! next frame (`auto_exposure_control.wgsl`, one invocation). The state lives in a GPU buffer from
//! frame to frame, so nothing is read back to steer the camera; the twin carries the same state
//! ([`Twin::ColorSequence`]). Frames must come in capture order: each frame's exposure follows from
//! the frames before it (the first gets the nominal exposure at unity gain).

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use super::color_pass::ColorPass;
use crate::image_f32::{linear_to_srgb, srgb_to_linear, RgbF32};
use crate::perturbation::{CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::reduce::Reduction;
use crate::twin::{Tolerance, Twin, TwinState};
use crate::uniform_layout::{rust_layout, RustLayout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "auto_exposure";
const SHADER: &str = "perturb/image/auto_exposure.wgsl";
const METER_SHADER: &str = "perturb/image/auto_exposure_meter.wgsl";
const CONTROL_SHADER: &str = "perturb/image/auto_exposure_control.wgsl";
const PURPOSE_SHOT: u32 = 0;
const PURPOSE_READ: u32 = 1;

/// The camera at one severity: a slower controller and a noisier, shallower pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Level {
    /// Time constant of the controller's first-order lag, in frames.
    pub time_constant_frames: f32,
    /// Saturation (full-well) capacity in electrons.
    pub full_well: f32,
    /// Temporal dark (read) noise in electrons rms.
    pub read_noise: f32,
}

/// Severity 1..=5. Full well and read noise span the EMVA 1288 figures of global-shutter
/// machine-vision sensors, from a large-pixel Sony Pregius (~20 ke⁻, ~3 e⁻) through an
/// MT9V034-class pixel (55 dB linear dynamic range: 8 ke⁻ / 12 e⁻) to small-pixel parts; the time
/// constants span a fast machine-vision AE (2 frames) to a sluggish webcam/UVC AE (~1 s at 30 Hz).
/// docs/src/sensor-effects.md, "Auto exposure and the sensor", lists the sources and what is assumed.
pub const LEVELS: [Level; 5] = [
    Level {
        time_constant_frames: 2.0,
        full_well: 20_000.0,
        read_noise: 3.0,
    },
    Level {
        time_constant_frames: 4.0,
        full_well: 12_000.0,
        read_noise: 6.0,
    },
    Level {
        time_constant_frames: 8.0,
        full_well: 8_000.0,
        read_noise: 12.0,
    },
    Level {
        time_constant_frames: 15.0,
        full_well: 5_000.0,
        read_noise: 18.0,
    },
    Level {
        time_constant_frames: 30.0,
        full_well: 3_000.0,
        read_noise: 25.0,
    },
];

/// The exposure at which a rendered linear value of 1 fills the full well, and the first frame's.
pub const NOMINAL_EXPOSURE_MS: f32 = 10.0;
/// The exposure is set in whole row times (assumed 20 µs, the order of a VGA global-shutter
/// sensor's row), from one row up to a 20 ms frame budget.
pub const EXPOSURE_STEP_MS: f32 = 0.02;
pub const MIN_EXPOSURE_MS: f32 = EXPOSURE_STEP_MS;
pub const MAX_EXPOSURE_MS: f32 = 20.0;
/// Analog gain range (MT9V034: 1× to 4×, register steps of 1/16), used once the exposure is at
/// its maximum.
pub const MAX_GAIN: f32 = 4.0;
pub const GAIN_STEP: f32 = 1.0 / 16.0;
/// ADC full scale: 10 bits (MT9V034).
pub const DN_MAX: f32 = 1023.0;
/// The mean linear brightness the controller steers to: 18 % grey (sRGB level 118).
pub const TARGET_MEAN: f32 = 0.18;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "auto-exposure camera: exposure (then analog gain) follows the frames' mean brightness to 18 % grey with a first-order lag; sensor photons → electrons (Poisson shot noise, read noise, full-well saturation) → 10-bit DN; frames in capture order; exposure and gain per frame in sensor_state.csv",
    parameters: |s| {
        let l = LEVELS[s as usize - 1];
        format!(
            "τ={} frames, full well {} e-, read noise {} e-",
            l.time_constant_frames, l.full_well, l.read_noise
        )
    },
    build: |kit| Ok(Box::new(AutoExposure::new(kit)?)),
    explicit: None,
    twin: Twin::ColorSequence {
        initial: ExposureState::INITIAL.as_twin_state(),
        fields: ["exposure_ms", "gain", "steered_ms", "metered_mean"],
        step: twin,
    },
    // As shot_noise (PTRS accept/reject on last-bit differences). The metered mean is summed in
    // another order on the GPU, but exposure and gain are set in register steps, so both sides
    // apply the same ones unless the steered value sits within its last bits of a step's edge.
    twin_tolerance: Tolerance {
        outliers: 1e-3,
        ..Tolerance::ONE_LEVEL
    },
    uniforms: &[
        SensorParams::LAYOUT,
        ExposureState::layout(SHADER),
        ExposureState::layout(CONTROL_SHADER),
        ControlParams::LAYOUT,
    ],
};

/// The controller's state, WGSL `ExposureState`: what the sensor pass of the next frame uses.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq, Pod, Zeroable)]
pub struct ExposureState {
    pub exposure_ms: f32,
    pub gain: f32,
    /// The exposure·gain product the controller steers, before exposure and gain are set in
    /// their register steps (keeping it lets the lag move by less than a step per frame).
    pub steered_ms: f32,
    /// The mean linear brightness of the frame the controller last saw.
    pub metered: f32,
}

impl ExposureState {
    pub const INITIAL: Self = Self {
        exposure_ms: NOMINAL_EXPOSURE_MS,
        gain: 1.0,
        steered_ms: NOMINAL_EXPOSURE_MS,
        metered: 0.0,
    };

    const LAYOUT: RustLayout = rust_layout!(ExposureState {
        exposure_ms,
        gain,
        steered_ms,
        metered
    });

    const fn layout(shader: &'static str) -> UniformLayout {
        UniformLayout {
            rust: Self::LAYOUT,
            wgsl: "ExposureState",
            shader,
        }
    }

    const fn as_twin_state(self) -> TwinState {
        [self.exposure_ms, self.gain, self.steered_ms, self.metered]
    }

    fn from_twin_state(state: &TwinState) -> Self {
        bytemuck::cast(*state)
    }
}

/// WGSL `Params` of `auto_exposure.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct SensorParams {
    shot_key: [u32; 4],
    read_key: [u32; 4],
    /// full well (e-), read noise (e- rms), ADC full scale (DN), nominal exposure (ms)
    sensor: [f32; 4],
}

impl SensorParams {
    const LAYOUT: UniformLayout = UniformLayout {
        rust: rust_layout!(SensorParams {
            shot_key,
            read_key,
            sensor
        }),
        wgsl: "Params",
        shader: SHADER,
    };

    fn for_frame(key: &FrameKey) -> Self {
        let level = LEVELS[key.level()];
        Self {
            shot_key: key.rng(NAME, PURPOSE_SHOT).0,
            read_key: key.rng(NAME, PURPOSE_READ).0,
            sensor: [
                level.full_well,
                level.read_noise,
                DN_MAX,
                NOMINAL_EXPOSURE_MS,
            ],
        }
    }
}

/// WGSL `Control` of `auto_exposure_control.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct ControlParams {
    /// target mean, α, min exposure (ms), max exposure (ms)
    law: [f32; 4],
    /// max gain, exposure step (ms), gain step
    limits: [f32; 4],
}

impl ControlParams {
    const LAYOUT: UniformLayout = UniformLayout {
        rust: rust_layout!(ControlParams { law, limits }),
        wgsl: "Control",
        shader: CONTROL_SHADER,
    };

    fn for_frame(key: &FrameKey) -> Self {
        let tau = LEVELS[key.level()].time_constant_frames;
        Self {
            law: [
                TARGET_MEAN,
                1.0 - (-1.0 / tau).exp(),
                MIN_EXPOSURE_MS,
                MAX_EXPOSURE_MS,
            ],
            limits: [MAX_GAIN, EXPOSURE_STEP_MS, GAIN_STEP, 0.0],
        }
    }
}

struct AutoExposure {
    sensor: ColorPass,
    meter: Reduction,
    control: wgpu::ComputePipeline,
    control_params: wgpu::Buffer,
    /// The controller's state, read and written by the control pass.
    state: wgpu::Buffer,
    /// The state the sensor pass of this frame reads (a uniform copy, see [`Kit::uniform_buffer`]),
    /// and the per-frame log's source ([`GpuPerturbation::state`]).
    state_now: wgpu::Buffer,
}

impl AutoExposure {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        let state = kit.storage_buffer(CONTROL_SHADER, std::mem::size_of::<ExposureState>() as u64);
        kit.ctx
            .queue
            .write_buffer(&state, 0, bytemuck::bytes_of(&ExposureState::INITIAL));
        Ok(Self {
            sensor: ColorPass::runs::<SensorParams>(kit, SHADER)?,
            meter: Reduction::new(kit, METER_SHADER)?,
            control: kit.pipeline(CONTROL_SHADER)?,
            control_params: kit.uniform_buffer::<ControlParams>(CONTROL_SHADER),
            state,
            state_now: kit.ctx.device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(SHADER),
                size: std::mem::size_of::<ExposureState>() as u64,
                usage: wgpu::BufferUsages::UNIFORM
                    | wgpu::BufferUsages::COPY_DST
                    | wgpu::BufferUsages::COPY_SRC,
                mapped_at_creation: false,
            }),
        })
    }
}

impl GpuPerturbation for AutoExposure {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        encoder.copy_buffer_to_buffer(&self.state, 0, &self.state_now, 0, None);
        self.sensor.encode(
            kit,
            encoder,
            frame,
            &SensorParams::for_frame(key),
            &[self.state_now.as_entire_binding()],
        );
        self.meter.encode(kit, encoder, frame.color_view());
        kit.write_uniform(&self.control_params, &ControlParams::for_frame(key));
        let bind_group = kit.bind_group(
            &self.control,
            CONTROL_SHADER,
            &[
                self.state.as_entire_binding(),
                self.meter.sums().as_entire_binding(),
                self.control_params.as_entire_binding(),
            ],
        );
        kit.dispatch_workgroups(
            encoder,
            &self.control,
            &bind_group,
            CONTROL_SHADER,
            [1, 1, 1],
        );
        Ok(())
    }

    fn state(&self) -> Option<&wgpu::Buffer> {
        Some(&self.state_now)
    }
}

/// The sensor's output in DN for one channel of pixel (x, y): `linear` is the rendered linear
/// value (1 fills the full well at the nominal exposure); the same arithmetic as the shader.
pub fn sensor_dn(
    key: &FrameKey,
    state: &ExposureState,
    site: [u32; 3],
    linear: f32,
    read_normal: f32,
) -> f32 {
    let level = LEVELS[key.level()];
    let full_well = level.full_well;
    let electrons_mean =
        (linear * (full_well * state.exposure_ms / NOMINAL_EXPOSURE_MS)).min(2.0 * full_well);
    let shot = key.rng(NAME, PURPOSE_SHOT).poisson(site, electrons_mean);
    let electrons = (shot + read_normal * level.read_noise).clamp(0.0, full_well);
    let dn_per_electron = state.gain * DN_MAX / full_well;
    (electrons * dn_per_electron + 0.5).floor().min(DN_MAX)
}

/// The controller's step (the WGSL `main` of `auto_exposure_control.wgsl`): the state after a
/// frame whose mean linear brightness was `metered`.
pub fn control(state: &ExposureState, metered: f32, key: &FrameKey) -> ExposureState {
    let [target, alpha, min_exposure, max_exposure] = ControlParams::for_frame(key).law;
    let [max_gain, exposure_step, gain_step, _] = ControlParams::for_frame(key).limits;
    let applied = state.exposure_ms * state.gain;
    let wanted =
        (applied * target / metered.max(1e-4)).clamp(min_exposure, max_exposure * max_gain);
    let steered = state.steered_ms * (alpha * (wanted / state.steered_ms).ln()).exp();
    let exposure_ms = in_steps(steered.clamp(min_exposure, max_exposure), exposure_step);
    let gain = in_steps((steered / exposure_ms).clamp(1.0, max_gain), gain_step);
    ExposureState {
        exposure_ms,
        gain,
        steered_ms: steered,
        metered,
    }
}

/// `value` rounded to a whole number of `step`s (halves up, as WGSL `floor(x + 0.5)`).
fn in_steps(value: f32, step: f32) -> f32 {
    (value / step + 0.5).floor() * step
}

/// The mean linear brightness of a frame as written (8-bit levels), the meter pass's mean.
pub fn metered_mean(image: &RgbF32) -> f32 {
    let written = RgbF32::from_rgb8(&image.to_rgb8());
    let sum: f64 = written
        .data
        .iter()
        .flatten()
        .map(|&v| srgb_to_linear(v) as f64)
        .sum();
    (sum / (3 * written.data.len()) as f64) as f32
}

/// CPU twin of the three passes: the frame through the sensor at the state's exposure and gain,
/// then the controller's step on what was written.
pub fn twin(image: &RgbF32, key: &FrameKey, state: &mut TwinState) -> RgbF32 {
    let now = ExposureState::from_twin_state(state);
    let read = key.rng(NAME, PURPOSE_READ);
    let out = image.map_pixels(|x, y, p| {
        let normals = read.normal3([x, y, 0, 0]);
        std::array::from_fn(|ch| {
            let dn = sensor_dn(
                key,
                &now,
                [x, y, ch as u32],
                srgb_to_linear(p[ch]),
                normals[ch],
            );
            linear_to_srgb(dn / DN_MAX) + 0.5 / 255.0
        })
    });
    *state = control(&now, metered_mean(&out), key).as_twin_state();
    out
}

#[cfg(test)]
#[path = "auto_exposure_tests.rs"]
mod tests;
