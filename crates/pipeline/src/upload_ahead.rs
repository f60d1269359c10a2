//! A source's frames decoded ahead of the GPU straight into upload buffers, and recorded into the
//! frame textures in order.

use rslam_gpu::{wgpu, FilledUpload, FrameTextures, FrameUploads, GpuContext, UploadFiller};

use crate::decode_ahead::{self, DecodeAhead};
use crate::PipelineError;

pub struct UploadAhead {
    size: (u32, u32),
    with_depth: bool,
    /// Frames decoded together in parallel.
    ahead: usize,
    /// Made by the first run, kept for the next.
    uploads: Option<FrameUploads>,
    /// Each frame of the run, filled with its source index.
    decoder: Option<DecodeAhead<(usize, FilledUpload)>>,
}

impl UploadAhead {
    /// For frames of `width × height`, with depth buffers if `with_depth`.
    pub fn new(width: u32, height: u32, with_depth: bool) -> Self {
        Self {
            size: (width, height),
            with_depth,
            ahead: decode_ahead::frames_per_core(),
            uploads: None,
            decoder: None,
        }
    }

    /// Starts a run over `items`, each a source index and what `decode` reads that frame from
    /// into the filler it is given; it replaces the run before.
    pub fn start<I: Send + Sync + 'static>(
        &mut self,
        ctx: &GpuContext,
        items: Vec<(usize, I)>,
        decode: impl Fn(&I, &UploadFiller) -> Result<FilledUpload, PipelineError>
            + Send
            + Sync
            + 'static,
    ) {
        // Dropping the run before first hands its buffers back.
        self.decoder = None;
        // While a frame is being filled, at most `ahead` frames wait decoded, `ahead - 1` more of
        // its chunk are filled, and the frame loop holds two (the one it records, the one
        // before): one buffer more than that is free for it.
        let ((width, height), with_depth, ahead) = (self.size, self.with_depth, self.ahead);
        let filler = self
            .uploads
            .get_or_insert_with(|| FrameUploads::new(ctx, width, height, with_depth, 2 * ahead + 2))
            .filler();
        self.decoder = Some(DecodeAhead::start(items, ahead, move |(index, item)| {
            Ok((*index, decode(item, &filler)?))
        }));
    }

    /// Records source frame `index`, which must be the run's next.
    pub fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        index: usize,
    ) -> Result<(), PipelineError> {
        let (Some(decoder), Some(uploads)) = (&self.decoder, &mut self.uploads) else {
            return Err(PipelineError::Worker(
                "frames recorded before prepare".into(),
            ));
        };
        let (decoded, upload) = decoder.next()?;
        if decoded != index {
            return Err(PipelineError::Worker(format!(
                "decoder delivered frame {decoded} where frame {index} was expected"
            )));
        }
        uploads.record(encoder, frame, upload);
        Ok(())
    }
}
