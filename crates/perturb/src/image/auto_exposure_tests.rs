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
                    let var =
                        dn.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (dn.len() - 1) as f64;
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
            relative_exposure.push((metered_mean(&RgbF32::from_rgb8(&out)) as f64 / scene, level));
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
