use super::*;
use crate::testing;

/// Small frames: one GPU invocation per row of 160 pixels.
const W: u32 = 160;
const H: u32 = 120;

/// Measured σ_z over a wall may differ from the model's by this fraction (the 10 %).
const SIGMA_TOLERANCE: f64 = 0.10;

/// Shadow edges may be off by this many columns (f32 disparities at an exact pixel boundary).
const SHADOW_SLACK: u32 = 1;

fn wall(z: f32) -> DepthImage {
    DepthImage {
        width: W,
        height: H,
        data: vec![z; (W * H) as usize],
    }
}

fn key_for(values: &[f64]) -> FrameKey<'_> {
    FrameKey {
        explicit: Some(values),
        camera: Some(testing::camera(W, H)),
        ..testing::key(11, 5)
    }
}

/// Mean and standard deviation of the valid pixels, and how many were valid.
fn stats(depth: &DepthImage) -> (f64, f64, usize) {
    let valid: Vec<f64> = depth
        .data
        .iter()
        .filter(|&&z| z > 0.0)
        .map(|&z| z as f64)
        .collect();
    let n = valid.len() as f64;
    let mean = valid.iter().sum::<f64>() / n;
    let var = valid.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / n;
    (mean, var.sqrt(), valid.len())
}

/// On a fronto-parallel wall at z the measured depth's σ follows the model's own
/// σ_z(z) = z²/F · √(σ_d² + step²/12): z' = F/d' with d' = d + n + e, n ~ N(0, σ_d) and the
/// rounding error e ≈ uniform on ±step/2 (variance step²/12, Sheppard's correction, accurate to
/// ~1 % once σ_d ≥ step/2), and to first order δz = −z²/F · δd. Run on the GPU.
#[test]
fn noise_on_flat_walls_follows_the_model() {
    for (index, model) in MODELS.iter().enumerate() {
        let values = [index as f64];
        for z in [1.0f32, 2.0, 2.5, 3.0] {
            let out = testing::run_depth(&ENTRY, &key_for(&values), &wall(z));
            let (mean, std, valid) = stats(&out);
            assert_eq!(
                valid,
                out.data.len(),
                "{}: a flat wall has no shadow",
                model.name
            );
            let sigma = model.sigma_z(z) as f64;
            let ratio = std / sigma;
            eprintln!(
                "{} z={z} m: σ measured {:.3} mm, model {:.3} mm, ratio {ratio:.3}",
                model.name,
                std * 1e3,
                sigma * 1e3
            );
            assert!(
                (ratio - 1.0).abs() < SIGMA_TOLERANCE,
                "{} at {z} m: σ {std} vs model {sigma}",
                model.name
            );
            // Quantisation biases the mean by at most half a step's depth.
            let half_step = (z * z / model.fb_native() * model.disparity_step_px / 2.0) as f64;
            assert!((mean - z as f64).abs() < half_step + 3.0 * sigma / (valid as f64).sqrt());
        }
    }
}

/// Severity k multiplies the Kinect's σ_d by k.
#[test]
fn severity_scales_the_disparity_noise() {
    let key = FrameKey {
        camera: Some(testing::camera(W, H)),
        ..testing::key(3, 4)
    };
    let z = 2.0;
    let (_, std, _) = stats(&twin(&wall(z), &key));
    let sigma = model_at(3).sigma_z(z) as f64;
    assert!(
        (std / sigma - 1.0).abs() < SIGMA_TOLERANCE,
        "{std} vs {sigma}"
    );
    assert_eq!(
        model_at(3).sigma_disparity_px,
        4.0 * KINECT_V1.sigma_disparity_px
    );
}

/// A box at 1 m covering columns [60, 100), rows [40, 80) before a wall at 2 m.
const BOX_LEFT: u32 = 60;
const BOX_RIGHT: u32 = 100;
const BOX_ROWS: std::ops::Range<u32> = 40..80;

fn box_before_wall() -> DepthImage {
    let mut depth = wall(2.0);
    for y in BOX_ROWS {
        for x in BOX_LEFT..BOX_RIGHT {
            depth.data[(y * W + x) as usize] = 1.0;
        }
    }
    depth
}

/// The invalid pixels are the columns `shadow` of the box's rows, give or take `SHADOW_SLACK`
/// columns at each end.
fn assert_shadow(out: &DepthImage, shadow: std::ops::RangeInclusive<u32>, what: &str) {
    let (first, last) = (*shadow.start(), *shadow.end());
    for y in 0..H {
        for x in 0..W {
            let invalid = out.data[(y * W + x) as usize] == 0.0;
            let in_rows = BOX_ROWS.contains(&y);
            let surely = in_rows && x >= first + SHADOW_SLACK && x + SHADOW_SLACK <= last;
            let maybe = in_rows && x + SHADOW_SLACK >= first && x <= last + SHADOW_SLACK;
            assert!(
                invalid == surely || (maybe && !surely),
                "{what}: pixel ({x}, {y}) invalid={invalid}, shadow predicted in columns \
                 {first}..={last} of rows {BOX_ROWS:?}"
            );
        }
    }
}

/// The shadow of the box falls on the side away from the emitter, f·|b|·(1/1 − 1/2) columns
/// wide (the difference of the box's and the wall's disparities), and nowhere else.
#[test]
fn projector_shadow_falls_away_from_the_emitter() {
    let depth = box_before_wall();
    let camera = testing::camera(W, H);
    let width = (camera.fx as f32 * KINECT_V1.baseline_m * (1.0 - 0.5)).round() as u32;
    assert_eq!(width, 6);
    // The Kinect's projector is at +x: the shadow is left of the box (GPU pass).
    let values = [0.0];
    let out = testing::run_depth(&ENTRY, &key_for(&values), &depth);
    assert_shadow(
        &out,
        BOX_LEFT - width..=BOX_LEFT - 1,
        "kinect, emitter at +x",
    );
    // The same sensor with its emitter at −x: the shadow is right of the box.
    let mirrored = SensorModel {
        baseline_m: -KINECT_V1.baseline_m,
        ..KINECT_V1
    };
    let out = sense(&depth, &mirrored, camera.fx as f32, &key_for(&values));
    assert_shadow(
        &out,
        BOX_RIGHT..=BOX_RIGHT + width - 1,
        "kinect, emitter at −x",
    );
}

/// Depth outside [z_min, z_max] becomes invalid; depth inside stays valid (one value per row,
/// so no shadows).
#[test]
fn depth_outside_the_range_is_invalid() {
    for (index, model) in MODELS.iter().enumerate() {
        let values = [index as f64];
        let rows = [
            model.z_min * 0.8,
            model.z_min * 1.2,
            model.z_max * 0.9,
            model.z_max * 1.2,
        ];
        let mut depth = DepthImage::new(8, rows.len() as u32);
        for (y, &z) in rows.iter().enumerate() {
            depth.data[y * 8..(y + 1) * 8].fill(z);
        }
        let out = twin(&depth, &key_for(&values));
        for (y, &z) in rows.iter().enumerate() {
            let inside = z >= model.z_min && z <= model.z_max;
            for &got in &out.data[y * 8..(y + 1) * 8] {
                assert_eq!(got > 0.0, inside, "{} at {z} m gave {got}", model.name);
            }
        }
    }
}

#[test]
fn models_parse_and_format_back() {
    for (i, model) in MODELS.iter().enumerate() {
        assert_eq!(parse_model(model.name), Ok(vec![i as f64]));
        let form = ENTRY.explicit.as_ref().unwrap();
        assert_eq!((form.format)(&[i as f64]), model.name);
    }
    assert!(parse_model("kinect2").is_err());
    let spec = crate::PerturbSpec::parse("depth_sensor:realsense").unwrap();
    assert_eq!(spec.to_string(), "depth_sensor:realsense");
}

/// Without a camera (image files) the perturber refuses it with a message that says why.
#[test]
fn needs_a_camera() {
    let spec = crate::PerturbSpec::parse("depth_sensor:kinect").unwrap();
    let err = crate::Perturber::new(testing::context(), &spec, 32, 32, 0, None)
        .err()
        .expect("built without a camera");
    assert!(err.to_string().contains("camera"), "{err}");
    let camera = testing::camera(32, 32);
    assert!(crate::Perturber::new(testing::context(), &spec, 32, 32, 0, Some(camera)).is_ok());
}

#[test]
fn seeded() {
    testing::assert_seeded(&ENTRY, 3);
}
