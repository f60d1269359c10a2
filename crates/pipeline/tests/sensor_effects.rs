//! Exposure and rolling shutter against what the camera's motion predicts, on planes built here:
//! a black|white edge at a known depth and a checkerboard, seen by a camera moving at a known
//! speed.

use std::sync::OnceLock;

use glam::{DQuat, DVec3};
use rslam_core::{DepthImage, ImagePool, Intrinsics, Pose, RgbImage};
use rslam_gpu::{AdapterChoice, GpuContext, MappedFrame};
use rslam_perturb::image_f32::srgb_to_linear;
use rslam_perturb::PerturbSpec;
use rslam_pipeline::sink::FrameSink;
use rslam_pipeline::source::SceneSource;
use rslam_pipeline::{Pipeline, PipelineError, Silent};
use rslam_render::{Mesh, Scene, Texture, Vertex};

const CAMERA: Intrinsics = Intrinsics {
    width: 160,
    height: 120,
    fx: 200.0,
    fy: 200.0,
    cx: 79.5,
    cy: 59.5,
};
const RATE_HZ: f64 = 10.0;
/// Distance of the plane in front of the camera, metres.
const PLANE_Z: f64 = 2.0;

fn context() -> &'static GpuContext {
    static CONTEXT: OnceLock<GpuContext> = OnceLock::new();
    CONTEXT.get_or_init(|| {
        GpuContext::new(&AdapterChoice::default())
            .unwrap_or_else(|e| panic!("these tests need an adapter (lavapipe is fine): {e}"))
    })
}

/// An axis-aligned rectangle of the plane z = PLANE_Z in one colour.
fn quad(mesh: &mut Mesh, [x0, y0, x1, y1]: [f32; 4], grey: u8) {
    let base = mesh.vertices.len() as u32;
    for (x, y) in [(x0, y0), (x1, y0), (x1, y1), (x0, y1)] {
        mesh.vertices.push(Vertex {
            position: [x, y, PLANE_Z as f32],
            uv: [0.0, 0.0],
            color: [grey, grey, grey, 255],
            layer: 0,
        });
    }
    mesh.indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
}

fn scene(name: &str, mesh: Mesh) -> Scene {
    Scene {
        name: name.into(),
        mesh,
        textures: vec![Texture::white()],
        default_trajectory: None,
        splats: None,
        floor: None,
        lights: None,
    }
}

/// Black for world x < 0, white for x > 0: a vertical edge.
fn edge_scene() -> Scene {
    let mut mesh = Mesh::default();
    quad(&mut mesh, [-20.0, -20.0, 0.0, 20.0], 0);
    quad(&mut mesh, [0.0, -20.0, 20.0, 20.0], 255);
    scene("edge", mesh)
}

/// Squares of 0.1 m (10 px at the plane's depth), black and white.
fn checker_scene() -> Scene {
    let mut mesh = Mesh::default();
    for i in -15..15 {
        for j in -15..15 {
            let (x, y) = (i as f32 * 0.1, j as f32 * 0.1);
            let grey = if (i + j) % 2 == 0 { 0 } else { 255 };
            quad(&mut mesh, [x, y, x + 0.1, y + 0.1], grey);
        }
    }
    scene("checker", mesh)
}

struct Collect(Vec<(RgbImage, DepthImage)>);

impl FrameSink for Collect {
    fn accept(&mut self, _source: usize, frame: MappedFrame) -> Result<(), PipelineError> {
        let (color, depth) = frame.unpack(&ImagePool::default())?;
        self.0.push((color, depth.expect("scenes have depth")));
        Ok(())
    }
}

/// Frame `index` of `scene` along `poses` (at RATE_HZ) under `spec`.
fn render(scene: &Scene, poses: &[Pose], spec: &str, index: usize) -> (RgbImage, DepthImage) {
    let ctx = context();
    let spec = match spec {
        "" => PerturbSpec::default(),
        text => PerturbSpec::parse(text).unwrap(),
    };
    let scene = std::sync::Arc::new(scene.clone());
    let mut source = SceneSource::new(
        ctx,
        &scene,
        CAMERA,
        poses.to_vec(),
        Default::default(),
        None,
    )
    .unwrap();
    source.set_sensor(ctx, &spec, RATE_HZ, 0).unwrap();
    let mut pipeline = Pipeline::new(ctx, source, &spec, 0).unwrap();
    let mut sink = Collect(Vec::new());
    pipeline.run(ctx, &[index], &Silent, &mut sink).unwrap();
    sink.0.pop().unwrap()
}

/// Row `y` in linear light (grey: the red channel).
fn linear_row(image: &RgbImage, y: u32) -> Vec<f64> {
    (0..image.width)
        .map(|x| {
            srgb_to_linear(image.data[((y * image.width + x) * 3) as usize] as f32 / 255.0) as f64
        })
        .collect()
}

/// Where a rising profile first reaches `level`, interpolated between pixel centres.
fn crossing(profile: &[f64], level: f64) -> f64 {
    let i = profile
        .windows(2)
        .position(|w| w[0] < level && w[1] >= level)
        .unwrap_or_else(|| panic!("the profile never rises through {level}: {profile:?}"));
    i as f64 + (level - profile[i]) / (profile[i + 1] - profile[i])
}

fn sideways(speed_m_s: f64) -> Vec<Pose> {
    (0..5)
        .map(|i| Pose::new(DQuat::IDENTITY, DVec3::X * speed_m_s * i as f64 / RATE_HZ))
        .collect()
}

/// Translating at v past a plane at depth z, an exposure T smears an edge over v·T·f/z pixels
/// (a linear ramp in linear light), centred where the edge is at mid-exposure.
#[test]
fn blur_length_is_speed_times_exposure_times_focal_over_depth() {
    let (speed, exposure_s) = (2.0, 0.1);
    let poses = sideways(speed);
    let (color, depth) = render(&edge_scene(), &poses, "exposure:100", 2);
    let expected = speed * exposure_s * CAMERA.fx / PLANE_Z;
    for y in [10, 60, 110] {
        let row = linear_row(&color, y);
        let (low, high) = (crossing(&row, 0.1), crossing(&row, 0.9));
        let length = (high - low) / 0.8;
        assert!(
            (length - expected).abs() < 0.1 * expected,
            "row {y}: blur of {length:.2} px, expected {expected:.2}"
        );
        let mid_exposure_x = poses[2].translation.x;
        let edge = CAMERA.cx - CAMERA.fx * mid_exposure_x / PLANE_Z;
        let centre = crossing(&row, 0.5);
        assert!(
            (centre - edge).abs() < 1.0,
            "row {y}: ramp centred at {centre:.2}, the mid-exposure edge is at {edge:.2}"
        );
    }
    let z = depth.data[(60 * CAMERA.width + 80) as usize];
    assert!(
        (z as f64 - PLANE_Z).abs() < 1e-4,
        "depth at mid-exposure: {z}"
    );
}

/// Under `fast:2` the camera covers two path samples per frame interval, during the exposure
/// too: twice the blur.
#[test]
fn fast_motion_blurs_in_proportion() {
    let poses = sideways(2.0);
    let (color, _) = render(&edge_scene(), &poses, "exposure:100,fast:2", 2);
    let row = linear_row(&color, 60);
    let length = (crossing(&row, 0.9) - crossing(&row, 0.1)) / 0.8;
    let expected = 2.0 * 2.0 * 0.1 * CAMERA.fx / PLANE_Z;
    assert!(
        (length - expected).abs() < 0.1 * expected,
        "blur of {length:.2} px, expected {expected:.2}"
    );
}

#[test]
fn zero_exposure_is_the_clean_frame() {
    let poses = sideways(2.0);
    let clean = render(&edge_scene(), &poses, "", 2);
    assert_eq!(render(&edge_scene(), &poses, "exposure:0", 2), clean);
    assert_eq!(render(&edge_scene(), &poses, "exposure:0@9", 2), clean);
    // A camera at rest through the whole sum-and-encode path: the same frame to a level.
    let still = vec![poses[2]; 5];
    let (summed, depth) = render(&checker_scene(), &still, "exposure:30@5", 2);
    let (plain, plain_depth) = render(&checker_scene(), &still, "", 2);
    assert_eq!(depth, plain_depth);
    let worst = summed
        .data
        .iter()
        .zip(&plain.data)
        .map(|(a, b)| a.abs_diff(*b))
        .max();
    assert!(worst <= Some(1), "largest difference {worst:?} levels");
}

/// A roll about the optical axis moves pixels in proportion to their distance from the
/// principal point: the border blurs, the centre hardly.
#[test]
fn rotation_blurs_the_border_more_than_the_centre() {
    let poses: Vec<Pose> = (0..5)
        .map(|i| Pose::new(DQuat::from_rotation_z(0.2 * i as f64), DVec3::ZERO))
        .collect();
    let checker = checker_scene();
    let (clean, _) = render(&checker, &poses, "", 2);
    let (blurred, _) = render(&checker, &poses, "exposure:50", 2);
    let mean_change = |inside: &dyn Fn(f64) -> bool| {
        let (mut sum, mut count) = (0.0, 0);
        for y in 0..CAMERA.height {
            for x in 0..CAMERA.width {
                let r = (x as f64 - CAMERA.cx).hypot(y as f64 - CAMERA.cy);
                if inside(r) {
                    let i = ((y * CAMERA.width + x) * 3) as usize;
                    sum += clean.data[i].abs_diff(blurred.data[i]) as f64;
                    count += 1;
                }
            }
        }
        sum / count as f64
    };
    let centre = mean_change(&|r| r < 12.0);
    let border = mean_change(&|r| r > 55.0);
    assert!(
        border > 3.0 * centre && border > 20.0,
        "mean change: {centre:.1} levels at the centre, {border:.1} at the border"
    );
}

/// Panning at ω, the row read out at t sees the edge at cx − f·tan(ω t): a shear of f·ω·T/H
/// pixels per row over a read-out time T.
#[test]
fn rolling_shutter_shears_a_vertical_edge_by_the_pan() {
    let omega = 2.0;
    let readout_s = 0.06;
    let poses: Vec<Pose> = (0..5)
        .map(|i| {
            Pose::new(
                DQuat::from_rotation_y(omega * (i as f64 - 2.0) / RATE_HZ),
                DVec3::ZERO,
            )
        })
        .collect();
    let (color, depth) = render(&edge_scene(), &poses, "rolling_shutter:60", 2);
    let height = CAMERA.height as f64;
    let mut fit = (0.0, 0.0, 0.0, 0.0, 0.0);
    for y in 0..CAMERA.height {
        let t = ((y as f64 + 0.5) / height - 0.5) * readout_s;
        let predicted = CAMERA.cx - CAMERA.fx * (omega * t).tan();
        let got = crossing(&linear_row(&color, y), 0.5);
        assert!(
            (got - predicted).abs() < 1.0,
            "row {y}: edge at {got:.2}, predicted {predicted:.2}"
        );
        let yf = y as f64;
        fit = (
            fit.0 + 1.0,
            fit.1 + yf,
            fit.2 + got,
            fit.3 + yf * yf,
            fit.4 + yf * got,
        );
    }
    let (n, sy, sx, syy, syx) = fit;
    let per_row = (n * syx - sy * sx) / (n * syy - sy * sy);
    let expected = -CAMERA.fx * omega * readout_s / height;
    assert!(
        (per_row - expected).abs() < 0.05 * expected.abs(),
        "shear of {per_row:.4} px per row, expected {expected:.4}"
    );
    assert!(
        depth.data.iter().all(|&z| z > 0.0),
        "every row has depth from its own read-out"
    );
}

/// The lenses of the distortion tests: a barrel radial-tangential one with tangential terms,
/// and an equidistant fisheye.
const LENSES: [&str; 2] = [
    "distortion:radtan(-0.3,0.08,0.002,-0.0015)",
    "distortion:equidistant(0.08,-0.03,0.01,-0.002)",
];

/// A bright round dot on the plane at (x, y): a fan whose brightness falls linearly from the
/// centre to black at `radius`, so that its centroid is found to a small fraction of a pixel.
fn dot(mesh: &mut Mesh, (x, y): (f64, f64), radius: f64) {
    const SIDES: u32 = 24;
    let vertex = |x: f64, y: f64, grey: u8| Vertex {
        position: [x as f32, y as f32, PLANE_Z as f32],
        uv: [0.0, 0.0],
        color: [grey, grey, grey, 255],
        layer: 0,
    };
    let centre = mesh.vertices.len() as u32;
    mesh.vertices.push(vertex(x, y, 255));
    for i in 0..SIDES {
        let a = std::f64::consts::TAU * i as f64 / SIDES as f64;
        mesh.vertices
            .push(vertex(x + radius * a.cos(), y + radius * a.sin(), 0));
        mesh.indices
            .extend([centre, centre + 1 + i, centre + 1 + (i + 1) % SIDES]);
    }
}

/// Dots on the plane, placed to be seen 12 px from the corners, at the centre and between,
/// through each lens: the brightness centroid of each is within 0.5 px of its centre projected
/// through the lens (the intrinsics and coefficients the dataset files carry), and the depth
/// there is the plane's z.
#[test]
fn distorted_render_puts_points_where_the_lens_model_projects_them() {
    let radius = 0.05;
    let corner = CAMERA.cx.hypot(CAMERA.cy);
    for spec in LENSES {
        let lens = PerturbSpec::parse(spec).unwrap().distortion.unwrap();
        let mut mesh = Mesh::default();
        let mut centres = Vec::new();
        for u in [12.0, 40.0, 80.0, 120.0, 148.0] {
            for v in [12.0, 36.0, 60.0, 84.0, 108.0] {
                let seen =
                    glam::DVec2::new((u - CAMERA.cx) / CAMERA.fx, (v - CAMERA.cy) / CAMERA.fy);
                let ray = lens.undistort(seen).unwrap();
                centres.push((ray.x * PLANE_Z, ray.y * PLANE_Z));
                dot(&mut mesh, *centres.last().unwrap(), radius);
            }
        }
        let dots = scene("dots", mesh);
        let (color, depth) = render(&dots, &[Pose::IDENTITY; 3], spec, 1);
        let (mut checked, mut outermost, mut worst) = (0, 0.0f64, 0.0f64);
        for &(x, y) in &centres {
            let d = lens.distort(glam::DVec2::new(x / PLANE_Z, y / PLANE_Z));
            let (u, v) = (CAMERA.fx * d.x + CAMERA.cx, CAMERA.fy * d.y + CAMERA.cy);
            let half = 9;
            let (u0, v0) = (u.round() as i64 - half, v.round() as i64 - half);
            let inside = |p: i64, side: u32| p >= 0 && p + 2 * half < side as i64;
            if !inside(u0, CAMERA.width) || !inside(v0, CAMERA.height) {
                continue;
            }
            let (mut sum, mut su, mut sv, mut rim) = (0.0, 0.0, 0.0, 0.0f64);
            for py in v0..=v0 + 2 * half {
                for px in u0..=u0 + 2 * half {
                    let i = (py as u32 * CAMERA.width + px as u32) as usize;
                    let w = srgb_to_linear(color.data[i * 3] as f32 / 255.0) as f64;
                    sum += w;
                    su += w * px as f64;
                    sv += w * py as f64;
                    if px == u0 || py == v0 || px == u0 + 2 * half || py == v0 + 2 * half {
                        rim = rim.max(w);
                    }
                }
            }
            assert!(sum > 1.0, "{spec}: no dot near ({u:.1}, {v:.1})");
            assert!(
                rim == 0.0,
                "{spec}: the dot at ({u:.1}, {v:.1}) is not inside its window: {rim}"
            );
            let error = (su / sum - u).hypot(sv / sum - v);
            assert!(
                error < 0.5,
                "{spec}: dot ({x}, {y}) at ({:.2}, {:.2}), projected to ({u:.2}, {v:.2})",
                su / sum,
                sv / sum
            );
            let z = depth.data[(v.round() as u32 * CAMERA.width + u.round() as u32) as usize];
            assert!(
                (z as f64 - PLANE_Z).abs() < 1e-4,
                "{spec}: depth {z} at ({u:.1}, {v:.1})"
            );
            checked += 1;
            worst = worst.max(error);
            outermost = outermost.max((u - CAMERA.cx).hypot(v - CAMERA.cy));
        }
        assert_eq!(checked, centres.len(), "{spec}: every dot is checked");
        assert!(
            outermost > 0.75 * corner,
            "{spec}: the outermost dot checked is {outermost:.1} px from the centre, the corners {corner:.1}"
        );
        eprintln!("{spec}: {checked} dots, worst {worst:.3} px, out to {outermost:.0} px");
    }
}

/// The lens comes after the shutter's sum: a camera at rest gives the same frame with or
/// without `exposure` (to the level of the sum's sRGB round trip), and the lens changes it.
#[test]
fn distortion_composes_with_the_shutter() {
    let still = vec![Pose::new(DQuat::IDENTITY, DVec3::new(0.03, 0.02, 0.0)); 5];
    let checker = checker_scene();
    let (plain, _) = render(&checker, &still, "", 2);
    for lens in LENSES {
        let (through_lens, lens_depth) = render(&checker, &still, lens, 2);
        let (summed, summed_depth) = render(
            &checker,
            &still,
            &format!("exposure:30@5,rolling_shutter:20,{lens}"),
            2,
        );
        assert_eq!(lens_depth, summed_depth, "{lens}");
        let worst = summed
            .data
            .iter()
            .zip(&through_lens.data)
            .map(|(a, b)| a.abs_diff(*b))
            .max();
        assert!(
            worst <= Some(1),
            "{lens}: largest difference {worst:?} levels"
        );
        assert_ne!(through_lens, plain, "{lens} changes the frame");
    }
}
