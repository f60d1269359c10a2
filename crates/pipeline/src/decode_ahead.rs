//! Frames decoded on a background thread, a few at a time in parallel, ahead of the GPU, and
//! handed over in order; decoded images go straight into upload buffers there.

use std::sync::mpsc::{sync_channel, Receiver};
use std::thread::JoinHandle;

use rayon::prelude::*;
use rslam_gpu::{FrameUploads, GpuContext};

use crate::PipelineError;

/// Frames decoded together, in parallel.
const DECODE_AHEAD: usize = 4;

/// Upload buffers for frames of `width × height` that a [`DecodeAhead`] fills. While a frame is
/// being filled, at most `DECODE_AHEAD` frames wait in the channel, `DECODE_AHEAD - 1` more of
/// its chunk are filled, and the frame loop holds two (the one it records, the one before): one
/// more than that keeps a buffer free for it.
pub fn frame_uploads(ctx: &GpuContext, width: u32, height: u32, with_depth: bool) -> FrameUploads {
    FrameUploads::new(ctx, width, height, with_depth, 2 * DECODE_AHEAD + 2)
}

pub struct DecodeAhead<T> {
    frames: Option<Receiver<Result<T, PipelineError>>>,
    thread: Option<JoinHandle<()>>,
}

impl<T: Send + 'static> DecodeAhead<T> {
    /// Starts decoding `items` in order with `decode`; it stops after the first error.
    pub fn start<I: Send + Sync + 'static>(
        items: Vec<I>,
        decode: impl Fn(&I) -> Result<T, PipelineError> + Send + Sync + 'static,
    ) -> Self {
        let (tx, rx) = sync_channel(DECODE_AHEAD);
        let thread = std::thread::spawn(move || {
            for chunk in items.chunks(DECODE_AHEAD) {
                let decoded: Vec<_> = chunk.par_iter().map(&decode).collect();
                for frame in decoded {
                    let failed = frame.is_err();
                    if tx.send(frame).is_err() || failed {
                        return;
                    }
                }
            }
        });
        Self {
            frames: Some(rx),
            thread: Some(thread),
        }
    }

    /// The next decoded frame, or the error that stopped decoding.
    pub fn next(&self) -> Result<T, PipelineError> {
        let stopped = || PipelineError::Worker("the frame decoder stopped".into());
        self.frames
            .as_ref()
            .ok_or_else(stopped)?
            .recv()
            .map_err(|_| stopped())?
    }
}

/// The next frame `decoder` (`None` before the source was prepared) hands over, which must be
/// source frame `index`: frames are recorded in the order they were given to
/// [`DecodeAhead::start`], each decoded with its source index.
pub fn next_frame<T: Send + 'static>(
    decoder: Option<&DecodeAhead<(usize, T)>>,
    index: usize,
) -> Result<T, PipelineError> {
    let decoder =
        decoder.ok_or_else(|| PipelineError::Worker("frames recorded before prepare".into()))?;
    let (decoded, frame) = decoder.next()?;
    if decoded != index {
        return Err(PipelineError::Worker(format!(
            "decoder delivered frame {decoded} where frame {index} was expected"
        )));
    }
    Ok(frame)
}

impl<T> Drop for DecodeAhead<T> {
    fn drop(&mut self) {
        // Closing the channel first lets a decoder blocked on a full channel finish.
        self.frames = None;
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
