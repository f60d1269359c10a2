//! The panels: each draws part of a [`crate::Session`] and turns input into calls on it.

mod camera_keys;
mod frame_panel;
mod perturbation_panel;
mod side_panel;
mod timeline;
mod top_bar;
mod trajectory_panel;

pub(crate) use camera_keys::camera_keys;
pub(crate) use frame_panel::frame_panel;
pub(crate) use perturbation_panel::perturbation_panel;
pub(crate) use side_panel::side_panel;
pub(crate) use timeline::timeline;
pub(crate) use top_bar::top_bar;
