//! TUM-VI's EuRoC-style export as `rslam_core::dataset::euroc::read_euroc` reads it: Kalibr's
//! `dso/camchain.yaml` and `dso/imu_config.yaml` in place of the sensor.yaml files. Each target's
//! file replaces one file of a small valid `dataset-room1_512_16`-style folder (two frames per
//! camera, imu0's readings as EuRoC's seed has them).

use std::path::Path;

use rslam_core::dataset::encode_grey_png;
use rslam_core::dataset::euroc::{read_camchain, read_euroc};
use rslam_core::{Pose, RgbImage};

use super::euroc;
use crate::Scratch;

pub const CAMCHAIN: &str = "dso/camchain.yaml";
pub const IMU_CONFIG: &str = "dso/imu_config.yaml";

/// cam0's and cam1's two stamps, 50 ms apart.
const STAMPS: [u64; 2] = [1_520_530_308_199_447_626, 1_520_530_308_249_448_626];

/// Every file the reader needs, valid: the targets' first seeds, imu0's readings and two frames
/// per camera listed in its data.csv.
pub fn prepare(dir: &Path) -> std::io::Result<()> {
    for (target, file) in [
        ("tum_vi_camchain", CAMCHAIN),
        ("tum_vi_imu_config", IMU_CONFIG),
        ("euroc_imu", euroc::IMU_CSV),
    ] {
        let seeds = crate::corpus::seeds(target).map_err(std::io::Error::other)?;
        let path = dir.join(file);
        std::fs::create_dir_all(path.parent().expect("a file inside the dataset"))?;
        std::fs::write(path, &seeds[0])?;
    }
    for cam in ["cam0", "cam1"] {
        let data = dir.join("mav0").join(cam).join("data");
        std::fs::create_dir_all(&data)?;
        let mut csv = String::from("#timestamp [ns],filename\n");
        let png = encode_grey_png(&RgbImage::new(8, 8)).map_err(std::io::Error::other)?;
        for t in STAMPS {
            csv += &format!("{t},{t}.png\n");
            std::fs::write(data.join(format!("{t}.png")), &png)?;
        }
        std::fs::write(dir.join("mav0").join(cam).join("data.csv"), csv)?;
    }
    Ok(())
}

pub fn camchain(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(CAMCHAIN, input)?;
    read(&scratch.dir)?;
    // An accepted camchain rewritten with every camera where it was reads back the same.
    let path = scratch.dir.join(CAMCHAIN);
    let chain = read_camchain(&path).map_err(|e| e.to_string())?;
    let same = chain
        .cameras
        .iter()
        .map(|c| (c.name.clone(), c.camera_from_imu))
        .collect();
    scratch.write(CAMCHAIN, chain.rewritten(&same).as_bytes())?;
    let again = read_camchain(&path).map_err(|e| format!("rewritten camchain: {e}"))?;
    for (a, b) in chain.cameras.iter().zip(&again.cameras) {
        let moved = (a.camera_from_imu.translation - b.camera_from_imu.translation).length();
        let turned = a
            .camera_from_imu
            .rotation
            .angle_between(b.camera_from_imu.rotation);
        assert!(
            moved < 1e-9 && turned < 1e-6,
            "{}: rewritten in place, read back {moved} m, {turned} rad away",
            a.name
        );
    }
    Ok(())
}

pub fn imu_config(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(IMU_CONFIG, input)?;
    read(&scratch.dir)
}

/// An accepted export is read as TUM-VI's, with finite camera poses, and keeps the EuRoC
/// reader's invariants.
fn read(root: &Path) -> Result<(), String> {
    euroc::read(root)?;
    let dataset = read_euroc(root).map_err(|e| e.to_string())?;
    assert!(dataset.tum_vi.is_some(), "read as EuRoC's layout");
    for camera in &dataset.cameras {
        let pose: &Pose = &camera.camera.body_from_camera;
        assert!(
            pose.translation.is_finite() && pose.rotation.is_finite(),
            "accepted {} pose {pose:?}",
            camera.camera.name
        );
    }
    Ok(())
}
