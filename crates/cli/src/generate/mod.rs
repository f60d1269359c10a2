//! Dataset generation: glue between the renderer (or a dataset on disk), the perturber and the
//! dataset writer. Frames go GPU → one readback → encoder threads; the manifest is written last.

mod decode_ahead;
mod drive;
mod encoder_pool;
mod manifest;
mod perturb_images;
mod perturb_job;
mod progress;
mod render_job;
mod sink;

pub use perturb_job::{run_perturb, PerturbInput, PerturbJob};
pub use render_job::{run_render, RenderJob};
