//! Encoding and writing on worker threads while the GPU renders the next frames. The queue is
//! bounded, so a slow disk holds the GPU back instead of filling memory.

use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

type Job = Box<dyn FnOnce() -> anyhow::Result<()> + Send>;

pub struct EncoderPool {
    sender: Option<SyncSender<Job>>,
    workers: Vec<JoinHandle<()>>,
    first_error: Arc<Mutex<Option<anyhow::Error>>>,
}

impl EncoderPool {
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
        job: impl FnOnce() -> anyhow::Result<()> + Send + 'static,
    ) -> anyhow::Result<()> {
        self.take_error()?;
        if let Some(sender) = &self.sender {
            sender
                .send(Box::new(job))
                .map_err(|_| anyhow::anyhow!("encoder threads stopped"))?;
        }
        Ok(())
    }

    fn take_error(&self) -> anyhow::Result<()> {
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
    pub fn finish(mut self) -> anyhow::Result<()> {
        self.sender = None;
        for worker in self.workers.drain(..) {
            worker
                .join()
                .map_err(|_| anyhow::anyhow!("an encoder thread panicked"))?;
        }
        self.take_error()
    }
}
