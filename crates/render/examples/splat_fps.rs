//! Frames per second of the splat rasteriser at 1200×680 (Replica camera) on a capture of room0
//! made from its mesh (`rslam_render::splat::capture_of_mesh`: N flat Gaussians over its
//! surfaces, coloured by them), seen along room0's path. Projection, both sorts, blending and the
//! readback are timed together, one frame at a time.
//!
//! `cargo run --release -p rslam-render --example splat_fps -- [GAUSSIANS] [FRAMES]`
//! (default 500000 and 20); `RSLAM_ADAPTER=NAME` picks the GPU.

use std::time::Instant;

use rslam_core::Intrinsics;
use rslam_gpu::{AdapterChoice, FrameReadback, FrameTextures, GpuContext};
use rslam_render::splat::capture_of_mesh;
use rslam_render::{load_scene, Rasterizer, Scene};

fn main() {
    let mut args = std::env::args().skip(1);
    let count: usize = args
        .next()
        .map_or(500_000, |a| a.parse().expect("GAUSSIANS"));
    let frames: usize = args.next().map_or(20, |a| a.parse().expect("FRAMES"));
    let choice = AdapterChoice {
        name_contains: std::env::var("RSLAM_ADAPTER").ok(),
    };
    let ctx = GpuContext::new(&choice).expect("Vulkan adapter");
    let room = load_scene("room0").expect("room0");
    let poses = room.default_trajectory.clone().expect("path").poses;
    let cloud = capture_of_mesh(&room, count);
    let scene = Scene {
        name: format!("room0 as {} Gaussians", cloud.len()),
        mesh: Default::default(),
        splats: Some(std::sync::Arc::new(cloud)),
        ..room
    };
    let k = Intrinsics::REPLICA;
    let mut rasterizer = Rasterizer::new(&ctx, &scene, k).expect("upload");
    let frame = FrameTextures::new(&ctx, k.width, k.height);
    let readback = FrameReadback::new(&ctx, k.width, k.height, true);
    let mut render = |i: usize| {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        let pose = &poses[(i * 37) % poses.len()];
        rasterizer
            .encode(&ctx, &mut encoder, &frame, pose)
            .expect("render");
        readback.encode_copy(&mut encoder, &frame);
        let submission = ctx.queue.submit([encoder.finish()]);
        readback.read(&ctx, submission).expect("readback");
    };
    render(0);
    let start = Instant::now();
    for i in 1..=frames {
        render(i);
    }
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "{}, {}x{}, {}: {:.2} frames/s ({:.1} ms a frame, {frames} frames)",
        scene.name,
        k.width,
        k.height,
        ctx.describe(),
        frames as f64 / seconds,
        1e3 * seconds / frames as f64
    );
}
