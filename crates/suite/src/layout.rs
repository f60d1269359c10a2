//! How a suite makes datasets of each layout ([`Layout`], rslam's layouts), for an error that
//! asks for another layout.

use rslam_core::dataset::Layout;
use rslam_pipeline::rig::RIG_NAMES;

/// How to make a suite of `layout`.
pub fn how_to_make(layout: Layout) -> String {
    match layout {
        Layout::Camera(format) => format!("`rslam suite init --format {format}`"),
        Layout::Euroc => format!(
            "rows that say format = \"euroc\" and rig = one of {}",
            RIG_NAMES.join(", ")
        ),
    }
}
