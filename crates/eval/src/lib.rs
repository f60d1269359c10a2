//! Trajectory evaluation, with the numbers of evo 1.38.1.
//!
//! Data flow for one run: two trajectory files → `rslam_core::trajectory_io` readers →
//! [`associate`] (nearest timestamp, or index) → [`fit_alignment`] (Umeyama on positions:
//! SE(3), Sim(3) or none) → ATE per pose, [`relative_pose_errors`] over the pairs of
//! [`RpeOptions`], [`success_rate`] over the whole ground truth → [`Evaluation`] (statistics as
//! evo prints them), shown by [`text_report`], serialised as JSON, drawn by [`plot_evaluation`].
//!
//! For many runs, [`runs`] walks `<runs>/<method>/<sequence>.txt`, finds each sequence's ground
//! truth in the datasets folder, counts failures with the benchmark's convention and writes the
//! tables (ATE, SR, SR path ratio, tracked fraction, CSR, survival upper bound, Welch's t-test)
//! as Markdown, CSV, JSON and one self-contained HTML page, with the CSR curves and per-category
//! bar plots.
//!
//! For several agents in one world frame (a multi-agent system), [`multi_agent`] gives each
//! agent's ATE and SSE under its own alignment and under ONE joint alignment of all agents'
//! pairs, and the joint ATE and SSE.
//!
//! For frames, [`image_stats`] gives the statistics behind `rslam scene stats` (FAST corners,
//! their strength, local contrast, gradients, saturation, low-texture cells) to set rendered
//! frames beside real ones, and the band real indoor photographs give.
//!
//! For maps, [`recon`] measures a reconstructed mesh or point cloud against the ground-truth mesh
//! (accuracy, completion, completion ratio; CO-SLAM's protocol, distances to surfaces, culled to
//! what the cameras saw), and [`view_quality`] a map's rendered views against the clean frames
//! (PSNR, SSIM, depth L1).

mod alignment;
mod association;
pub mod correlation;
mod dynamic_ate;
mod error;
mod evaluate;
mod grouped_bars;
mod html_page;
pub mod image_stats;
pub mod multi_agent;
mod plot;
pub mod profile;
pub mod recon;
mod rpe;
mod rpe_pairs;
pub mod runs;
mod statistics;
mod success_rate;
mod text_report;
mod umeyama;
pub mod view_quality;
mod view_quality_plot;

#[cfg(test)]
mod test_support;

pub use alignment::{fit_alignment, AlignMode, Similarity};
pub use association::{associate, Association, Matching, DEFAULT_MAX_DIFF};
pub use dynamic_ate::{dataset_of, dynamic_ate, read_dynamic_fractions, DynamicAte};
pub use error::EvalError;
pub use evaluate::{
    evaluate, evaluate_files, read_and_evaluate, EvalOptions, EvalSeries, Evaluation,
};
pub use plot::plot_evaluation;
pub use rpe::{relative_pose_errors, DeltaUnit, RpeErrors, RpeOptions};
pub use rpe_pairs::pose_pairs;
pub use statistics::ErrorStatistics;
pub use success_rate::{success_rate, PathLengths, SuccessRate};
pub use text_report::text_report;
pub use umeyama::umeyama;
pub use view_quality_plot::{plot_view_quality_against_ate, ViewQualityPoint};
