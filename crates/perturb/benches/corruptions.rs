//! Milliseconds per 1200×680 frame for every catalogue entry at severities 1, 3 and 5: the GPU
//! work (record, submit, wait) and, once, the readback of a frame (copy, map, unpad), timed
//! separately. Each timed frame starts from the same clean frame, restored outside the timing.
//! Then file in → file out for every image corruption at severity 3, sequentially per frame
//! (PNG read + decode, upload, GPU, readback, PNG encode (fast) + write), with the PNG read and
//! write alone for reference: the figure to set beside `imagecorruptions`. The input PNG is
//! $RSLAM_BENCH_PNG (a 1200×680 photo or rendered frame) or else a synthetic frame.
//!
//! cargo bench -p rslam-perturb --bench corruptions [-- FILTER]

use std::time::{Duration, Instant};

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use rslam_core::dataset::{encode_png, read_rgb};
use rslam_core::{DepthImage, Intrinsics, RgbImage};
use rslam_gpu::{AdapterChoice, FrameReadback, FrameTextures, GpuContext};
use rslam_perturb::{FrameKey, Group, Kit, Scratch, Severity, CATALOGUE};

const WIDTH: u32 = 1200;
const HEIGHT: u32 = 680;

/// A clean frame with photo-like structure: gradients, edges, texture; depth with steps.
fn clean_frame() -> (RgbImage, DepthImage) {
    let mut color = RgbImage::new(WIDTH, HEIGHT);
    let mut depth = DepthImage::new(WIDTH, HEIGHT);
    for y in 0..HEIGHT {
        for x in 0..WIDTH {
            let (u, v) = (x as f32 / WIDTH as f32, y as f32 / HEIGHT as f32);
            let i = (y * WIDTH + x) as usize;
            let checker = ((x / 24 + y / 24) % 2) as f32;
            let c = [
                0.2 + 0.6 * u,
                0.3 + 0.4 * v,
                0.5 + 0.3 * (9.0 * u + 5.0 * v).sin() * checker,
            ];
            for (k, value) in c.iter().enumerate() {
                color.data[i * 3 + k] = (value * 255.0) as u8;
            }
            let in_box = (0.3..0.6).contains(&u) && (0.2..0.7).contains(&v);
            depth.data[i] = if in_box { 1.5 } else { 2.0 + 2.5 * v };
        }
    }
    (color, depth)
}

fn corruptions(c: &mut Criterion) {
    let ctx = GpuContext::new(&AdapterChoice::default()).expect("a GPU adapter (lavapipe is fine)");
    eprintln!("adapter: {}", ctx.describe());
    let scratch = Scratch::new(&ctx, WIDTH, HEIGHT);
    let kit = Kit {
        ctx: &ctx,
        width: WIDTH,
        height: HEIGHT,
        scratch: &scratch,
        camera: Some(Intrinsics::REPLICA),
    };
    let (color, depth) = clean_frame();
    let pristine = FrameTextures::new(&ctx, WIDTH, HEIGHT);
    pristine.upload(&ctx, &color, Some(&depth));
    let frame = FrameTextures::new(&ctx, WIDTH, HEIGHT);
    let restore = || {
        let mut encoder = ctx.device.create_command_encoder(&Default::default());
        for (from, to) in [
            (&pristine.color, &frame.color),
            (&pristine.depth, &frame.depth),
        ] {
            encoder.copy_texture_to_texture(from.as_image_copy(), to.as_image_copy(), frame.size());
        }
        ctx.queue.submit([encoder.finish()]);
        ctx.wait_idle().expect("restore");
    };

    let mut group = c.benchmark_group("gpu_1200x680");
    group.throughput(Throughput::Elements((WIDTH * HEIGHT) as u64));
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    for entry in CATALOGUE {
        let mut perturbation = (entry.build)(&kit).expect("build");
        for severity in [1u8, 3, 5] {
            group.bench_function(format!("{}/{severity}", entry.name), |b| {
                b.iter_custom(|iterations| {
                    let mut total = Duration::ZERO;
                    for i in 0..iterations {
                        restore();
                        let key = FrameKey {
                            seed: 0,
                            frame: i as u32,
                            severity: Severity::whole(severity).expect("a severity"),
                            explicit: None,
                            camera: Some(Intrinsics::REPLICA),
                        };
                        let start = Instant::now();
                        let mut encoder = ctx.device.create_command_encoder(&Default::default());
                        perturbation
                            .encode(&kit, &mut encoder, &frame, &key)
                            .expect("encode");
                        ctx.queue.submit([encoder.finish()]);
                        ctx.wait_idle().expect("GPU work");
                        total += start.elapsed();
                    }
                    total
                });
            });
        }
    }
    group.finish();

    let readback = FrameReadback::new(&ctx, WIDTH, HEIGHT, true);
    let color_readback = FrameReadback::new(&ctx, WIDTH, HEIGHT, false);
    let mut group = c.benchmark_group("readback_1200x680");
    group.throughput(Throughput::Elements((WIDTH * HEIGHT) as u64));
    group.sample_size(10);
    for (name, readback) in [("color_and_depth", &readback), ("color", &color_readback)] {
        group.bench_function(name, |b| {
            b.iter(|| {
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                readback.encode_copy(&mut encoder, &frame);
                readback
                    .read(&ctx, ctx.queue.submit([encoder.finish()]))
                    .expect("readback")
            });
        });
    }
    group.finish();

    let dir = std::env::temp_dir().join("rslam-perturb-bench");
    std::fs::create_dir_all(&dir).expect("bench temp dir");
    let input = match std::env::var_os("RSLAM_BENCH_PNG") {
        Some(path) => std::path::PathBuf::from(path),
        None => {
            let path = dir.join("clean.png");
            std::fs::write(&path, encode_png(&color).expect("encode")).expect("write");
            path
        }
    };
    let output = dir.join("out.png");
    let mut group = c.benchmark_group("file_1200x680");
    group.throughput(Throughput::Elements(1));
    group.sample_size(10);
    group.warm_up_time(Duration::from_millis(500));
    group.measurement_time(Duration::from_secs(2));
    group.bench_function("png_read", |b| b.iter(|| read_rgb(&input).expect("read")));
    let decoded = read_rgb(&input).expect("read");
    assert_eq!(
        (decoded.width, decoded.height),
        (WIDTH, HEIGHT),
        "{} must be 1200x680",
        input.display()
    );
    group.bench_function("png_write_fast", |b| {
        b.iter(|| std::fs::write(&output, encode_png(&decoded).expect("encode")).expect("write"))
    });
    for entry in CATALOGUE.iter().filter(|e| e.group == Group::Image) {
        let mut perturbation = (entry.build)(&kit).expect("build");
        let mut index = 0;
        group.bench_function(format!("{}/3", entry.name), |b| {
            b.iter(|| {
                let image = read_rgb(&input).expect("read");
                frame.upload(&ctx, &image, None);
                let key = FrameKey {
                    seed: 0,
                    frame: index,
                    severity: Severity::whole(3).expect("a severity"),
                    explicit: None,
                    camera: Some(Intrinsics::REPLICA),
                };
                index += 1;
                let mut encoder = ctx.device.create_command_encoder(&Default::default());
                perturbation
                    .encode(&kit, &mut encoder, &frame, &key)
                    .expect("encode");
                color_readback.encode_copy(&mut encoder, &frame);
                let (out, _) = color_readback
                    .read(&ctx, ctx.queue.submit([encoder.finish()]))
                    .expect("readback");
                std::fs::write(&output, encode_png(&out).expect("encode")).expect("write");
            });
        });
    }
    group.finish();
}

criterion_group!(benches, corruptions);
criterion_main!(benches);
