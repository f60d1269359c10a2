//! One file per subcommand: clap arguments turned into library option structs.

mod actor_args;
pub mod eval;
mod eval_recon;
pub mod list;
mod make;
pub mod perturb;
pub mod render;
mod run_summary;
pub mod scene;
mod scene_stats;
pub mod suite;
pub mod verify;
pub mod view;

/// The command line as typed, with the program called `rslam` whatever path started it, so that
/// the same command records the same manifest.
pub fn typed_command() -> Vec<String> {
    std::iter::once("rslam".to_string())
        .chain(std::env::args().skip(1))
        .collect()
}
