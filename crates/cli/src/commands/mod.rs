//! One file per subcommand: clap arguments turned into library option structs.

pub mod eval;
pub mod list;
pub mod perturb;
pub mod render;
pub mod scene;
