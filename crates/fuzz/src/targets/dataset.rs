//! The files of a dataset folder as `rslam perturb` and `rslam verify` read them: TUM frame
//! lists and associations, Replica's `cam_params.json`, the manifest, the checksum list, images.

use std::path::Path;

use rslam_core::dataset::{
    decode_depth_png, is_inside, read_dataset, read_rgb, Checksums, DatasetOverrides,
    SourceDataset, CHECKSUM_FILE, MANIFEST_FILE,
};
use rslam_core::limits::{MAX_IMAGE_SIDE, MAX_POSES};
use rslam_core::Intrinsics;

use crate::Scratch;

pub const ASSOCIATIONS: &str = "associations.txt";
pub const RGB_LIST: &str = "rgb.txt";
pub const CAM_PARAMS: &str = "cam_params.json";
pub const MANIFEST: &str = MANIFEST_FILE;
pub const CHECKSUMS: &str = CHECKSUM_FILE;
pub const IMAGE: &str = "frame000000.png";
pub const DEPTH_PNG: &str = "depth000000.png";

const VALID_RGB_LIST: &str = "# color images\n0.000 rgb/0.000.png\n0.033 rgb/0.033.png\n";
const VALID_DEPTH_LIST: &str = "# depth maps\n0.001 depth/0.001.png\n0.034 depth/0.034.png\n";

/// A TUM sequence's frame lists; the target's file replaces one of them.
pub fn prepare_tum(dir: &Path) -> std::io::Result<()> {
    std::fs::write(dir.join(RGB_LIST), VALID_RGB_LIST)?;
    std::fs::write(dir.join("depth.txt"), VALID_DEPTH_LIST)
}

/// A Replica scene folder with one frame (its bytes are not read when listing).
pub fn prepare_replica(dir: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir.join("results"))?;
    std::fs::write(dir.join("results/frame000000.jpg"), b"")?;
    std::fs::write(dir.join("results/depth000000.png"), b"")
}

/// The TUM camera and rate, given as `--camera tum --rate 30` would.
const TUM_OVERRIDES: DatasetOverrides = DatasetOverrides {
    camera: Some(Intrinsics::TUM),
    rate_hz: Some(30.0),
};

pub fn associations(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(ASSOCIATIONS, input)?;
    read(&scratch.dir, &TUM_OVERRIDES)
}

/// rgb.txt without associations, paired with depth.txt by time; the rate measured from it.
pub fn rgb_list(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(RGB_LIST, input)?;
    let overrides = DatasetOverrides {
        rate_hz: None,
        ..TUM_OVERRIDES
    };
    read(&scratch.dir, &overrides)
}

pub fn cam_params(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(CAM_PARAMS, input)?;
    let overrides = DatasetOverrides {
        camera: None,
        rate_hz: Some(20.0),
    };
    read(&scratch.dir, &overrides)
}

/// The manifest gives camera and rate of a dataset rslam wrote.
pub fn manifest(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(MANIFEST, input)?;
    read(&scratch.dir, &DatasetOverrides::default())
}

/// An accepted checksum list names only files inside the dataset.
pub fn checksums(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(CHECKSUMS, input)?;
    let sums = Checksums::read(&scratch.dir).map_err(|e| e.to_string())?;
    if let Some(outside) = sums.paths().find(|p| !is_inside(p)) {
        panic!("accepted a checksum for '{outside}', outside the dataset");
    }
    Ok(())
}

pub fn image(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    let path = scratch.write(IMAGE, input)?;
    let image = read_rgb(&path).map_err(|e| e.to_string())?;
    check_size(image.width, image.height, image.data.len() / 3);
    Ok(())
}

pub fn depth_png(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    let path = scratch.write(DEPTH_PNG, input)?;
    let depth = decode_depth_png(&path, 5000.0).map_err(|e| e.to_string())?;
    check_size(depth.width, depth.height, depth.data.len());
    if let Some(d) = depth.data.iter().find(|d| !(d.is_finite() && **d >= 0.0)) {
        panic!("accepted depth {d}");
    }
    Ok(())
}

fn check_size(width: u32, height: u32, pixels: usize) {
    assert!(
        width.max(height) <= MAX_IMAGE_SIDE,
        "accepted a {width}x{height} image"
    );
    assert_eq!(
        pixels,
        width as usize * height as usize,
        "{width}x{height} image"
    );
}

/// An accepted dataset has a usable camera and rate and finite frame times.
fn read(root: &Path, overrides: &DatasetOverrides) -> Result<(), String> {
    let dataset: SourceDataset = read_dataset(root, overrides).map_err(|e| e.to_string())?;
    if let Err(problem) = dataset.intrinsics.check() {
        panic!("accepted camera {:?}: {problem}", dataset.intrinsics);
    }
    assert!(
        dataset.rate_hz.is_finite() && dataset.rate_hz > 0.0,
        "accepted rate {}",
        dataset.rate_hz
    );
    assert!(
        dataset.frames.len() <= MAX_POSES,
        "accepted {} frames",
        dataset.frames.len()
    );
    for (i, frame) in dataset.frames.iter().enumerate() {
        assert!(
            frame.rgb_time.is_finite() && frame.depth_time.is_finite(),
            "frame {i}: accepted times {} and {}",
            frame.rgb_time,
            frame.depth_time
        );
    }
    Ok(())
}
