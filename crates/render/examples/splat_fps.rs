//! Frames per second of the splat rasteriser at 1200×680 (Replica camera) on a capture of room0
//! made here: N Gaussians sampled over room0's surfaces by area, flat along them, sized to cover
//! them, coloured by the mesh, seen along room0's path. Projection, both sorts, blending and the
//! readback are timed together, one frame at a time.
//!
//! `cargo run --release -p rslam-render --example splat_fps -- [GAUSSIANS] [FRAMES]`
//! (default 500000 and 20); `RSLAM_ADAPTER=NAME` picks the GPU.

use std::time::Instant;

use glam::{Quat, Vec3};
use rslam_core::splat_io::SplatCloud;
use rslam_core::Intrinsics;
use rslam_gpu::{AdapterChoice, FrameReadback, FrameTextures, GpuContext};
use rslam_render::{load_scene, Rasterizer, Scene};

/// xorshift64 in [0, 1).
struct Random(u64);

impl Random {
    fn next(&mut self) -> f32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// `count` Gaussians over the mesh's triangles, each triangle's share by its area.
fn capture_of(scene: &Scene, count: usize) -> SplatCloud {
    let mesh = &scene.mesh;
    let corner = |t: usize, k: usize| &mesh.vertices[mesh.indices[3 * t + k] as usize];
    let areas: Vec<f32> = (0..mesh.triangle_count())
        .map(|t| {
            let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(corner(t, k).position));
            0.5 * (b - a).cross(c - a).length()
        })
        .collect();
    let total: f32 = areas.iter().sum();
    // Discs as wide as the mean spacing of `count` points over the surface.
    let width = (total / count as f32).sqrt();
    let mut random = Random(0x9e37_79b9_7f4a_7c15);
    let mut cloud = SplatCloud::default();
    let mut carried = 0.0;
    for (t, area) in areas.iter().enumerate() {
        carried += area / total * count as f32;
        let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(corner(t, k).position));
        let normal = (b - a).cross(c - a).normalize_or_zero();
        let rotation = Quat::from_rotation_arc(Vec3::Z, normal);
        while carried >= 1.0 {
            carried -= 1.0;
            let (mut u, mut v) = (random.next(), random.next());
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            cloud.means.push((a + u * (b - a) + v * (c - a)).to_array());
            cloud
                .log_scales
                .push([width.ln(), width.ln(), (0.05 * width).ln()]);
            cloud
                .rotations
                .push([rotation.w, rotation.x, rotation.y, rotation.z]);
            cloud.opacity_logits.push(3.0);
            let color = corner(t, 0).color;
            cloud
                .sh
                .push([0, 1, 2].map(|i| (color[i] as f32 / 255.0 - 0.5) / 0.282_094_8));
        }
    }
    cloud
}

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
    let cloud = capture_of(&room, count);
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
