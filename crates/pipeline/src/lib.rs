//! The generation pipeline: a source, a perturbation spec and a sink, driven through the GPU.
//!
//! Data flow: a [`Job`] (made by [`run`]) or an in-memory caller ([`FramesInMemory`]) picks a
//! [`source`] — a scene drawn along a (deviated) path, a dataset or
//! image files decoded ahead, buffers in memory — and makes the [`FramePlan`] before any frame is
//! drawn (a scene under a shutter — `exposure`, `rolling_shutter` — draws each frame from the
//! poses of its capture interval and sums them on the GPU; under a lens — `distortion` — it draws
//! with a wider pinhole and resamples through the lens): which source frame each output frame's colour and depth come from, their capture times
//! and every frame's severities. The [`Pipeline`] records each needed source frame and its image
//! then depth corruptions into one command encoder, keeps several frames in flight and reads each
//! back once; a [`sink`] encodes it into a dataset on worker threads or assembles output frames
//! in memory. For display, [`FramesInMemory::show`] leaves an output frame on the GPU in a
//! [`ShownFrame`] instead (clean, perturbed, depth colour-mapped), with no readback. A dataset
//! run first marks its folder with `rslam.run.json` ([`output_folder`]), so that the same job
//! resumes where it stopped, and finishes with checksums and the manifest. A [`rig`] of several
//! cameras and an IMU is one scene source, pipeline and sink per camera along one motion spline,
//! written in the EuRoC layout; a recorded EuRoC dataset is one decoding source per camera.

mod agents;
mod dataset_run;
mod decode_ahead;
pub mod depth_colormap;
mod encoder_pool;
mod error;
mod frame_loop;
mod frames_in_memory;
mod input;
mod job;
mod lens_render;
mod manifest;
pub mod output_folder;
mod perturb_bag;
mod perturb_dataset;
mod perturb_images;
mod pipeline;
mod plan;
mod progress;
mod render;
pub mod rig;
mod scene_actors;
mod scene_job;
mod scene_light;
pub mod settings;
mod shown_frame;
mod shutter_render;
pub mod sink;
pub mod source;
mod state_log;
mod upload_ahead;

pub use agents::{agent_folders, agent_scene_job};
pub use depth_colormap::DepthRange;
pub use error::{JobPart, PipelineError};
pub use frames_in_memory::FramesInMemory;
pub use input::PerturbInput;
pub use job::{run, Job, JobReport, PlannedJob, Sensors, Source, Streams};
pub use output_folder::{FolderState, Holding};
pub use perturb_images::image_files;
pub use pipeline::Pipeline;
pub use plan::{speed_up, FramePlan, SourceOutputs, SourceTiming};
pub use progress::{Progress, Silent};
pub use rig::{Rig, RigPreset};
pub use scene_job::{ActorFiles, ResolvedScene, SceneCache, SceneJob};
pub use shown_frame::{PixelReadout, ShownFrame, ShownSources, ShownViews};
pub use sink::RgbdFrame;
pub use state_log::StateTable;
