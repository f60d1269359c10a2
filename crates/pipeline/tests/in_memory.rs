//! The in-memory API against the files a run writes: the same frames, whether asked for as a
//! range, one at a time, or written as a dataset; buffers go through the GPU unchanged when
//! nothing perturbs them.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use rslam_core::dataset::{decode_depth_png, decode_mask_png, read_rgb, DatasetFormat, DepthPng};
use rslam_core::Intrinsics;
use rslam_gpu::{AdapterChoice, GpuContext};
use rslam_perturb::PerturbSpec;
use rslam_pipeline::source::BufferSource;
use rslam_pipeline::{
    run, FramesInMemory, Job, RgbdFrame, SceneJob, Sensors, Silent, Source, Streams,
};

const CAMERA: Intrinsics = Intrinsics {
    width: 72,
    height: 40,
    fx: 40.0,
    fy: 40.0,
    cx: 35.5,
    cy: 19.5,
};
/// TUM depth PNGs store round(z · 5000).
const DEPTH_STEP_M: f32 = 0.5 / 5000.0 + 1e-6;

fn context() -> &'static GpuContext {
    static CONTEXT: OnceLock<GpuContext> = OnceLock::new();
    CONTEXT.get_or_init(|| {
        GpuContext::new(&AdapterChoice::default())
            .unwrap_or_else(|e| panic!("these tests need an adapter (lavapipe is fine): {e}"))
    })
}

fn scene_job(spec: &str) -> SceneJob {
    SceneJob {
        scene: "room0".into(),
        trajectory: None,
        frames: Some(8),
        camera: CAMERA,
        rate_hz: 20.0,
        spec: match spec {
            "" => PerturbSpec::default(),
            text => PerturbSpec::parse(text).unwrap(),
        },
        seed: 3,
        agent: None,
        capture: Default::default(),
        actor_files: Vec::new(),
    }
}

fn collect(
    frames: &mut FramesInMemory<impl rslam_pipeline::source::FrameSource>,
    range: std::ops::Range<usize>,
) -> Vec<RgbdFrame> {
    let mut got = Vec::new();
    frames
        .frames(context(), range, |frame| {
            got.push(frame);
            Ok(())
        })
        .unwrap();
    got
}

/// The frames as buffers handed over in memory.
fn buffers_of(frames: &[RgbdFrame]) -> BufferSource {
    BufferSource::new(
        frames
            .iter()
            .map(|f| (f.color.clone(), f.depth.clone()))
            .collect(),
    )
    .unwrap()
}

/// `job` rendered as a TUM dataset into a new folder: the folder, the dataset in it, its frames.
fn render_tum(job: SceneJob) -> (tempfile::TempDir, PathBuf, usize) {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ds");
    let report = run(
        context(),
        &Job {
            source: Source::Scene {
                scene: job,
                sensors: Sensors::Camera {
                    format: DatasetFormat::Tum,
                    depth_png: DepthPng::Fast,
                    bag: Default::default(),
                },
            },
            out: out.clone(),
            force: false,
            command: vec!["test".into()],
        },
        &Silent,
    )
    .unwrap();
    let Streams::Frames(frames) = report.streams else {
        panic!("one camera's frames: {:?}", report.streams)
    };
    (dir, out, frames)
}

/// The TUM dataset at `out` holds `frame`: its colour exactly, its depth to the PNG's step.
fn assert_written(out: &Path, frame: &RgbdFrame) {
    let png = out.join(format!("rgb/{:.6}.png", frame.rgb_time));
    assert_eq!(
        read_rgb(&png).unwrap(),
        frame.color,
        "frame {}",
        frame.index
    );
    let depth_png = out.join(format!("depth/{:.6}.png", frame.depth_time));
    let written = decode_depth_png(&depth_png, 5000.0).unwrap();
    let depth = frame.depth.as_ref().expect("scenes have depth");
    let off = written
        .data
        .iter()
        .zip(&depth.data)
        .filter(|(a, b)| (*a - b.min(65535.0 / 5000.0)).abs() > DEPTH_STEP_M)
        .count();
    assert_eq!(
        off, 0,
        "frame {}: depth pixels off by more than a step",
        frame.index
    );
}

#[test]
fn scene_frames_in_memory_are_the_frames_a_render_writes() {
    let ctx = context();
    let job = scene_job("gaussian_noise:2@dynamic,depth_noise:3,fast:2,misalign:1");
    let mut frames = FramesInMemory::scene(ctx, &job).unwrap();
    assert_eq!(frames.plan().len(), 4, "fast:2 keeps 4 of 8");
    let all = collect(&mut frames, 0..4);
    assert_eq!(
        all.iter().map(|f| f.index).collect::<Vec<_>>(),
        vec![0, 1, 2, 3]
    );
    let alone = frames.frame(ctx, 2).unwrap();
    assert_eq!(
        alone, all[2],
        "a frame does not depend on which others were made"
    );

    let (_dir, out, written) = render_tum(job);
    assert_eq!(written, 4);
    for frame in &all {
        assert_written(&out, frame);
    }
    // misalign:1 on the fast stream: output 2 carries the depth captured with output 1, and
    // output 1 that of output 0, which output 0 (clamped at the start) carries too.
    assert_eq!(all[2].depth_time, all[1].rgb_time);
    assert_eq!(all[1].depth, all[0].depth);
    assert_ne!(all[2].depth, all[1].depth);
}

/// Walkers through a lens under a rolling shutter, in memory as a render writes them (instance
/// masks too), whether the frames were made with them or the same sensor without walkers took
/// them in place (its lens and shutter then carry masks too).
#[test]
fn walkers_in_memory_and_their_masks_are_what_a_render_writes() {
    let ctx = context();
    let sensor = "rolling_shutter:30,distortion:radtan(-0.2,0.05,0,0)";
    let job = SceneJob {
        scene: "office2".into(),
        frames: Some(60),
        ..scene_job(&format!("actors:5,{sensor}"))
    };
    let made_with = collect(&mut FramesInMemory::scene(ctx, &job).unwrap(), 0..60);
    let mut taken_in_place = FramesInMemory::scene(
        ctx,
        &SceneJob {
            spec: PerturbSpec::parse(sensor).unwrap(),
            ..job.clone()
        },
    )
    .unwrap();
    assert!(collect(&mut taken_in_place, 0..2)[0].mask.is_none());
    taken_in_place.set_spec(ctx, &job.spec, job.seed).unwrap();
    assert_eq!(collect(&mut taken_in_place, 0..60), made_with);
    let (_dir, out, written) = render_tum(job);
    assert_eq!(written, 60);
    let mut seen = 0;
    for frame in &made_with {
        assert_written(&out, frame);
        let png = out.join(format!("mask/{:.6}.png", frame.rgb_time));
        let mask = frame
            .mask
            .as_ref()
            .expect("frames with walkers carry masks");
        assert_eq!(
            &decode_mask_png(&png).unwrap(),
            mask,
            "frame {}",
            frame.index
        );
        seen += usize::from(mask.dynamic_fraction() > 0.0);
    }
    assert!(seen >= 5, "walkers in {seen} frames");
}

#[test]
fn buffers_pass_through_unchanged_and_are_perturbed_per_frame() {
    let ctx = context();
    let mut scene = FramesInMemory::scene(ctx, &scene_job("")).unwrap();
    let rendered = collect(&mut scene, 0..3);
    let buffers = || buffers_of(&rendered);
    let mut clean = FramesInMemory::buffers(ctx, buffers(), &PerturbSpec::default(), 0).unwrap();
    for (back, original) in collect(&mut clean, 0..3).iter().zip(&rendered) {
        assert_eq!(back.color, original.color);
        assert_eq!(back.depth, original.depth);
    }
    let spec = PerturbSpec::parse("gaussian_noise:3,depth_missing:4").unwrap();
    let mut noisy = FramesInMemory::buffers(ctx, buffers(), &spec, 0).unwrap();
    let once = collect(&mut noisy, 0..3);
    let again = collect(&mut noisy, 0..3);
    assert_eq!(once, again, "same seed, same bytes");
    assert_ne!(once[0].color, rendered[0].color);
    assert_ne!(once[1].depth, rendered[1].depth);

    let mut odd = rendered[0].color.clone();
    odd.width -= 1;
    odd.data
        .truncate(odd.width as usize * odd.height as usize * 3);
    let error = BufferSource::new(vec![(rendered[0].color.clone(), None), (odd, None)]).err();
    assert!(error.unwrap().to_string().contains("frame 1"));
    let no_depth = BufferSource::new(vec![(rendered[0].color.clone(), None)]).unwrap();
    let refused = FramesInMemory::buffers(ctx, no_depth, &spec, 0)
        .err()
        .unwrap();
    assert!(refused.to_string().contains("depth"), "{refused}");
    // Buffers may come in any order; a stateful item needs them in capture order.
    let one = || BufferSource::new(vec![(rendered[0].color.clone(), None)]).unwrap();
    let stateful = PerturbSpec::parse("fog:1,auto_exposure:2").unwrap();
    let refused = FramesInMemory::buffers(ctx, one(), &stateful, 0)
        .err()
        .unwrap();
    assert!(
        refused
            .to_string()
            .contains("auto_exposure carries its state from frame to frame"),
        "{refused}"
    );
    let mut fog =
        FramesInMemory::buffers(ctx, one(), &PerturbSpec::parse("fog:1").unwrap(), 0).unwrap();
    assert!(fog.set_spec(ctx, &stateful, 0).is_err());
}

#[test]
fn buffers_with_their_camera_take_depth_sensor_as_the_render_does() {
    let ctx = context();
    let job = scene_job("depth_sensor:kinect");
    let mut scene = FramesInMemory::scene(ctx, &job).unwrap();
    let sensed = collect(&mut scene, 0..2);
    let mut clean = FramesInMemory::scene(ctx, &scene_job("")).unwrap();
    let rendered = collect(&mut clean, 0..2);
    let buffers = || buffers_of(&rendered);
    let spec = &job.spec;
    let mut in_memory = FramesInMemory::buffers(
        ctx,
        buffers().with_camera(job.camera).unwrap(),
        spec,
        job.seed,
    )
    .unwrap();
    let back = collect(&mut in_memory, 0..2);
    for (i, (b, s)) in back.iter().zip(&sensed).enumerate() {
        assert!(b.color == s.color, "colour of frame {i}");
        let (b, s) = (b.depth.as_ref().unwrap(), s.depth.as_ref().unwrap());
        let differ = b.data.iter().zip(&s.data).filter(|(x, y)| x != y).count();
        assert_eq!(differ, 0, "frame {i}: {differ} depths differ");
    }

    let refused = FramesInMemory::buffers(ctx, buffers(), spec, job.seed)
        .err()
        .unwrap();
    assert!(
        refused.to_string().contains("without a camera"),
        "{refused}"
    );
    let mut other = job.camera;
    other.width += 2;
    let wrong = buffers().with_camera(other).err().unwrap().to_string();
    assert!(wrong.contains("expected the frames' size"), "{wrong}");
}

/// A dataset run reads frames back into the image buffers its encoders hand back once written;
/// in memory every frame gets fresh ones. Enough frames that each buffer goes round several times
/// whatever the number of encoder threads (at most two frames per thread and the ring's three
/// are out at once).
#[test]
fn a_long_render_through_reused_image_buffers_writes_the_frames_made_one_at_a_time() {
    let ctx = context();
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get());
    let count = 4 * (2 * threads + 4);
    let job = SceneJob {
        frames: Some(count),
        ..scene_job("gaussian_noise:2@dynamic,depth_noise:3")
    };
    let mut frames = FramesInMemory::scene(ctx, &job).unwrap();
    let all = collect(&mut frames, 0..count);
    let (_dir, out, _) = render_tum(job);
    for frame in &all {
        assert_written(&out, frame);
    }
}
