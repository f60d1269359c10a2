//! A window capture written as PNG through `rslam-core`'s encoder.

use std::path::Path;

use rslam_core::dataset::{encode_png, write_atomically};
use rslam_core::RgbImage;

use crate::ViewerError;

pub fn save(image: &egui::ColorImage, path: &Path) -> Result<(), ViewerError> {
    let [width, height] = image.size;
    let data = image
        .pixels
        .iter()
        .flat_map(|c| [c.r(), c.g(), c.b()])
        .collect();
    let rgb = RgbImage {
        width: width as u32,
        height: height as u32,
        data,
    };
    write_atomically(path, &encode_png(&rgb)?)?;
    Ok(())
}
