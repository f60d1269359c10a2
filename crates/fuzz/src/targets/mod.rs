//! The parsers under test, grouped by what they read; [`TARGETS`] lists them all.

mod all;
mod dataset;
mod euroc;
mod mesh;
mod suite;
mod text;
mod trajectory;

pub use all::TARGETS;
