//! The light items against what their models predict, on a plane built here whose light is two
//! layers (a lamp and the daylight) with known colours, seen by a camera at rest: flicker
//! sampled by the frame rate peaks at the alias frequency with its full depth, integrated over an
//! exposure with the depth times sinc; under a rolling shutter each band of rows shows the flicker
//! at its read-out instant; switched lamps go dark on exactly the frames their schedule says.

use std::f64::consts::PI;
use std::sync::{Arc, OnceLock};

use rslam_core::{ImagePool, Intrinsics, Pose, RgbImage};
use rslam_gpu::{AdapterChoice, GpuContext, MappedFrame};
use rslam_perturb::image_f32::srgb_to_linear;
use rslam_perturb::light::{Flicker, LayerKind, LightSchedule};
use rslam_perturb::sensor::RollingShutter;
use rslam_perturb::PerturbSpec;
use rslam_pipeline::sink::FrameSink;
use rslam_pipeline::source::SceneSource;
use rslam_pipeline::{Pipeline, PipelineError, Silent};
use rslam_render::{LightKind, LightLayers, Mesh, Scene, Texture, Vertex};

const CAMERA: Intrinsics = Intrinsics {
    width: 64,
    height: 120,
    fx: 100.0,
    fy: 100.0,
    cx: 31.5,
    cy: 59.5,
};
const RATE_HZ: f64 = 30.0;
const SEED: u64 = 11;
/// Linear colour the lamp and the daylight give the plane at full strength.
const LAMP: f32 = 0.3;
const DAYLIGHT: f32 = 0.1;

fn context() -> &'static GpuContext {
    static CONTEXT: OnceLock<GpuContext> = OnceLock::new();
    CONTEXT.get_or_init(|| {
        GpuContext::new(&AdapterChoice::default())
            .unwrap_or_else(|e| panic!("these tests need an adapter (lavapipe is fine): {e}"))
    })
}

/// A plane at z = 2 m filling the view, lit by one lamp and the daylight.
fn lit_plane() -> Arc<Scene> {
    let mut mesh = Mesh::default();
    for (x, y) in [(-3.0, -3.0), (3.0, -3.0), (3.0, 3.0), (-3.0, 3.0)] {
        mesh.vertices.push(Vertex {
            position: [x, y, 2.0],
            uv: [0.0, 0.0],
            color: [255; 4],
            layer: 0,
        });
    }
    mesh.indices = vec![0, 1, 2, 0, 2, 3];
    let colours = (0..4).flat_map(|_| [[LAMP; 3], [DAYLIGHT; 3]]).collect();
    Arc::new(Scene {
        name: "lit-plane".into(),
        mesh,
        textures: vec![Texture::white()],
        default_trajectory: None,
        splats: None,
        floor: None,
        lights: Some(LightLayers {
            kinds: vec![LightKind::Lamp, LightKind::Daylight],
            colours,
        }),
    })
}

struct Collect(Vec<RgbImage>);

impl FrameSink for Collect {
    fn accept(&mut self, source: usize, frame: MappedFrame) -> Result<(), PipelineError> {
        assert_eq!(source, self.0.len(), "frames in order");
        self.0.push(frame.unpack(&ImagePool::default())?.0);
        Ok(())
    }
}

/// `count` frames of the camera at rest under `spec`.
fn frames(spec: &str, count: usize) -> Vec<RgbImage> {
    let ctx = context();
    let spec = PerturbSpec::parse(spec).unwrap();
    let poses = vec![Pose::IDENTITY; count];
    let mut source =
        SceneSource::new(ctx, &lit_plane(), CAMERA, poses, Default::default(), None).unwrap();
    source.set_sensor(ctx, &spec, RATE_HZ, SEED).unwrap();
    let mut pipeline = Pipeline::new(ctx, source, &spec, SEED).unwrap();
    let mut sink = Collect(Vec::new());
    let sources: Vec<usize> = (0..count).collect();
    pipeline.run(ctx, &sources, &Silent, &mut sink).unwrap();
    sink.0
}

/// The lamp's intensity that a row's (or a frame's) mean linear value shows.
fn lamp_intensity(linear: f64) -> f64 {
    (linear - DAYLIGHT as f64) / LAMP as f64
}

fn mean_linear(image: &RgbImage, rows: std::ops::Range<u32>) -> f64 {
    let w = image.width as usize;
    let values: Vec<f64> = rows
        .flat_map(|y| (0..w).map(move |x| (y as usize * w + x) * 3))
        .map(|i| srgb_to_linear(image.data[i] as f32 / 255.0) as f64)
        .collect();
    values.iter().sum::<f64>() / values.len() as f64
}

/// Amplitude of the component at `bin` cycles over the series (single-sided).
fn amplitude(series: &[f64], bin: usize) -> f64 {
    let n = series.len() as f64;
    let (re, im) = series
        .iter()
        .enumerate()
        .fold((0.0, 0.0), |(re, im), (j, v)| {
            let a = 2.0 * PI * bin as f64 * j as f64 / n;
            (re + v * a.cos(), im - v * a.sin())
        });
    2.0 * (re * re + im * im).sqrt() / n
}

/// The series' strongest non-constant bin and its amplitude.
fn peak(series: &[f64]) -> (usize, f64) {
    (1..series.len() / 2)
        .map(|k| (k, amplitude(series, k)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap()
}

#[test]
fn flicker_aliases_to_the_frame_rate_with_the_depth_the_exposure_leaves() {
    // 100 Hz seen at 30 Hz aliases to |100 − 3·30| = 10 Hz: 30 cycles over 90 frames (3 s).
    let depth = 0.3;
    for (spec, expected) in [
        ("flicker:100/0.3", depth),
        // A 4 ms exposure averages the flicker: depth · sin(π·100·0.004) / (π·100·0.004).
        (
            "flicker:100/0.3,exposure:4",
            depth * (0.4 * PI).sin() / (0.4 * PI),
        ),
    ] {
        let series: Vec<f64> = frames(spec, 90)
            .iter()
            .map(|f| lamp_intensity(mean_linear(f, 0..CAMERA.height)))
            .collect();
        let (bin, found) = peak(&series);
        assert_eq!(bin, 30, "{spec}: the peak is at {} Hz", bin as f64 / 3.0);
        assert!(
            (found - expected).abs() < 0.04 * expected,
            "{spec}: amplitude {found}, expected {expected}"
        );
    }
}

#[test]
fn a_rolling_shutter_shows_flicker_as_bands_at_each_rows_instant() {
    let image = &frames("flicker:100/0.5,rolling_shutter:30", 2)[1];
    let flicker = Flicker::parse("100/0.5").unwrap();
    let phase = Flicker::phase(SEED);
    let shutter = RollingShutter::parse("30", None).unwrap();
    // 30 ms of read-out at 100 Hz: three periods over the frame, in eight bands each.
    let t = 1.0 / RATE_HZ;
    let mut worst = 0.0f64;
    let mut rows = Vec::new();
    for y in 0..CAMERA.height {
        let seen = lamp_intensity(mean_linear(image, y..y + 1));
        rows.push(seen);
        let at_row = flicker.at(phase, t + shutter.row_offset(y as f64, CAMERA.height));
        worst = worst.max((seen - at_row).abs());
    }
    // Bands of 5 rows each take their middle row's instant: the flicker moves by at most
    // 2π·100·(2.5 rows · 0.25 ms) · 0.5 ≈ 0.2 within a band.
    assert!(
        worst < 0.22,
        "a row is {worst} off its read-out instant's flicker"
    );
    assert_eq!(peak(&rows).0, 3, "three flicker periods over the rows");
}

#[test]
fn switched_lamps_go_dark_on_the_frames_their_schedule_says() {
    for spec in ["lights:1/0.5/0.2", "lights:1/0.5/0.2,exposure:20"] {
        let parsed = PerturbSpec::parse(spec).unwrap();
        let layers = [LayerKind::Lamp, LayerKind::Daylight];
        let schedule = LightSchedule::new(&parsed.light, SEED, &layers, 10.0);
        let half = parsed.exposure.map_or(0.0, |e| e.seconds() / 2.0);
        let seen = frames(spec, 60);
        let mut dark = 0;
        for (j, frame) in seen.iter().enumerate() {
            let t = j as f64 / RATE_HZ;
            let expected = schedule.weights(t - half, t + half)[0][0] as f64;
            let found = lamp_intensity(mean_linear(frame, 0..CAMERA.height));
            assert!(
                (found - expected).abs() < 0.02,
                "{spec} frame {j}: {found} vs {expected}"
            );
            dark += usize::from(expected == 0.0);
        }
        assert!(dark > 3 && dark < 57, "{spec}: {dark} of 60 frames dark");
    }
}
