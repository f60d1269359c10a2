//! Frames per second of the rasterizer on room0 at 1200×680 (Replica camera) and 640×480 (TUM),
//! GPU work and readback timed separately. Runs on whatever adapter wgpu picks (lavapipe here);
//! `RSLAM_ADAPTER=NAME` chooses another.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use rslam_core::Intrinsics;
use rslam_gpu::{AdapterChoice, FrameReadback, FrameTextures, GpuContext};
use rslam_render::{load_scene, Rasterizer};

fn render_benches(c: &mut Criterion) {
    let choice = AdapterChoice {
        name_contains: std::env::var("RSLAM_ADAPTER").ok(),
    };
    let ctx = GpuContext::new(&choice).expect("Vulkan adapter");
    eprintln!("adapter: {}", ctx.describe());
    let scene = load_scene("room0").expect("room0");
    let poses = scene.default_trajectory.clone().expect("trajectory").poses;
    for (label, k) in [
        ("replica_1200x680", Intrinsics::REPLICA),
        ("tum_640x480", Intrinsics::TUM),
    ] {
        let mut rasterizer = Rasterizer::new(&ctx, &scene, k).expect("rasterizer");
        let frame = FrameTextures::new(&ctx, k.width, k.height);
        let readback = FrameReadback::new(&ctx, k.width, k.height, true);
        let mut group = c.benchmark_group(format!("render_room0_{label}"));
        group.throughput(Throughput::Elements(1));
        group.sample_size(20);
        let mut i = 0;
        group.bench_function("render_only", |b| {
            b.iter(|| {
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                rasterizer
                    .encode(&ctx, &mut encoder, &frame, &poses[i % poses.len()])
                    .expect("render");
                ctx.queue.submit([encoder.finish()]);
                ctx.wait_idle().expect("gpu");
                i += 7;
            })
        });
        group.bench_function("render_and_readback", |b| {
            b.iter(|| {
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                rasterizer
                    .encode(&ctx, &mut encoder, &frame, &poses[i % poses.len()])
                    .expect("render");
                readback.encode_copy(&mut encoder, &frame);
                let submission = ctx.queue.submit([encoder.finish()]);
                readback.read(&ctx, submission).expect("readback");
                i += 7;
            })
        });
        group.finish();
    }
}

criterion_group!(benches, render_benches);
criterion_main!(benches);
