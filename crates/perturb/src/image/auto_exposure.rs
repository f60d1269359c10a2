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
use crate::perturbation::{Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
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

/// The camera at the frame's severity: the time constant and read noise linear between the
/// table's rows and the full well linear in 1/full-well (the shot noise's variance), from an
/// instant, noiseless controller and pixel at severity 0.
fn level_at(key: &FrameKey) -> Level {
    match key.severity.as_whole() {
        Some(_) => LEVELS[key.level()],
        None => Level {
            time_constant_frames: key.interpolate(0.0, &LEVELS.map(|l| l.time_constant_frames))
                as f32,
            full_well: key.interpolate_in(
                0.0,
                &LEVELS.map(|l| l.full_well),
                |w| 1.0 / w,
                |r| 1.0 / r,
            ) as f32,
            read_noise: key.interpolate(0.0, &LEVELS.map(|l| l.read_noise)) as f32,
        },
    }
}

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
    between: Between::Interpolated("time constant and read noise linear from 0, full well linear in 1/full well from ∞"),
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
        let level = level_at(key);
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
        let tau = level_at(key).time_constant_frames;
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
    let level = level_at(key);
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
mod tests {
    use statrs::distribution::{ContinuousCDF, Discrete, Normal, Poisson};

    use super::*;
    use crate::image_f32::truncate8;
    use crate::testing::{self, EntryOnGpu};

    /// EMVA 1288's photon transfer: over flat patches the DN variance grows with the DN mean with
    /// slope K, the system gain (DN per electron), here analog gain × full scale / full well; the
    /// samples come from the twin's sensor function, which the GPU pass matches (catalogue test).
    #[test]
    fn photon_transfer_slope_is_the_system_gain() {
        let pixels = 20_000u32;
        for severity in [1u8, 3, 5] {
            let key = testing::key(7, severity);
            let read = key.rng(NAME, PURPOSE_READ);
            for gain in [1.0f32, 2.0] {
                let state = ExposureState {
                    gain,
                    ..ExposureState::INITIAL
                };
                let patches: Vec<(f64, f64)> = [0.05f32, 0.1, 0.2, 0.3, 0.4]
                    .iter()
                    .enumerate()
                    .map(|(patch, &linear)| {
                        let dn: Vec<f64> = (0..pixels)
                            .map(|i| {
                                let normal = read.normal3([i, patch as u32, 0, 0])[0];
                                sensor_dn(&key, &state, [i, patch as u32, 0], linear, normal) as f64
                            })
                            .collect();
                        let mean = dn.iter().sum::<f64>() / dn.len() as f64;
                        let var = dn.iter().map(|v| (v - mean).powi(2)).sum::<f64>()
                            / (dn.len() - 1) as f64;
                        (mean, var)
                    })
                    .collect();
                let n = patches.len() as f64;
                let (mx, my) = patches
                    .iter()
                    .fold((0.0, 0.0), |(sx, sy), (x, y)| (sx + x / n, sy + y / n));
                let slope = patches
                    .iter()
                    .map(|(x, y)| (x - mx) * (y - my))
                    .sum::<f64>()
                    / patches.iter().map(|(x, _)| (x - mx).powi(2)).sum::<f64>();
                let expected = (gain * DN_MAX / LEVELS[severity as usize - 1].full_well) as f64;
                assert!(
                    (slope / expected - 1.0).abs() < 0.1,
                    "severity {severity} gain {gain}: PTC slope {slope:.4} DN/e-, system gain \
                     {expected:.4}; patches (mean, var) {patches:?}"
                );
            }
        }
    }

    /// Above the full well every pixel reads full scale with no noise left; below it, they do not.
    #[test]
    fn saturation_clips_at_the_full_well() {
        for severity in [1u8, 5] {
            let key = testing::key(2, severity);
            let state = ExposureState::INITIAL;
            let read = key.rng(NAME, PURPOSE_READ);
            let dn = |linear: f32, i: u32| {
                sensor_dn(
                    &key,
                    &state,
                    [i, 0, 0],
                    linear,
                    read.normal3([i, 0, 0, 0])[0],
                )
            };
            assert!(
                (0..5000).all(|i| dn(1.1, i) == DN_MAX),
                "severity {severity}"
            );
            let below = (0..5000).filter(|&i| dn(0.9, i) < DN_MAX).count();
            assert_eq!(below, 5000, "severity {severity}: 0.9 of full well clipped");
        }
    }

    /// The exposure time takes the whole correction up to its maximum; the gain only the rest.
    #[test]
    fn gain_engages_only_at_the_maximum_exposure() {
        let key = testing::key(0, 1);
        let mut state = ExposureState::INITIAL;
        for _ in 0..40 {
            state = control(&state, 0.01, &key);
            assert!(
                state.gain == 1.0 || state.exposure_ms == MAX_EXPOSURE_MS,
                "{state:?}"
            );
        }
        assert_eq!(state.exposure_ms, MAX_EXPOSURE_MS);
        assert!((state.gain - MAX_GAIN).abs() < 1e-3, "{state:?}");
        for _ in 0..60 {
            state = control(&state, 0.9, &key);
        }
        assert_eq!(state.gain, 1.0);
        assert!(state.exposure_ms < MAX_EXPOSURE_MS, "{state:?}");
    }

    /// The probabilities of each output level of a flat patch at `level` through the sensor at the
    /// nominal exposure and unity gain: Poisson electrons convolved with the Gaussian read noise,
    /// clamped, rounded to DN, encoded to sRGB and rounded to 8 bits.
    fn output_level_law(level: u8, severity: u8) -> [f64; 256] {
        let l = LEVELS[severity as usize - 1];
        let k_dn = (DN_MAX / l.full_well) as f64;
        let lambda = (srgb_to_linear(level as f32 / 255.0) * l.full_well) as f64;
        let poisson = Poisson::new(lambda).expect("λ > 0");
        let read = Normal::new(0.0, l.read_noise as f64).expect("σ > 0");
        let span = 10.0 * lambda.sqrt() + 10.0;
        let mut levels = [0.0; 256];
        let out_level =
            |dn: f64| truncate8(linear_to_srgb((dn / DN_MAX as f64) as f32) + 0.5 / 255.0) as usize;
        for k in ((lambda - span).max(0.0) as u64)..=((lambda + span) as u64) {
            let pk = poisson.pmf(k);
            let centre = k as f64 * k_dn;
            let reach = 10.0 * l.read_noise as f64 * k_dn + 2.0;
            let low = (centre - reach).floor().max(0.0) as u32;
            let high = ((centre + reach).ceil() as u32).min(DN_MAX as u32);
            for dn in low..=high {
                // Electrons whose rounded DN is `dn`; 0 and full scale take the clamped tails.
                let from = if dn == 0 {
                    f64::NEG_INFINITY
                } else {
                    (dn as f64 - 0.5) / k_dn - k as f64
                };
                let to = if dn == DN_MAX as u32 {
                    f64::INFINITY
                } else {
                    (dn as f64 + 0.5) / k_dn - k as f64
                };
                levels[out_level(dn as f64)] += pk * (read.cdf(to) - read.cdf(from));
            }
        }
        levels
    }

    /// The GPU's first frame (nominal exposure, unity gain) of flat patches against the exact law
    /// of shot noise, read noise, DN and 8-bit rounding.
    #[test]
    fn noise_statistics_follow_the_sensor_law() {
        for level in [30u8, 118, 230] {
            let grey = testing::uniform_image(256, 256, level);
            for severity in [1u8, 3, 5] {
                let out = testing::run_color(&ENTRY, severity, 4, &grey);
                let (mean, std) = testing::level_stats(&output_level_law(level, severity));
                testing::assert_stats(
                    testing::stats(&out),
                    mean,
                    std,
                    &format!("level {level} severity {severity}"),
                );
            }
        }
    }

    /// Flat frames whose brightness drops by 5.7× (sRGB 118 → 50): on the GPU, the exposure·gain
    /// read off each frame (output mean / input linear) approaches the one that restores 18 % grey
    /// with the configured time constant (within 10 %) and settles there, through the exposure limit
    /// into gain; every frame matches the twin run on the same sequence.
    #[test]
    fn brightness_step_is_followed_with_the_time_constant() {
        let (w, h) = (64, 48);
        let (bright, dark) = (118u8, 50u8);
        for severity in [1u8, 3] {
            let tau = LEVELS[severity as usize - 1].time_constant_frames as f64;
            let mut gpu = EntryOnGpu::new(&ENTRY, w, h).expect("builds");
            let mut twin = ENTRY.twin.start();
            let frames = 6 + (8.0 * tau) as u32;
            let mut relative_exposure = Vec::new();
            for frame in 0..frames {
                let level = if frame < 3 { bright } else { dark };
                let input = testing::uniform_image(w, h, level);
                let key = FrameKey {
                    frame,
                    ..testing::key(9, severity)
                };
                let out = gpu.apply(&key, &input, None).expect("runs").color;
                let mut expected = testing::Frame {
                    color: input.clone(),
                    depth: rslam_core::DepthImage::new(w, h),
                };
                twin.apply(&mut expected.color, &mut expected.depth, &key);
                let label = format!("auto_exposure-step-s{severity}-frame{frame}");
                testing::compare_color(&out, &expected.color, &ENTRY.twin_tolerance, &label)
                    .unwrap_or_else(|e| panic!("{e}"));
                let scene = srgb_to_linear(level as f32 / 255.0) as f64;
                relative_exposure
                    .push((metered_mean(&RgbF32::from_rgb8(&out)) as f64 / scene, level));
            }
            let wanted = (TARGET_MEAN as f64) / srgb_to_linear(dark as f32 / 255.0) as f64;
            // Log distance to the settled exposure, frame by frame after the step.
            let errors: Vec<f64> = relative_exposure[3..]
                .iter()
                .map(|(h, _)| (wanted / h).ln())
                .collect();
            // Decay rates over the frames still well away from the settled value (gain steps of
            // 1/16 leave up to ~1 % of the log distance, noise less).
            let rates: Vec<f64> = errors
                .windows(2)
                .take_while(|e| e[1] > 0.2)
                .map(|e| (e[0] / e[1]).ln())
                .collect();
            assert!(rates.len() >= 2, "severity {severity}: {errors:?}");
            let measured_tau = rates.len() as f64 / rates.iter().sum::<f64>();
            assert!(
                (measured_tau / tau - 1.0).abs() < 0.1,
                "severity {severity}: τ measured {measured_tau:.2} frames, configured {tau}; \
                 log errors {errors:?}"
            );
            let settled = errors.last().expect("frames after the step").abs();
            assert!(settled < 0.02, "severity {severity}: settled {settled}");
            assert!(wanted * NOMINAL_EXPOSURE_MS as f64 > MAX_EXPOSURE_MS as f64);
        }
    }

    #[test]
    fn seeded() {
        testing::assert_seeded(&ENTRY, 3);
    }
}
