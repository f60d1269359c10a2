//! Frames decoded on a background thread, a few at a time in parallel, ahead of the GPU, and
//! handed over in order.

use std::sync::mpsc::{sync_channel, Receiver};
use std::thread::JoinHandle;

use rayon::prelude::*;

use crate::PipelineError;

/// Frames decoded together, in parallel; as many more wait decoded.
pub const DECODE_AHEAD: usize = 4;

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

impl<T> Drop for DecodeAhead<T> {
    fn drop(&mut self) {
        // Closing the channel first lets a decoder blocked on a full channel finish.
        self.frames = None;
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}
