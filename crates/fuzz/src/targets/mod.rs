//! The parsers under test, grouped by what they read; [`TARGETS`] lists them all.

mod all;
mod dataset;
mod euroc;
mod mesh;
mod ros2_bag;
mod suite;
mod text;
mod trajectory;
mod tum_vi;

pub use all::TARGETS;
