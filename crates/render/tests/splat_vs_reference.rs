//! The GPU splat rasteriser against a reference written here plainly, sharing no code with it:
//! per pixel, every Gaussian in depth order, in f64, as the 3DGS reference implementation
//! defines the render (EWA projection with 0.3 px dilation, 3σ tile rectangles, α ≤ 0.99, α below
//! 1/255 skipped, stop before transmittance falls under 1e-4).

mod fixtures;

use std::sync::Arc;

use glam::{DMat3, DQuat, DVec2, DVec3};
use rslam_core::splat_io::SplatCloud;
use rslam_core::{DepthImage, Intrinsics, Pose, RgbImage};
use rslam_render::splat::{SplatDepth, SplatSettings};
use rslam_render::{Mesh, Rasterizer, Scene, Texture};

/// 100×70 pixels (7×5 tiles, the last ones partial), principal point off centre.
const CAMERA: Intrinsics = Intrinsics {
    width: 100,
    height: 70,
    fx: 80.0,
    fy: 78.0,
    cx: 46.3,
    cy: 37.9,
};

fn gpu_render(cloud: &SplatCloud, pose: &Pose, settings: SplatSettings) -> (RgbImage, DepthImage) {
    let ctx = fixtures::gpu();
    let scene = Scene {
        name: "test capture".into(),
        mesh: Mesh::default(),
        textures: vec![Texture::white()],
        default_trajectory: None,
        lights: None,
        splats: Some(Arc::new(cloud.clone())),
        floor: None,
    };
    let mut rasterizer =
        Rasterizer::with_splat_settings(ctx, &scene, CAMERA, settings).expect("upload capture");
    let rendered = fixtures::render_with(ctx, &mut rasterizer, &[*pose], |_, _| {});
    ctx.check().expect("no GPU error");
    rendered.into_iter().next().expect("one view")
}

struct Projected {
    pixel: DVec2,
    depth: f64,
    opacity: f64,
    conic: [f64; 3],
    color: DVec3,
    /// Tiles [min, max).
    tiles: ([i64; 2], [i64; 2]),
}

const SH_C0: f64 = 0.28209479177387814;
const SH_C1: f64 = 0.4886025119029199;
const SH_C2: [f64; 5] = [
    1.0925484305920792,
    -1.0925484305920792,
    0.31539156525252005,
    -1.0925484305920792,
    0.5462742152960396,
];
const SH_C3: [f64; 7] = [
    -0.5900435899266435,
    2.890611442640554,
    -0.4570457994644658,
    0.3731763325901154,
    -0.4570457994644658,
    1.445305721320277,
    -0.5900435899266435,
];

fn reference_color(sh: &[[f32; 3]], d: DVec3) -> DVec3 {
    let c = |k: usize| DVec3::new(sh[k][0] as f64, sh[k][1] as f64, sh[k][2] as f64);
    let (x, y, z) = (d.x, d.y, d.z);
    let mut out = SH_C0 * c(0);
    if sh.len() > 1 {
        out += -SH_C1 * y * c(1) + SH_C1 * z * c(2) - SH_C1 * x * c(3);
    }
    if sh.len() > 4 {
        let (xx, yy, zz) = (x * x, y * y, z * z);
        out += SH_C2[0] * x * y * c(4)
            + SH_C2[1] * y * z * c(5)
            + SH_C2[2] * (2.0 * zz - xx - yy) * c(6)
            + SH_C2[3] * x * z * c(7)
            + SH_C2[4] * (xx - yy) * c(8);
        if sh.len() > 9 {
            out += SH_C3[0] * y * (3.0 * xx - yy) * c(9)
                + SH_C3[1] * x * y * z * c(10)
                + SH_C3[2] * y * (4.0 * zz - xx - yy) * c(11)
                + SH_C3[3] * z * (2.0 * zz - 3.0 * xx - 3.0 * yy) * c(12)
                + SH_C3[4] * x * (4.0 * zz - xx - yy) * c(13)
                + SH_C3[5] * z * (xx - yy) * c(14)
                + SH_C3[6] * x * (xx - 3.0 * yy) * c(15);
        }
    }
    (out + DVec3::splat(0.5)).max(DVec3::ZERO)
}

fn project(cloud: &SplatCloud, i: usize, pose: &Pose) -> Option<Projected> {
    let k = CAMERA;
    let world_to_camera = pose.inverse();
    let mean = DVec3::from(cloud.means[i].map(f64::from));
    let p = world_to_camera.transform_point(mean);
    if p.z <= 0.2 {
        return None;
    }
    let [w, x, y, z] = cloud.rotations[i].map(f64::from);
    let r = DMat3::from_quat(DQuat::from_xyzw(x, y, z, w).normalize());
    let s = DMat3::from_diagonal(DVec3::from(cloud.log_scales[i].map(f64::from)).exp());
    let sigma = r * s * s.transpose() * r.transpose();
    let view = DMat3::from_quat(world_to_camera.rotation);
    let sigma_cam = view * sigma * view.transpose();
    let lim_x = 1.3 * 0.5 * k.width as f64 / k.fx;
    let lim_y = 1.3 * 0.5 * k.height as f64 / k.fy;
    let centre_x = (0.5 * (k.width as f64 - 1.0) - k.cx) / k.fx;
    let centre_y = (0.5 * (k.height as f64 - 1.0) - k.cy) / k.fy;
    let tx = (p.x / p.z).clamp(centre_x - lim_x, centre_x + lim_x) * p.z;
    let ty = (p.y / p.z).clamp(centre_y - lim_y, centre_y + lim_y) * p.z;
    let row0 = DVec3::new(k.fx / p.z, 0.0, -k.fx * tx / (p.z * p.z));
    let row1 = DVec3::new(0.0, k.fy / p.z, -k.fy * ty / (p.z * p.z));
    let a = row0.dot(sigma_cam * row0) + 0.3;
    let b = row0.dot(sigma_cam * row1);
    let c = row1.dot(sigma_cam * row1) + 0.3;
    let det = a * c - b * b;
    if det <= 0.0 {
        return None;
    }
    let mid = 0.5 * (a + c);
    let radius = (3.0 * (mid + (mid * mid - det).max(0.1).sqrt()).sqrt()).ceil();
    let pixel = DVec2::new(k.fx * p.x / p.z + k.cx, k.fy * p.y / p.z + k.cy);
    let grid = [k.width.div_ceil(16) as i64, k.height.div_ceil(16) as i64];
    let lo = |v: f64, g: i64| (((v - radius) / 16.0).floor() as i64).clamp(0, g);
    let hi = |v: f64, g: i64| (((v + radius + 15.0) / 16.0).floor() as i64).clamp(0, g);
    let tiles = (
        [lo(pixel.x, grid[0]), lo(pixel.y, grid[1])],
        [hi(pixel.x, grid[0]), hi(pixel.y, grid[1])],
    );
    if tiles.1[0] <= tiles.0[0] || tiles.1[1] <= tiles.0[1] {
        return None;
    }
    let centre = pose.translation;
    Some(Projected {
        pixel,
        depth: p.z,
        opacity: 1.0 / (1.0 + (-(cloud.opacity_logits[i] as f64)).exp()),
        conic: [c / det, -b / det, a / det],
        color: reference_color(cloud.sh_of(i), (mean - centre).normalize()),
        tiles,
    })
}

/// Colour (0–255, unrounded) and depth of every pixel.
fn reference_render(
    cloud: &SplatCloud,
    pose: &Pose,
    settings: SplatSettings,
) -> (Vec<[f64; 3]>, Vec<f64>) {
    let mut splats: Vec<Projected> = (0..cloud.len())
        .filter_map(|i| project(cloud, i, pose))
        .collect();
    splats.sort_by(|a, b| a.depth.total_cmp(&b.depth));
    let (w, h) = (CAMERA.width as usize, CAMERA.height as usize);
    let mut colors = Vec::with_capacity(w * h);
    let mut depths = Vec::with_capacity(w * h);
    for y in 0..h {
        for x in 0..w {
            let tile = [(x / 16) as i64, (y / 16) as i64];
            let mut t = 1.0f64;
            let mut color = DVec3::ZERO;
            let mut depth_sum = 0.0;
            let mut median = 0.0;
            for s in &splats {
                let inside = (0..2).all(|a| s.tiles.0[a] <= tile[a] && tile[a] < s.tiles.1[a]);
                if !inside {
                    continue;
                }
                let d = s.pixel - DVec2::new(x as f64, y as f64);
                let power = -0.5 * (s.conic[0] * d.x * d.x + s.conic[2] * d.y * d.y)
                    - s.conic[1] * d.x * d.y;
                if power > 0.0 {
                    continue;
                }
                let alpha = (s.opacity * power.exp()).min(0.99);
                if alpha < 1.0 / 255.0 {
                    continue;
                }
                let next = t * (1.0 - alpha);
                if next < 1e-4 {
                    break;
                }
                color += s.color * alpha * t;
                depth_sum += s.depth * alpha * t;
                if t >= 0.5 && next < 0.5 {
                    median = s.depth;
                }
                t = next;
            }
            let opacity = 1.0 - t;
            let depth = if opacity >= settings.min_opacity as f64 && opacity > 0.0 {
                match settings.depth {
                    SplatDepth::Expected => depth_sum / opacity,
                    SplatDepth::Median => median,
                }
            } else {
                0.0
            };
            colors.push((color.clamp(DVec3::ZERO, DVec3::ONE) * 255.0).to_array());
            depths.push(depth);
        }
    }
    (colors, depths)
}

/// Compares a GPU render with the reference: colour rounded alike, depth within 1e-4 relative
/// where both measure, and the same pixels measured.
fn assert_matches(cloud: &SplatCloud, pose: &Pose, settings: SplatSettings) {
    let (rgb, depth) = gpu_render(cloud, pose, settings);
    let (colors, depths) = reference_render(cloud, pose, settings);
    // Every channel is the reference rounded to the nearest level, within float error.
    let worst = (rgb.data.chunks_exact(3).zip(&colors))
        .flat_map(|(got, reference)| got.iter().zip(reference))
        .map(|(&got, &reference)| (got as f64 - reference).abs())
        .fold(0.0, f64::max);
    assert!(worst < 0.55, "colour off the reference by {worst} levels");
    let mut measured = 0;
    for (i, &reference) in depths.iter().enumerate() {
        let got = depth.data[i] as f64;
        assert_eq!(
            got > 0.0,
            reference > 0.0,
            "pixel {i}: depth {got} vs {reference}"
        );
        if reference > 0.0 {
            measured += 1;
            assert!(
                (got - reference).abs() <= 1e-4 * reference + 1e-5,
                "pixel {i}: depth {got} vs {reference}"
            );
        }
    }
    assert!(
        measured > 300,
        "only {measured} pixels measured: a weak test scene"
    );
}

/// A camera at the origin looking down +z (OpenCV axes).
fn facing_z() -> Pose {
    Pose::new(DQuat::IDENTITY, DVec3::ZERO)
}

/// xorshift in [0, 1).
struct Random(u64);

impl Random {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }

    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.next()
    }
}

/// `count` Gaussians in front of the camera, anisotropic and rotated, with SH of `degree`.
fn random_cloud(count: usize, degree: u32, seed: u64) -> SplatCloud {
    let mut r = Random(seed);
    let k = ((degree + 1) * (degree + 1)) as usize;
    let mut cloud = SplatCloud {
        sh_degree: degree,
        ..Default::default()
    };
    for _ in 0..count {
        let z = r.range(0.8, 4.0);
        cloud
            .means
            .push([r.range(-0.6, 0.6) * z, r.range(-0.5, 0.5) * z, z]);
        cloud.log_scales.push([
            r.range(-4.0, -1.5),
            r.range(-4.0, -1.5),
            r.range(-5.0, -2.0),
        ]);
        cloud.rotations.push([
            r.range(-1.0, 1.0),
            r.range(-1.0, 1.0),
            r.range(-1.0, 1.0),
            r.range(0.1, 1.0),
        ]);
        cloud.opacity_logits.push(r.range(-2.0, 4.0));
        cloud
            .sh
            .push([r.range(-1.5, 1.5), r.range(-1.5, 1.5), r.range(-1.5, 1.5)]);
        for _ in 1..k {
            cloud
                .sh
                .push([r.range(-0.4, 0.4), r.range(-0.4, 0.4), r.range(-0.4, 0.4)]);
        }
    }
    cloud
}

#[test]
fn degree_zero_anisotropic_rotated_gaussians_match_the_reference() {
    let cloud = random_cloud(300, 0, 7);
    assert_matches(&cloud, &facing_z(), SplatSettings::default());
}

#[test]
fn degree_three_colours_match_the_reference_from_a_turned_camera() {
    let cloud = random_cloud(300, 3, 11);
    let pose = Pose::new(
        DQuat::from_euler(glam::EulerRot::YXZ, 0.12, -0.08, 0.05),
        DVec3::new(0.1, -0.05, -0.2),
    );
    assert_matches(&cloud, &pose, SplatSettings::default());
}

#[test]
fn median_depth_and_a_lower_opacity_threshold_match_the_reference() {
    let cloud = random_cloud(300, 1, 13);
    let settings = SplatSettings {
        depth: SplatDepth::Median,
        min_opacity: 0.2,
    };
    assert_matches(&cloud, &facing_z(), settings);
}

#[test]
fn gaussians_behind_the_camera_and_straddling_the_near_plane_match_the_reference() {
    let mut cloud = random_cloud(150, 0, 17);
    // Behind the camera, and large: must not leak into the frame.
    for (mean, scale) in [([0.0, 0.0, -1.0], -0.5), ([0.3, 0.1, -0.1], 0.0)] {
        cloud.means.push(mean);
        cloud.log_scales.push([scale; 3]);
        cloud.rotations.push([1.0, 0.0, 0.0, 0.0]);
        cloud.opacity_logits.push(5.0);
        cloud.sh.push([2.0, -2.0, 2.0]);
    }
    // Centre in front of the near cut (z = 0.2) and behind it, each reaching across it.
    for (mean, scale) in [([0.05, 0.02, 0.26], -1.6), ([-0.05, 0.0, 0.15], -1.6)] {
        cloud.means.push(mean);
        cloud.log_scales.push([scale; 3]);
        cloud.rotations.push([0.9, 0.3, 0.1, 0.0]);
        cloud.opacity_logits.push(1.0);
        cloud.sh.push([1.0, 0.2, -0.5]);
    }
    assert_matches(&cloud, &facing_z(), SplatSettings::default());
}

#[test]
fn thousands_overlapping_in_one_tile_match_the_reference() {
    // Far more than one 256-Gaussian batch in the same tiles, most of them nearly transparent,
    // so that pixels blend across batches before they saturate.
    let mut cloud = random_cloud(3000, 0, 19);
    for (i, mean) in cloud.means.iter_mut().enumerate() {
        let z = 1.0 + 0.001 * i as f32;
        *mean = [
            0.02 * (i % 7) as f32 - 0.06,
            0.02 * (i % 5) as f32 - 0.04,
            z,
        ];
    }
    cloud.opacity_logits.iter_mut().for_each(|o| *o = -4.0);
    assert_matches(&cloud, &facing_z(), SplatSettings::default());
}
