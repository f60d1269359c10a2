//! The one GPU context of rslam.
//!
//! Data flow: [`GpuContext`] picks the adapter (lavapipe or a real GPU) and owns device and queue;
//! [`shader`] hands out the embedded WGSL with `#include`s resolved; [`FrameTextures`] hold one
//! frame's colour and depth on the GPU, where the renderer writes them and the perturbations
//! transform them; [`FrameUploads`] brings decoded frames in from the threads that decoded them;
//! [`FrameRing`] keeps several frames in flight and reads each back once, as a [`MappedFrame`]
//! unpacked wherever it is handed to. [`Scan`] and [`RadixSort`] are the prefix sum and the
//! stable sort that GPU-resident algorithms (the splat rasteriser) build on.

pub mod compute;
mod context;
mod error;
mod frame;
mod frame_ring;
mod frame_uploads;
mod mapped_frame;
mod radix_sort;
mod readback;
mod scan;
pub mod shader;
mod texture;

pub use context::{AdapterChoice, GpuContext};
pub use error::GpuError;
pub use frame::FrameTextures;
pub use frame_ring::{FrameRing, ReadFrame};
pub use frame_uploads::{FilledUpload, FrameUploads, UploadFiller};
pub use mapped_frame::{MappedColor, MappedDepth, MappedFrame, MappedMask};
pub use radix_sort::RadixSort;
pub use readback::{read_buffer, read_texels, BufferReadback, FrameReadback};
pub use scan::Scan;
pub use wgpu;
