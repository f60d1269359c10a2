//! Hostile input for every parser of rslam.
//!
//! Data flow: a [`Target`] takes the bytes of one input file (or flag) and hands them to one
//! parser through the same entry point rslam uses, in a scratch folder holding whatever else the
//! parser needs; [`run_one`] runs it and turns what came back into an [`Outcome`]: accepted,
//! rejected with a one-line error, or a [`Finding`] (a panic, a multi-line error, an error that
//! does not name its file, an accepted value that breaks an invariant such as a NaN pose).
//! The fuzzer (`rslam-fuzz`, [`worker`] and [`supervisor`]) feeds [`mutate`]d seeds from
//! `corpus/` for a given time and catches what [`run_one`] cannot: aborts, allocations over the
//! memory cap, inputs that take too long. The property tests (`tests/`) feed the same targets
//! from proptest.

pub mod corpus;
pub mod mutate;
mod outcome;
pub mod supervisor;
mod target;
mod targets;
pub mod worker;

pub use outcome::{finding_key, run_one, signature, Finding, Outcome};
pub use target::{Scratch, Target};
pub use targets::TARGETS;

/// The target called `name`.
pub fn target(name: &str) -> Option<&'static Target> {
    TARGETS.iter().find(|t| t.name == name)
}
