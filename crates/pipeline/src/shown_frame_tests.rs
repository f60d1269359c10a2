//! The shown frame against the frames a run reads back: the same pixels, with no readback on the
//! way; a new spec re-perturbs the held source frames like a new run would; the depth colours
//! are the CPU twin's.

use std::sync::OnceLock;

use rslam_core::{DepthImage, Intrinsics, RgbImage};
use rslam_gpu::{read_texels, AdapterChoice, FrameReadback, FrameTextures, GpuContext};
use rslam_perturb::PerturbSpec;

use super::*;
use crate::depth_colormap::depth_color;
use crate::{FramesInMemory, SceneJob};

const CAMERA: Intrinsics = Intrinsics {
    width: 48,
    height: 32,
    fx: 26.0,
    fy: 26.0,
    cx: 23.5,
    cy: 15.5,
};

/// A channel may differ by one step where the depth colours are rounded (f32 on both sides, but
/// not bit-identical polynomial evaluation).
const COLOR_TOLERANCE: i32 = 1;

fn context() -> &'static GpuContext {
    static CONTEXT: OnceLock<GpuContext> = OnceLock::new();
    CONTEXT.get_or_init(|| {
        GpuContext::new(&AdapterChoice::default())
            .unwrap_or_else(|e| panic!("these tests need an adapter (lavapipe is fine): {e}"))
    })
}

fn job(spec: &str) -> SceneJob {
    SceneJob {
        scene: "room0".into(),
        trajectory: None,
        frames: Some(6),
        camera: CAMERA,
        rate_hz: 20.0,
        spec: match spec {
            "" => PerturbSpec::default(),
            text => PerturbSpec::parse(text).unwrap(),
        },
        seed: 5,
        agent: None,
    }
}

fn read(ctx: &GpuContext, frame: &FrameTextures) -> (RgbImage, DepthImage) {
    let readback = FrameReadback::new(ctx, frame.width, frame.height, true);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    readback.encode_copy(&mut encoder, frame);
    let (color, depth) = readback
        .read(ctx, ctx.queue.submit([encoder.finish()]))
        .unwrap();
    (color, depth.unwrap())
}

/// The perturbed colour and depth `shown` holds, read back for the test.
fn shown_pixels(ctx: &GpuContext, shown: &ShownFrame) -> (RgbImage, DepthImage) {
    let sources = shown.sources().unwrap();
    let (color, _) = read(ctx, &shown.perturbed);
    let (_, depth) = read(ctx, shown.depth_frames(sources).1);
    (color, depth)
}

#[test]
fn a_shown_frame_holds_what_the_frame_loop_reads_back() {
    let ctx = context();
    let spec = "gaussian_noise:2@dynamic,depth_noise:3,misalign:1";
    let mut frames = FramesInMemory::scene(ctx, &job(spec)).unwrap();
    let mut shown = ShownFrame::new(ctx, CAMERA.width, CAMERA.height).unwrap();
    let len = frames.plan().len();
    for index in [0, len - 1, 2] {
        frames
            .show(ctx, index, &mut shown, DepthRange::default())
            .unwrap();
        let expected = frames.frame(ctx, index).unwrap();
        let (color, depth) = shown_pixels(ctx, &shown);
        assert_eq!(color, expected.color, "colour of output frame {index}");
        assert_eq!(Some(depth), expected.depth, "depth of output frame {index}");
    }
    let sources = shown.sources().unwrap();
    assert_ne!(
        sources.rgb, sources.depth,
        "misalign:1 shows another depth frame"
    );
}

#[test]
fn a_new_spec_re_perturbs_the_held_frame_like_a_new_run() {
    let ctx = context();
    let mut frames = FramesInMemory::scene(ctx, &job("fog:1,depth_missing:2")).unwrap();
    let mut shown = ShownFrame::new(ctx, CAMERA.width, CAMERA.height).unwrap();
    frames
        .show(ctx, 3, &mut shown, DepthRange::default())
        .unwrap();
    let before = shown_pixels(ctx, &shown);
    for (spec, seed) in [("fog:4,depth_missing:2", 5), ("fog:4,depth_missing:5", 9)] {
        let spec = PerturbSpec::parse(spec).unwrap();
        frames.set_spec(ctx, &spec, seed).unwrap();
        frames
            .show(ctx, 3, &mut shown, DepthRange::default())
            .unwrap();
        let fresh_job = SceneJob {
            spec: spec.clone(),
            seed,
            agent: None,
            ..job("")
        };
        let expected = FramesInMemory::scene(ctx, &fresh_job)
            .unwrap()
            .frame(ctx, 3)
            .unwrap();
        let (color, depth) = shown_pixels(ctx, &shown);
        assert_eq!(color, expected.color, "{spec}");
        assert_eq!(Some(depth), expected.depth, "{spec}");
        assert_ne!(color, before.0, "{spec} changed the colour");
    }
}

#[test]
fn depth_colours_are_the_cpu_twins() {
    let ctx = context();
    let mut frames = FramesInMemory::scene(ctx, &job("depth_missing:5")).unwrap();
    let mut shown = ShownFrame::new(ctx, CAMERA.width, CAMERA.height).unwrap();
    let range = DepthRange {
        near: 0.5,
        far: 4.0,
    };
    frames.show(ctx, 1, &mut shown, range).unwrap();
    let (_, depth) = shown_pixels(ctx, &shown);
    let pixels: Vec<(u32, u32)> = (0..CAMERA.height)
        .step_by(3)
        .flat_map(|y| (0..CAMERA.width).step_by(5).map(move |x| (x, y)))
        .collect();
    let texels: Vec<_> = pixels
        .iter()
        .map(|&(x, y)| (&shown.perturbed_depth_colors, x, y))
        .collect();
    let got = read_texels(ctx, &texels).unwrap();
    let mut holes = 0;
    for (&(x, y), texel) in pixels.iter().zip(&got) {
        let z = depth.data[(y * CAMERA.width + x) as usize];
        holes += (z == 0.0) as usize;
        let want = depth_color(z, range);
        for c in 0..3 {
            let diff = (texel[c] as i32 - want[c] as i32).abs();
            assert!(
                diff <= COLOR_TOLERANCE,
                "pixel ({x}, {y}) z = {z}: GPU {texel:?}, twin {want:?}"
            );
        }
    }
    assert!(holes > 0, "depth_missing:5 leaves holes, which show black");
    let readout = shown.read_pixel(ctx, 7, 9).unwrap().unwrap();
    assert_eq!(
        readout.perturbed_depth,
        depth.data[(9 * CAMERA.width + 7) as usize]
    );
}
