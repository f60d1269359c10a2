//! What a suite will cost before it runs: frames, bytes and time per sequence and in all. Bytes
//! per frame and frames per second come from this suite's own finished sequences and timed runs
//! when there are any, else from figures measured on the development machine (said so).

use std::collections::HashMap;
use std::path::Path;

use rslam_core::dataset::{read_frames_deleted, DatasetFormat, DepthPng, Layout};
use rslam_pipeline::Sensors;
use serde::Serialize;

use crate::disk::folder_bytes;
use crate::sequence::{FrameCounts, Sequence};
use crate::state::SequenceState;
use crate::timings::Timings;
use crate::SuiteError;

/// Whole `rslam render` of room0 at 1200×680 on the development machine (2 cores, lavapipe).
const MEASURED_FRAMES_PER_SECOND: f64 = 20.0;
const MEASURED_PIXELS: f64 = 1200.0 * 680.0;

#[derive(Clone, Debug, Serialize)]
pub struct SequencePlan {
    pub name: String,
    pub frames_rendered: usize,
    pub frames_written: usize,
    /// On disk now (complete or partial), or estimated when missing.
    pub bytes: u64,
    pub bytes_measured: bool,
    /// Bytes still to write (0 when complete, or used and its frames deleted).
    pub bytes_to_write: u64,
    pub frames_to_render: usize,
    /// What stays once its frames are deleted (manifest, checksums, ground truth): measured when
    /// they were, else estimated.
    pub kept_bytes: u64,
}

#[derive(Clone, Debug, Serialize)]
pub struct SuitePlan {
    pub sequences: Vec<SequencePlan>,
    pub bytes_total: u64,
    pub bytes_to_write: u64,
    pub frames_to_render: usize,
    pub frames_per_second: f64,
    /// Where `frames_per_second` comes from.
    pub rate_source: String,
    pub seconds_to_go: f64,
}

/// Plans `sequences` (with their states) of the suite in `suite_dir`.
pub fn plan(
    suite_dir: &Path,
    sequences: &[(&Sequence, SequenceState)],
) -> Result<SuitePlan, SuiteError> {
    let mut measured: HashMap<(Layout, u32, u32), (u64, usize)> = HashMap::new();
    let mut counted = Vec::with_capacity(sequences.len());
    for (sequence, state) in sequences {
        let frames = sequence.frame_counts(suite_dir)?;
        let on_disk = match state {
            SequenceState::Missing => 0,
            _ => folder_bytes(&sequence.dir(suite_dir))?,
        };
        let whole = match state {
            SequenceState::Complete => Some(on_disk),
            SequenceState::FramesDeleted => read_frames_deleted(&sequence.dir(suite_dir))?
                .map(|deleted| on_disk + deleted.bytes),
            _ => None,
        };
        if let Some(whole) = whole {
            let entry = measured.entry(size_key(sequence)).or_default();
            entry.0 += whole;
            entry.1 += frames.written;
        }
        counted.push((sequence, state, frames, on_disk));
    }
    let mut plans = Vec::with_capacity(counted.len());
    for (sequence, state, frames, on_disk) in counted {
        plans.push(sequence_plan(sequence, state, frames, on_disk, &measured));
    }
    let timings = Timings::read(suite_dir)?;
    let (frames_per_second, rate_source) = match timings.frames_per_second() {
        Some(rate) => (
            rate,
            format!(
                "measured over {} sequence run(s) of this suite",
                timings.len()
            ),
        ),
        None => {
            let pixels = sequences.first().map_or(MEASURED_PIXELS, |(s, _)| {
                s.camera.width as f64 * s.camera.height as f64
            });
            (
                MEASURED_FRAMES_PER_SECOND * MEASURED_PIXELS / pixels,
                "no run timed yet: assumed from 20 frames/s at 1200x680 on a 2-core CPU (lavapipe); a GPU is faster".into(),
            )
        }
    };
    let frames_to_render = plans.iter().map(|p| p.frames_to_render).sum();
    Ok(SuitePlan {
        bytes_total: plans.iter().map(|p| p.bytes).sum(),
        bytes_to_write: plans.iter().map(|p| p.bytes_to_write).sum(),
        frames_to_render,
        frames_per_second,
        rate_source,
        seconds_to_go: frames_to_render as f64 / frames_per_second,
        sequences: plans,
    })
}

fn sequence_plan(
    sequence: &Sequence,
    state: &SequenceState,
    frames: FrameCounts,
    on_disk: u64,
    measured: &HashMap<(Layout, u32, u32), (u64, usize)>,
) -> SequencePlan {
    let (per_frame, bytes_measured) = match measured.get(&size_key(sequence)) {
        Some(&(bytes, written)) if written > 0 => (bytes as f64 / written as f64, true),
        _ => (estimated_bytes_per_frame(sequence), false),
    };
    let estimate = (per_frame * frames.written as f64).round() as u64;
    let kept_estimate = kept_bytes_per_frame(sequence) * frames.written as u64;
    let plan = |bytes, bytes_to_write, frames_to_render, kept_bytes| SequencePlan {
        name: sequence.name.clone(),
        frames_rendered: frames.rendered,
        frames_written: frames.written,
        bytes,
        bytes_measured: bytes_measured || state.is_finished(),
        bytes_to_write,
        frames_to_render,
        kept_bytes,
    };
    match state {
        SequenceState::Complete => plan(on_disk, 0, 0, kept_estimate),
        // Left alone by `suite run`; its whole size counted once.
        SequenceState::FramesDeleted => plan(estimate.max(on_disk), 0, 0, on_disk),
        _ => {
            let done_fraction = (on_disk as f64 / estimate.max(1) as f64).min(1.0);
            plan(
                estimate.max(on_disk),
                estimate.saturating_sub(on_disk),
                ((1.0 - done_fraction) * frames.rendered as f64).ceil() as usize,
                kept_estimate,
            )
        }
    }
}

/// Bytes a written frame leaves in the files kept when the frames are deleted (ground truth,
/// timestamps, the manifest's per-frame lists), measured on 100-frame renders of room0: 565 B
/// (Replica), 451 B (TUM); with an IMU (`rgbd-imu`, EuRoC rigs) its samples and the rig's
/// records, 5.1–5.3 kB.
fn kept_bytes_per_frame(sequence: &Sequence) -> u64 {
    match sequence.sensors {
        Sensors::Camera { .. } => 600,
        Sensors::CameraImu { .. } | Sensors::Rig(..) => 5400,
    }
}

fn size_key(sequence: &Sequence) -> (Layout, u32, u32) {
    (
        sequence.layout(),
        sequence.camera.width,
        sequence.camera.height,
    )
}

fn estimated_bytes_per_frame(sequence: &Sequence) -> f64 {
    let noisy = sequence
        .spec
        .image
        .iter()
        .any(|item| item.name.ends_with("_noise"));
    let (clean, noise) = match &sequence.sensors {
        Sensors::Camera {
            format, depth_png, ..
        }
        | Sensors::CameraImu {
            format, depth_png, ..
        } => measured_bytes_per_pixel(*format, *depth_png),
        Sensors::Rig(..) => EUROC_GREY_BYTES_PER_PIXEL,
    };
    let pixels = sequence.camera.width as f64 * sequence.camera.height as f64;
    pixels * if noisy { noise } else { clean }
}

/// Bytes per pixel of a rig camera's written frame (8-bit grey PNG) of built-in room0 with the
/// `stereo-imu` rig (752x480), clean (54.6 MB for 398 frames) and under gaussian_noise:5, which
/// PNG cannot compress.
const EUROC_GREY_BYTES_PER_PIXEL: (f64, f64) = (0.38, 1.00);

/// Bytes per pixel of a written frame (colour and depth) of built-in room0, release build, clean
/// and under gaussian_noise:5 (the worst case, taken for every noise corruption): Replica layout
/// (JPEG + 16-bit PNG) 1.10 and 2.66 MB per 1200x680 frame; TUM layout (PNG + PNG) 737 kB and
/// 1.18 MB per 640x480 frame. Small depth PNGs: 2000 clean frames take 1.31 GB (Replica) and
/// 1.10 GB (TUM); noisy colour does not shrink, so the noise figure stays. A bag stores raw
/// `rgb8` and `16UC1` images, 5 bytes a pixel whatever they show.
fn measured_bytes_per_pixel(format: DatasetFormat, depth_png: DepthPng) -> (f64, f64) {
    match (format, depth_png) {
        (DatasetFormat::Replica, DepthPng::Fast) => (1.35, 3.26),
        (DatasetFormat::Replica, DepthPng::Small) => (0.80, 3.26),
        (DatasetFormat::Tum, DepthPng::Fast) => (2.40, 3.84),
        (DatasetFormat::Tum, DepthPng::Small) => (1.79, 3.84),
        (DatasetFormat::Ros2, _) => (5.0, 5.0),
    }
}
