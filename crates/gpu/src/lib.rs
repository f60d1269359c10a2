//! The one GPU context of rslam.
//!
//! Data flow: [`GpuContext`] picks the adapter (lavapipe or a real GPU) and owns device and queue;
//! [`shader`] hands out the embedded WGSL with `#include`s resolved; [`FrameTextures`] hold one
//! frame's colour and depth on the GPU, where the renderer writes them and the perturbations
//! transform them; [`FrameUploads`] brings decoded frames in from the threads that decoded them;
//! [`FrameRing`] keeps several frames in flight and reads each back once, as a [`MappedFrame`]
//! unpacked wherever it is handed to.

mod context;
mod error;
mod frame;
mod frame_ring;
mod frame_uploads;
mod mapped_frame;
mod readback;
pub mod shader;
mod texture;

pub use context::{AdapterChoice, GpuContext};
pub use error::GpuError;
pub use frame::FrameTextures;
pub use frame_ring::{FrameRing, ReadFrame};
pub use frame_uploads::{FilledUpload, FrameUploads, UploadFiller};
pub use mapped_frame::{MappedColor, MappedDepth, MappedFrame};
pub use readback::{read_buffer, read_texels, FrameReadback};
pub use wgpu;
