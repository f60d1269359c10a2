//! The ring lends each read-back frame's staging buffers until its images are unpacked: frames
//! held back while later frames are recorded keep their own images, and a frame dropped without
//! unpacking still hands its buffers back (else the ring would wait for them forever).

use std::collections::VecDeque;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use rslam_core::{DepthImage, ImagePool, RgbImage};
use rslam_gpu::{AdapterChoice, FrameRing, GpuContext, GpuError, ReadFrame};

const IN_FLIGHT: usize = 2;
/// Frames the test holds unpacked at once: as many as the ring lends beyond those in flight.
const HELD: usize = IN_FLIGHT;
const FRAMES: usize = 14;
// An odd width: rows are padded in the staging buffers.
const WIDTH: u32 = 5;
const HEIGHT: u32 = 3;

fn images(i: usize) -> (RgbImage, DepthImage) {
    let mut color = RgbImage::new(WIDTH, HEIGHT);
    for (k, v) in color.data.iter_mut().enumerate() {
        *v = (i * 17 + k) as u8;
    }
    let mut depth = DepthImage::new(WIDTH, HEIGHT);
    for (k, v) in depth.data.iter_mut().enumerate() {
        *v = i as f32 + k as f32 / 100.0;
    }
    (color, depth)
}

/// Unpacks `frame` and checks it holds the images uploaded as its index; returns that index.
fn check(frame: ReadFrame, pool: &ImagePool) -> usize {
    let (color, depth) = frame.images.unpack(pool).expect("unpack");
    let expected = images(frame.index);
    assert_eq!(color, expected.0, "colour of frame {}", frame.index);
    assert_eq!(depth, Some(expected.1), "depth of frame {}", frame.index);
    frame.index
}

/// Frames 0, 3, 6 … are dropped as read; the others are held until `HELD` more have come out.
fn run_ring() -> Result<Vec<usize>, GpuError> {
    let ctx = GpuContext::new(&AdapterChoice::default())?;
    let mut ring = FrameRing::new(&ctx, WIDTH, HEIGHT, IN_FLIGHT, true);
    let pool = ImagePool::default();
    let (mut held, mut unpacked) = (VecDeque::new(), Vec::new());
    for i in 0..FRAMES {
        let read = ring.submit(&ctx, i, |_, frame| -> Result<(), GpuError> {
            let (color, depth) = images(i);
            frame.upload(&ctx, &color, Some(&depth));
            Ok(())
        })?;
        if let Some(frame) = read.filter(|f| f.index % 3 != 0) {
            held.push_back(frame);
        }
        if held.len() > HELD {
            unpacked.extend(held.pop_front().map(|f| check(f, &pool)));
        }
    }
    unpacked.extend(held.into_iter().map(|f| check(f, &pool)));
    unpacked.extend(ring.drain(&ctx)?.into_iter().map(|f| check(f, &pool)));
    Ok(unpacked)
}

#[test]
fn held_frames_keep_their_images_and_dropped_frames_free_their_buffers() {
    let (done, finished) = mpsc::channel();
    let ring = std::thread::spawn(move || {
        let result = run_ring();
        let _ = done.send(());
        result
    });
    if let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(Duration::from_secs(30)) {
        panic!("the ring stalled waiting for staging buffers that never came back");
    }
    let unpacked = ring
        .join()
        .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
        .expect("the ring's frames on a GPU adapter (lavapipe is fine)");
    let mut expected: Vec<usize> = (0..FRAMES - IN_FLIGHT).filter(|i| i % 3 != 0).collect();
    expected.extend(FRAMES - IN_FLIGHT..FRAMES);
    assert_eq!(unpacked, expected);
}
