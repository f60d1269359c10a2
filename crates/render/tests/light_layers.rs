//! A built-in scene's light layers: at full strength they mix to the baked colours, and the GPU's
//! mix (`mesh.wgsl`) draws what its CPU twin ([`LightLayers::lit_mesh`]) gives for any weights —
//! every lamp off, daylight tinted — while differing clearly from the baked light.

use rslam_core::{Intrinsics, Pose, RgbImage};
use rslam_gpu::{AdapterChoice, FrameReadback, FrameTextures, GpuContext};
use rslam_render::{load_scene, LightKind, Rasterizer, Scene};

const CAMERA: Intrinsics = Intrinsics {
    width: 160,
    height: 96,
    fx: 80.0,
    fy: 80.0,
    cx: 79.5,
    cy: 47.5,
};

fn srgb(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        c * 12.92 * 255.0
    } else {
        (1.055 * c.powf(1.0 / 2.4) - 0.055) * 255.0
    }
}

#[test]
fn every_light_at_full_strength_mixes_to_the_baked_colours() {
    let scene = load_scene("room0").unwrap();
    let lights = scene
        .lights
        .as_ref()
        .expect("a built-in scene has light layers");
    assert_eq!(lights.names().last().map(String::as_str), Some("daylight"));
    assert!(
        lights
            .kinds
            .iter()
            .filter(|&&k| k == LightKind::Lamp)
            .count()
            >= 2
    );
    let ones = vec![[1.0; 3]; lights.kinds.len()];
    let mut worst = 0.0f32;
    for (i, v) in scene.mesh.vertices.iter().enumerate() {
        let mixed = lights.mixed(i, &ones);
        for (&m, &baked) in mixed.iter().zip(&v.color) {
            worst = worst.max((srgb(m) - baked as f32).abs());
        }
    }
    // The baked colour is the total encoded through a 4096-step table and rounded to 8 bits (up
    // to 0.84 levels off the exact encoding seen here); the layers sum to the total up to f32
    // rounding. A layer missing or counted twice moves vertices by tens of levels.
    assert!(
        worst <= 1.0,
        "a vertex's mix is {worst} levels off its baked colour"
    );
}

fn render(ctx: &GpuContext, scene: &Scene, pose: &Pose, weights: Option<&[[f32; 3]]>) -> RgbImage {
    let mut rasterizer = Rasterizer::new(ctx, scene, CAMERA).unwrap();
    rasterizer.set_light(ctx, weights).unwrap();
    let frame = FrameTextures::new(ctx, CAMERA.width, CAMERA.height);
    let readback = FrameReadback::new(ctx, CAMERA.width, CAMERA.height, false);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    rasterizer.encode(ctx, &mut encoder, &frame, pose).unwrap();
    readback.encode_copy(&mut encoder, &frame);
    let submission = ctx.queue.submit([encoder.finish()]);
    readback.read(ctx, submission).unwrap().0
}

/// Mean and largest |difference| per channel, in 8-bit levels.
fn difference(a: &RgbImage, b: &RgbImage) -> (f64, u8) {
    let d: Vec<u8> = a
        .data
        .iter()
        .zip(&b.data)
        .map(|(x, y)| x.abs_diff(*y))
        .collect();
    let mean = d.iter().map(|&v| v as f64).sum::<f64>() / d.len() as f64;
    (mean, d.into_iter().max().unwrap_or(0))
}

#[test]
fn the_gpu_mix_draws_what_its_cpu_twin_gives() {
    let ctx = GpuContext::new(&AdapterChoice::default()).expect("a Vulkan adapter");
    let scene = load_scene("room0").unwrap();
    let lights = scene.lights.clone().unwrap();
    let path = scene.default_trajectory.as_ref().unwrap();
    let baked_twin = |weights: &[[f32; 3]]| Scene {
        mesh: lights.lit_mesh(&scene.mesh, weights),
        lights: None,
        ..scene.clone()
    };
    let lamps_off: Vec<[f32; 3]> = (lights.kinds.iter())
        .map(|k| match k {
            LightKind::Lamp => [0.0; 3],
            LightKind::Daylight => [0.8, 0.85, 1.1],
        })
        .collect();
    let uneven: Vec<[f32; 3]> = (0..lights.kinds.len())
        .map(|l| [0.3 + 0.4 * l as f32; 3])
        .collect();
    for pose in path.poses.iter().step_by(500) {
        let baked = render(&ctx, &scene, pose, None);
        for weights in [&lamps_off, &uneven] {
            let mixed = render(&ctx, &scene, pose, Some(weights));
            let twin = render(&ctx, &baked_twin(weights), pose, None);
            let (mean, max) = difference(&mixed, &twin);
            // The twin's vertex colours are rounded to 8 bits before interpolation, the mix's
            // are not: a level or two apart, on average well under one.
            assert!(
                mean < 0.5 && max <= 4,
                "mix vs twin: mean {mean}, max {max}"
            );
            let (changed, _) = difference(&mixed, &baked);
            assert!(
                changed > 3.0,
                "the weights barely change the frame: {changed}"
            );
        }
    }
}
