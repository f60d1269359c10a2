//! Frames into and out of the GPU through buffers that are lent and come back. The ring lends
//! each read-back frame's staging buffers until its images are unpacked: frames held back while
//! later frames are recorded keep their own images, and a frame dropped without unpacking still
//! hands its buffers back (else the ring would wait for them forever). Upload buffers filled on
//! another thread go back for the next frames only once the frame that used them is submitted.

use std::collections::VecDeque;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

use rslam_core::{DepthImage, ImagePool, MaskImage, RgbImage};
use rslam_gpu::{AdapterChoice, FrameRing, FrameUploads, GpuContext, GpuError, ReadFrame};

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

/// Ids up to 70 000 (saturating at 65 535 when unpacked) in every pixel of frame `i`'s mask.
fn mask_ids(i: usize) -> Vec<u32> {
    (0..WIDTH * HEIGHT).map(|k| i as u32 * 5000 + k).collect()
}

/// Unpacks `frame` and checks it holds the images uploaded as its index (its mask too, where the
/// ring reads one); returns that index.
fn check(mut frame: ReadFrame, pool: &ImagePool) -> usize {
    if let Some(mask) = frame.images.mask.take() {
        let ids = mask_ids(frame.index).into_iter();
        let expected = MaskImage {
            width: WIDTH,
            height: HEIGHT,
            data: ids.map(|id| id.min(65_535) as u16).collect(),
        };
        assert_eq!(
            mask.unpack().expect("mask"),
            expected,
            "mask of {}",
            frame.index
        );
    }
    let (color, depth) = frame.images.unpack(pool).expect("unpack");
    let expected = images(frame.index);
    assert_eq!(color, expected.0, "colour of frame {}", frame.index);
    assert_eq!(depth, Some(expected.1), "depth of frame {}", frame.index);
    frame.index
}

/// Frames 0, 3, 6 … are dropped as read; the others are held until `HELD` more have come out.
/// The ring reads instance masks too.
fn run_ring() -> Result<Vec<usize>, GpuError> {
    let ctx = GpuContext::new(&AdapterChoice::default())?;
    let mut ring = FrameRing::new(&ctx, WIDTH, HEIGHT, IN_FLIGHT, (true, true));
    let pool = ImagePool::default();
    let (mut held, mut unpacked) = (VecDeque::new(), Vec::new());
    for i in 0..FRAMES {
        let read = ring.submit(&ctx, i, |_, frame| -> Result<(), GpuError> {
            let (color, depth) = images(i);
            frame.upload(&ctx, &color, Some(&depth));
            let mask = frame.mask.as_ref().expect("a ring with masks");
            ctx.queue.write_texture(
                mask.as_image_copy(),
                bytemuck::cast_slice(&mask_ids(i)),
                rslam_gpu::wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(WIDTH * 4),
                    rows_per_image: Some(HEIGHT),
                },
                frame.size(),
            );
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

/// Frames filled on another thread, one waiting, through the fewest upload buffers that can work:
/// the one the frame loop recorded last and the one it records. Between recording a frame and
/// submitting it the loop pauses, so that a filler given a buffer too early would write into it
/// before the frame's copy out of it.
fn run_uploads() -> Result<Vec<usize>, GpuError> {
    let ctx = GpuContext::new(&AdapterChoice::default())?;
    let mut uploads = FrameUploads::new(&ctx, WIDTH, HEIGHT, true, 2);
    let filler = uploads.filler();
    assert!(
        filler
            .fill(&RgbImage::new(WIDTH + 1, HEIGHT), None)
            .is_err(),
        "a frame of another size was written"
    );
    let (filled, next) = mpsc::sync_channel(1);
    let filling = std::thread::spawn(move || -> Result<(), GpuError> {
        for i in 0..FRAMES {
            let (color, depth) = images(i);
            if filled.send(filler.fill(&color, Some(&depth))?).is_err() {
                break;
            }
        }
        Ok(())
    });
    let mut ring = FrameRing::new(&ctx, WIDTH, HEIGHT, IN_FLIGHT, (true, false));
    let pool = ImagePool::default();
    let mut read = Vec::new();
    for i in 0..FRAMES {
        let Ok(upload) = next.recv() else { break };
        let frame = ring.submit(&ctx, i, |encoder, frame| -> Result<(), GpuError> {
            uploads.record(encoder, frame, upload);
            std::thread::sleep(Duration::from_millis(20));
            Ok(())
        })?;
        read.extend(frame.map(|f| check(f, &pool)));
    }
    read.extend(ring.drain(&ctx)?.into_iter().map(|f| check(f, &pool)));
    filling
        .join()
        .unwrap_or_else(|panic| std::panic::resume_unwind(panic))?;
    Ok(read)
}

/// `run`'s result, failing the test if it has not finished within 30 s (lent buffers that never
/// came back) and passing on its panics.
fn within_deadline<T: Send + 'static>(run: fn() -> Result<T, GpuError>) -> T {
    let (done, finished) = mpsc::channel();
    let thread = std::thread::spawn(move || {
        let result = run();
        let _ = done.send(());
        result
    });
    if let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(Duration::from_secs(30)) {
        panic!("stalled waiting for lent buffers that never came back");
    }
    thread
        .join()
        .unwrap_or_else(|panic| std::panic::resume_unwind(panic))
        .expect("frames on a GPU adapter (lavapipe is fine)")
}

#[test]
fn held_frames_keep_their_images_and_dropped_frames_free_their_buffers() {
    let unpacked = within_deadline(run_ring);
    let mut expected: Vec<usize> = (0..FRAMES - IN_FLIGHT).filter(|i| i % 3 != 0).collect();
    expected.extend(FRAMES - IN_FLIGHT..FRAMES);
    assert_eq!(unpacked, expected);
}

#[test]
fn frames_filled_on_another_thread_arrive_whole_through_two_buffers() {
    assert_eq!(
        within_deadline(run_uploads),
        (0..FRAMES).collect::<Vec<_>>()
    );
}
