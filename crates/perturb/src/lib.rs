//! Perturbations of RGB-D sequences: the catalogue, the spec parser, GPU compute passes, and the
//! trajectory and stream operations.
//!
//! Data flow: a `--perturb` string is parsed into a [`PerturbSpec`]. Trajectory items (`rot`,
//! `trans`) deviate the poses before rendering ([`trajectory`]); sensor items (`exposure`,
//! `rolling_shutter`) tell the renderer which poses of the capture interval to draw and sum
//! ([`sensor`]); calibration items (`baseline`, `extrinsic_*`) move a rig's sensors or its written
//! calibration ([`calibration`]). The renderer leaves each frame
//! in [`rslam_gpu::FrameTextures`]; a [`Perturber`] records the spec's image corruptions and then
//! its depth corruptions into the frame's command encoder, each one a [`GpuPerturbation`] from the
//! [`CATALOGUE`] transforming the textures in place, and reports the severity each got. Stream
//! items (`fast`, `misalign`) choose which rendered frames are written ([`stream`]). IMU items
//! (`imu_noise`, `imu_bias_step`, …, `cam_imu_offset`) act on a rig's IMU stream and camera
//! stamps on the CPU ([`imu`]). Randomness
//! comes from one counter-based hash keyed by (seed, perturbation, frame, purpose) ([`rng`]),
//! the same in Rust and WGSL. Every shader has a CPU twin next to it, reached through its entry
//! ([`Twin`]): the oracle of one table-driven test over the catalogue. Each entry also lists the
//! layouts of the parameter structs it writes into uniform blocks ([`uniform_layout`]), which a
//! test checks against naga's layout of the WGSL structs.

mod applies;
pub mod calibration;
mod catalogue;
#[cfg(test)]
mod catalogue_tests;
pub mod depth;
mod error;
pub mod image;
pub mod image_f32;
pub mod imu;
pub mod light;
mod listing;
mod perturbation;
mod perturber;
#[cfg(test)]
mod real_severity_tests;
pub mod reduce;
pub mod rng;
pub mod sensor;
mod severity;
mod spec;
pub mod stream;
#[cfg(test)]
pub(crate) mod testing;
pub mod trajectory;
mod twin;
pub mod uniform_layout;
#[cfg(test)]
mod uniform_layout_tests;
pub mod world;

pub use applies::{ItemEntry, Lenses, Need, Setting};
pub use catalogue::{find, names, CATALOGUE};
pub use error::PerturbError;
pub use listing::{listing, ListEntry};
pub use perturbation::{
    view, Between, CatalogueEntry, ExplicitForm, FrameKey, GpuPerturbation, Group, Kit, Scratch,
    WORKGROUP,
};
pub use perturber::{dynamic_severity, severity_on, FrameSeverities, ItemSeverity, Perturber};
pub use severity::Severity;
pub use spec::{
    all_names, parse_severity, Deviation, FrameItem, Level, Misalign, PerturbSpec, ITEM_TABLES,
};
pub use twin::{Tolerance, Twin, TwinRun, TwinState};
