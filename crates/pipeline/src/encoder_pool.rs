//! Encoding and writing on worker threads while the GPU renders the next frames. The queue is
//! bounded, so a slow disk holds the GPU back instead of filling memory.

use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use crate::PipelineError;

type Job = Box<dyn FnOnce() -> Result<(), PipelineError> + Send>;

pub struct EncoderPool {
    sender: Option<SyncSender<Job>>,
    workers: Vec<JoinHandle<()>>,
    first_error: Arc<Mutex<Option<PipelineError>>>,
}

impl EncoderPool {
    /// One worker per core, with a queue of two jobs per worker.
    pub fn per_core() -> Self {
        let threads = std::thread::available_parallelism().map_or(2, |n| n.get());
        Self::new(threads, 2 * threads)
    }

    pub fn new(threads: usize, queue: usize) -> Self {
        let (sender, receiver) = sync_channel::<Job>(queue);
        let receiver = Arc::new(Mutex::new(receiver));
        let first_error = Arc::new(Mutex::new(None));
        let workers = (0..threads.max(1))
            .map(|_| {
                let receiver: Arc<Mutex<Receiver<Job>>> = receiver.clone();
                let first_error = first_error.clone();
                std::thread::spawn(move || loop {
                    let job = {
                        let guard = receiver.lock().unwrap_or_else(|p| p.into_inner());
                        guard.recv()
                    };
                    let Ok(job) = job else { break };
                    if let Err(e) = job() {
                        first_error
                            .lock()
                            .unwrap_or_else(|p| p.into_inner())
                            .get_or_insert(e);
                    }
                })
            })
            .collect();
        Self {
            sender: Some(sender),
            workers,
            first_error,
        }
    }

    /// Queues a job; fails with the first error any job has reported so far.
    pub fn submit(
        &self,
        job: impl FnOnce() -> Result<(), PipelineError> + Send + 'static,
    ) -> Result<(), PipelineError> {
        self.take_error()?;
        if let Some(sender) = &self.sender {
            sender
                .send(Box::new(job))
                .map_err(|_| PipelineError::Worker("the encoder threads stopped".into()))?;
        }
        Ok(())
    }

    fn take_error(&self) -> Result<(), PipelineError> {
        match self
            .first_error
            .lock()
            .unwrap_or_else(|p| p.into_inner())
            .take()
        {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Waits for every queued job and returns the first error.
    pub fn finish(mut self) -> Result<(), PipelineError> {
        self.sender = None;
        for worker in self.workers.drain(..) {
            worker
                .join()
                .map_err(|_| PipelineError::Worker("an encoder thread panicked".into()))?;
        }
        self.take_error()
    }
}
