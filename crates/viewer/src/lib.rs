//! The egui viewer behind `rslam view`: inspect a scene or a dataset and tune perturbations live.
//!
//! Data flow: [`ViewOptions`] name a scene or dataset, a spec and a seed. A [`Session`] opens them
//! as the pipeline's `FramesInMemory` on the one [`GpuContext`] and keeps everything the window
//! shows as plain state: the frame index and playback, the spec being edited ([`SpecEditor`]),
//! the trajectory panel's data (ground truth, the aligned estimate), the free camera. On each
//! change the session asks the pipeline to leave the current output frame on the GPU in a
//! `ShownFrame` (clean and perturbed, depth colour-mapped); [`ViewerApp`] registers those textures
//! with egui-wgpu once and draws them, so frames go from rasterisation through the corruptions to
//! the screen without a readback. eframe presents with the same device ([`run_window`]).

mod app;
mod error;
mod free_camera;
mod playback;
mod screenshot;
mod sequence;
mod session;
mod spec_editor;
mod trajectory_view;
mod ui;
mod window;

pub use app::{FrameView, ViewerApp};
pub use error::ViewerError;
pub use free_camera::{CameraStep, FreeCamera};
pub use playback::Playback;
pub use rslam_gpu::GpuContext;
pub use sequence::Sequence;
pub use session::{Session, ViewOptions, ViewSource};
pub use spec_editor::{DeviationSetting, EditorItem, ItemSetting, SpecEditor};
pub use trajectory_view::{EstimateOverlay, TrajectoryView};
pub use window::{render_state_for, run_window, WindowOptions};
