//! What a perturb job's input is: a dataset, a ROS 2 bag, a folder of images, or one image.

use std::path::{Path, PathBuf};

use crate::perturb_images::is_image;
use crate::rig::is_euroc_input;
use crate::PipelineError;

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PerturbInput {
    Dataset(PathBuf),
    /// A EuRoC (ASL) dataset: the folder holding `mav0/`, or `mav0/` itself.
    Euroc(PathBuf),
    /// A ROS 2 bag: a rosbag2 folder (`metadata.yaml` and its storage file).
    Bag(PathBuf),
    ImageFolder(PathBuf),
    Image(PathBuf),
}

impl PerturbInput {
    /// A dataset (Replica `results/`, TUM `rgb.txt` or EuRoC `mav0/`), a ROS 2 bag
    /// (`metadata.yaml`), a folder of PNG/JPEG images, or one image.
    pub fn detect(path: &Path) -> Result<Self, PipelineError> {
        if path.is_file() {
            if !is_image(path) {
                return Err(PipelineError::input(
                    path,
                    "expected a dataset folder, an image folder or a .png/.jpg file",
                ));
            }
            return Ok(Self::Image(path.to_path_buf()));
        }
        if !path.is_dir() {
            return Err(PipelineError::input(path, "no such file or folder"));
        }
        if is_euroc_input(path) {
            return Ok(Self::Euroc(path.to_path_buf()));
        }
        if path.join("rgb.txt").is_file() || path.join("results").is_dir() {
            return Ok(Self::Dataset(path.to_path_buf()));
        }
        if path.join("metadata.yaml").is_file() {
            return Ok(Self::Bag(path.to_path_buf()));
        }
        Ok(Self::ImageFolder(path.to_path_buf()))
    }
}
