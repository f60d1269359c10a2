//! ORB-SLAM3 v1.0 stereo and stereo-inertial settings for a EuRoC rig: cam0 is the left camera
//! (`Camera1`), cam1 the right one (`Camera2`), the body frame the IMU's. Keys, order and values
//! follow ORB-SLAM3 v1.0's own `Examples/Stereo/EuRoC.yaml` and
//! `Examples/Stereo-Inertial/EuRoC.yaml` (distorted pinhole pair, `Stereo.T_c1_c2`,
//! `IMU.T_b_c1`); the calibration is the rig's, the tracking parameters the examples'.
//!
//! Frames. EuRoC's `T_BS` of a sensor S maps S coordinates to body coordinates
//! (`body_from_camera`). ORB-SLAM3's `T_a_b` maps b coordinates to a coordinates (b's pose in
//! a). So
//! - `Stereo.T_c1_c2` = cam0_from_cam1 = inverse(T_BS cam0) · T_BS cam1 (its translation is
//!   the right camera's position in the left camera's frame, about +0.11 m along x on EuRoC);
//! - `IMU.T_b_c1` = imu_from_cam0 = inverse(T_BS imu0) · T_BS cam0, which is cam0's `T_BS`
//!   itself when the body frame is the IMU's (imu0's `T_BS` the identity, as in EuRoC and in
//!   what rslam writes).

use super::imu::imu_part;
use crate::dataset::euroc::{CameraColour, EurocCamera, EurocImu};
use crate::Pose;

/// `Stereo.ThDepth` of ORB-SLAM3's EuRoC stereo examples: points closer than 60 baselines are
/// "close" (triangulated from one stereo pair).
const TH_DEPTH: &str = "60.0";
/// `ORBextractor.nFeatures` of ORB-SLAM3's EuRoC stereo examples (752×480 images).
const FEATURES: u32 = 1200;

/// A number as OpenCV's `FileStorage` reads a real: ORB-SLAM3's `Settings` refuses a float key
/// whose node is not `isReal()`, so `200` must be written `200.0`. Rust's shortest round-trip
/// digits, never an exponent, always a decimal point.
pub(super) fn real(v: f64) -> String {
    let text = format!("{v}");
    if text.contains('.') {
        text
    } else {
        format!("{text}.0")
    }
}

/// `name: !!opencv-matrix` of a rigid transform, 4×4 row-major, single precision (`dt: f`), laid
/// out as the examples lay out `Stereo.T_c1_c2`. Entries under 1e-12, rounding left over from
/// composing transforms and far below single precision, are written as 0.0.
pub(super) fn opencv_matrix(name: &str, pose: &Pose) -> String {
    let entry = |v: f64| real(if v.abs() < 1e-12 { 0.0 } else { v });
    let rows: Vec<String> = pose
        .to_row_major()
        .chunks_exact(4)
        .map(|row| row.iter().map(|v| entry(*v)).collect::<Vec<_>>().join(", "))
        .collect();
    format!(
        "{name}: !!opencv-matrix\n  rows: 4\n  cols: 4\n  dt: f\n  data: [{}]\n",
        rows.join(",\n         ")
    )
}

/// `CameraN.fx … CameraN.p2`: pinhole intrinsics and radial-tangential distortion.
fn camera_block(n: u32, camera: &EurocCamera) -> String {
    let k = &camera.intrinsics;
    let d = &camera.distortion;
    format!(
        "# {name}: {comment}\n\
         Camera{n}.fx: {fx}\nCamera{n}.fy: {fy}\nCamera{n}.cx: {cx}\nCamera{n}.cy: {cy}\n\n\
         Camera{n}.k1: {k1}\nCamera{n}.k2: {k2}\nCamera{n}.p1: {p1}\nCamera{n}.p2: {p2}\n",
        name = camera.name,
        comment = crate::printable(&camera.comment),
        fx = real(k.fx),
        fy = real(k.fy),
        cx = real(k.cx),
        cy = real(k.cy),
        k1 = real(d.k1),
        k2 = real(d.k2),
        p1 = real(d.p1),
        p2 = real(d.p2),
    )
}

/// Why `left` and `right` cannot be one ORB-SLAM3 stereo pair, or `None` when they can:
/// ORB-SLAM3 has one `Camera.width`/`height` and one `Camera.fps` for both cameras, and pairs
/// their frames by timestamp.
pub fn stereo_pair_problem(left: &EurocCamera, right: &EurocCamera) -> Option<String> {
    let (a, b) = (&left.intrinsics, &right.intrinsics);
    if (a.width, a.height) != (b.width, b.height) {
        return Some(format!(
            "{} is {}x{} and {} is {}x{}: ORB-SLAM3's stereo settings need one resolution for both cameras",
            left.name, a.width, a.height, right.name, b.width, b.height
        ));
    }
    if left.rate_hz != right.rate_hz {
        return Some(format!(
            "{} runs at {} Hz and {} at {} Hz: ORB-SLAM3's stereo settings need one rate for both cameras",
            left.name, left.rate_hz, right.name, right.rate_hz
        ));
    }
    None
}

/// Everything both files share up to and including `Stereo.T_c1_c2`.
fn cameras_part(left: &EurocCamera, right: &EurocCamera, what: &str) -> String {
    let k = &left.intrinsics;
    // Camera.RGB only matters for 3-channel images (ORB-SLAM3 converts those to grey in this
    // channel order); grey PNGs are read as one channel.
    let rgb = [left, right].iter().any(|c| c.colour == CameraColour::Rgb);
    let cam0_from_cam1 = left
        .body_from_camera
        .inverse()
        .compose(&right.body_from_camera);
    format!(
        "%YAML:1.0\n\
         # ORB-SLAM3 {what} settings written by rslam for this dataset's {left_name} (Camera1, left)\n\
         # and {right_name} (Camera2, right), from their mav0/*/sensor.yaml.\n\
         File.version: \"1.0\"\n\n\
         Camera.type: \"PinHole\"\n\n\
         {camera1}\n{camera2}\n\
         Camera.width: {w}\nCamera.height: {h}\n\
         Camera.fps: {fps}\n\
         Camera.RGB: {rgb}\n\n\
         Stereo.ThDepth: {TH_DEPTH}\n\
         # {right_name}'s pose in {left_name}'s frame: inverse(T_BS {left_name}) * T_BS {right_name}.\n\
         {t_c1_c2}",
        left_name = left.name,
        right_name = right.name,
        camera1 = camera_block(1, left),
        camera2 = camera_block(2, right),
        w = k.width,
        h = k.height,
        fps = left.rate_hz.round() as u32,
        rgb = u8::from(rgb),
        t_c1_c2 = opencv_matrix("Stereo.T_c1_c2", &cam0_from_cam1),
    )
}

/// ORB extractor and viewer keys, the examples' values.
fn tracking_part() -> String {
    format!(
        "\nORBextractor.nFeatures: {FEATURES}\n\
         ORBextractor.scaleFactor: 1.2\n\
         ORBextractor.nLevels: 8\n\
         ORBextractor.iniThFAST: 20\n\
         ORBextractor.minThFAST: 7\n\n\
         Viewer.KeyFrameSize: 0.05\n\
         Viewer.KeyFrameLineWidth: 1.0\n\
         Viewer.GraphLineWidth: 0.9\n\
         Viewer.PointSize: 2.0\n\
         Viewer.CameraSize: 0.08\n\
         Viewer.CameraLineWidth: 3.0\n\
         Viewer.ViewpointX: 0.0\n\
         Viewer.ViewpointY: -0.7\n\
         Viewer.ViewpointZ: -1.8\n\
         Viewer.ViewpointF: 500.0\n\
         Viewer.imageViewScale: 1.0\n"
    )
}

/// `orbslam3_stereo.yaml`: ORB-SLAM3 v1.0 stereo settings for `left` (cam0, `Camera1`) and
/// `right` (cam1, `Camera2`), distorted images rectified by ORB-SLAM3 itself. The pair must pass
/// [`stereo_pair_problem`] (the width, height and fps written are `left`'s).
pub fn stereo_settings(left: &EurocCamera, right: &EurocCamera) -> String {
    cameras_part(left, right, "stereo") + &tracking_part()
}

/// `orbslam3_stereo_inertial.yaml`: [`stereo_settings`] plus the IMU: `IMU.T_b_c1` (cam0's pose
/// in the IMU frame) and the noise model. ORB-SLAM3's `IMU.Noise*`/`*Walk` are continuous-time
/// densities as Kalibr's and EuRoC's sensor.yaml give them (ORB-SLAM3 scales them by √rate
/// itself); its EuRoC example rounds EuRoC's 1.6968e-4 rad/s/√Hz to `NoiseGyro: 1.7e-04` and
/// keeps 2.0e-3, 1.9393e-5 and 3.0e-3. `IMU.InsertKFsWhenLost` is left out, as in that
/// example.
pub fn stereo_inertial_settings(left: &EurocCamera, right: &EurocCamera, imu: &EurocImu) -> String {
    format!(
        "{cameras}\n{imu}{tracking}",
        cameras = cameras_part(left, right, "stereo-inertial"),
        imu = imu_part(&left.name, &left.body_from_camera, imu),
        tracking = tracking_part(),
    )
}
