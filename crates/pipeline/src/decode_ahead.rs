//! Frames decoded on a background thread, a few at a time in parallel, ahead of the GPU, and
//! handed over in order.

use std::sync::mpsc::{sync_channel, Receiver};
use std::thread::JoinHandle;

use rayon::prelude::*;

use crate::PipelineError;

/// How many frames to decode together, in parallel: one per core, at least 4 and at most 16.
/// With 4 on a 16-core machine, decoding PNGs held `rslam perturb` to about 7 busy cores; 16
/// bounds the upload buffers a run makes (`UploadAhead`).
pub fn frames_per_core() -> usize {
    std::thread::available_parallelism().map_or(4, |n| n.get().clamp(4, 16))
}

pub struct DecodeAhead<T> {
    frames: Option<Receiver<Result<T, PipelineError>>>,
    thread: Option<JoinHandle<()>>,
}

impl<T: Send + 'static> DecodeAhead<T> {
    /// Starts decoding `items` in order with `decode`, `ahead` at a time in parallel while as
    /// many more wait decoded; it stops after the first error.
    pub fn start<I: Send + Sync + 'static>(
        items: Vec<I>,
        ahead: usize,
        decode: impl Fn(&I) -> Result<T, PipelineError> + Send + Sync + 'static,
    ) -> Self {
        let (tx, rx) = sync_channel(ahead);
        let thread = std::thread::spawn(move || {
            for chunk in items.chunks(ahead) {
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

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use super::DecodeAhead;
    use crate::PipelineError;

    #[test]
    fn frames_come_in_order_however_long_each_takes() {
        // Later frames of a chunk finish first: item i sleeps (7 - i % 7) ms.
        let decoder = DecodeAhead::start((0..37u64).collect(), 5, |&i| {
            std::thread::sleep(Duration::from_millis(7 - i % 7));
            Ok(i * 10)
        });
        let got: Vec<u64> = (0..37).map(|_| decoder.next().unwrap()).collect();
        assert_eq!(got, (0..37).map(|i| i * 10).collect::<Vec<_>>());
        assert!(decoder.next().is_err(), "nothing after the last frame");
    }

    #[test]
    fn decoding_stops_at_the_first_error() {
        let decoder = DecodeAhead::start((0..20u32).collect(), 4, |&i| {
            if i == 6 {
                Err(PipelineError::Worker(format!("frame {i} is broken")))
            } else {
                Ok(i)
            }
        });
        for i in 0..6 {
            assert_eq!(decoder.next().unwrap(), i);
        }
        let error = decoder.next().unwrap_err().to_string();
        assert!(error.contains("frame 6 is broken"), "{error}");
        let after = decoder.next().unwrap_err().to_string();
        assert!(after.contains("decoder stopped"), "{after}");
    }
}
