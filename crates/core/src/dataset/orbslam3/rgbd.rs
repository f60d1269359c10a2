//! ORB-SLAM3 v1.0 RGB-D settings for a camera, with every key its loader and viewer read.

use super::imu::imu_part;
use crate::dataset::euroc::EurocImu;
use crate::{Distortion, Intrinsics, Pose};

/// `orbslam3.yaml` of the TUM layout: the camera with its lens distortion (`PinHole` with
/// k1, k2, p1, p2 for radial-tangential, `KannalaBrandt8` with k1..k4 for equidistant), depth in
/// 1/5000 m. Without distortion the file is the one rslam has always written.
pub fn settings(k: &Intrinsics, distortion: Option<&Distortion>, rate_hz: f64) -> String {
    let (described, camera_type, coefficients) = match distortion {
        None => (
            "no distortion".to_string(),
            "PinHole",
            "Camera1.k1: 0.0\nCamera1.k2: 0.0\nCamera1.p1: 0.0\nCamera1.p2: 0.0\nCamera1.k3: 0.0"
                .to_string(),
        ),
        Some(lens) => {
            let [a, b, c, d] = lens.coefficients();
            let (camera_type, names) = match lens {
                Distortion::Radtan { .. } => ("PinHole", ["k1", "k2", "p1", "p2"]),
                Distortion::Equidistant { .. } => ("KannalaBrandt8", ["k1", "k2", "k3", "k4"]),
            };
            let mut lines: Vec<String> = names
                .iter()
                .zip([a, b, c, d])
                .map(|(name, value)| format!("Camera1.{name}: {value:e}"))
                .collect();
            if camera_type == "PinHole" {
                lines.push("Camera1.k3: 0.0".into());
            }
            (
                format!("{} distortion", lens.model()),
                camera_type,
                lines.join("\n"),
            )
        }
    };
    format!(
        r#"%YAML:1.0
# ORB-SLAM3 RGB-D settings written by rslam for this dataset's camera ({described}).
File.version: "1.0"

Camera.type: "{camera_type}"
Camera1.fx: {fx:.6}
Camera1.fy: {fy:.6}
Camera1.cx: {cx:.6}
Camera1.cy: {cy:.6}
{coefficients}
Camera.width: {w}
Camera.height: {h}
Camera.fps: {fps}
Camera.RGB: 1

Stereo.ThDepth: 40.0
Stereo.b: 0.07
RGBD.DepthMapFactor: 5000.0

ORBextractor.nFeatures: 1000
ORBextractor.scaleFactor: 1.2
ORBextractor.nLevels: 8
ORBextractor.iniThFAST: 20
ORBextractor.minThFAST: 7

Viewer.KeyFrameSize: 0.05
Viewer.KeyFrameLineWidth: 1.0
Viewer.GraphLineWidth: 0.9
Viewer.PointSize: 2.0
Viewer.CameraSize: 0.08
Viewer.CameraLineWidth: 3.0
Viewer.ViewpointX: 0.0
Viewer.ViewpointY: -0.7
Viewer.ViewpointZ: -1.8
Viewer.ViewpointF: 500.0
"#,
        fx = k.fx,
        fy = k.fy,
        cx = k.cx,
        cy = k.cy,
        w = k.width,
        h = k.height,
        fps = rate_hz.round() as u32,
    )
}

/// `orbslam3_rgbd_inertial.yaml` of the `rgbd-imu` rig (ORB-SLAM3's `IMU_RGBD` sensor): the
/// undistorted camera's [`settings`] plus `IMU.T_b_c1` (the camera's pose in the IMU frame, from
/// its `body_from_camera` and the IMU's), the IMU's noise densities and rate, and
/// `IMU.InsertKFsWhenLost: 0`, the keys of ORB-SLAM3 v1.0's
/// `Examples/RGB-D-Inertial/RealSense_D435i.yaml`.
pub fn rgbd_inertial_settings(
    k: &Intrinsics,
    rate_hz: f64,
    body_from_camera: &Pose,
    imu: &EurocImu,
) -> String {
    format!(
        "{camera}\n{imu}\n# Do not insert keyframes when recently lost, as ORB-SLAM3's D435i example.\nIMU.InsertKFsWhenLost: 0\n",
        camera = settings(k, None, rate_hz),
        imu = imu_part("cam0", body_from_camera, imu),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::hash::fnv1a64;

    /// `settings(&Intrinsics::REPLICA, 20.0)` as rslam has written it since the TUM layout came
    /// in: datasets already written must not change under a later edit.
    const REPLICA_20_HZ: &str = r#"%YAML:1.0
# ORB-SLAM3 RGB-D settings written by rslam for this dataset's camera (no distortion).
File.version: "1.0"

Camera.type: "PinHole"
Camera1.fx: 600.000000
Camera1.fy: 600.000000
Camera1.cx: 599.500000
Camera1.cy: 339.500000
Camera1.k1: 0.0
Camera1.k2: 0.0
Camera1.p1: 0.0
Camera1.p2: 0.0
Camera1.k3: 0.0
Camera.width: 1200
Camera.height: 680
Camera.fps: 20
Camera.RGB: 1

Stereo.ThDepth: 40.0
Stereo.b: 0.07
RGBD.DepthMapFactor: 5000.0

ORBextractor.nFeatures: 1000
ORBextractor.scaleFactor: 1.2
ORBextractor.nLevels: 8
ORBextractor.iniThFAST: 20
ORBextractor.minThFAST: 7

Viewer.KeyFrameSize: 0.05
Viewer.KeyFrameLineWidth: 1.0
Viewer.GraphLineWidth: 0.9
Viewer.PointSize: 2.0
Viewer.CameraSize: 0.08
Viewer.CameraLineWidth: 3.0
Viewer.ViewpointX: 0.0
Viewer.ViewpointY: -0.7
Viewer.ViewpointZ: -1.8
Viewer.ViewpointF: 500.0
"#;

    #[test]
    fn rgbd_settings_are_byte_identical_to_what_earlier_versions_wrote() {
        assert_eq!(settings(&Intrinsics::REPLICA, None, 20.0), REPLICA_20_HZ);
        // FNV-1a 64 of the TUM preset's file, taken before the stereo settings were added.
        let tum = settings(&Intrinsics::TUM, None, 30.0);
        assert_eq!(fnv1a64(tum.as_bytes()), 0x8eb1_f531_8bd5_b75d, "{tum}");
    }

    /// The RGB-D file, then every IMU key of ORB-SLAM3's RealSense_D435i.yaml once, `IMU.T_b_c1`
    /// the camera's pose in the IMU's frame (here an IMU off the body's origin).
    #[test]
    fn rgbd_inertial_settings_are_the_rgbd_ones_plus_the_d435i_example_imu_keys() {
        use glam::{DQuat, DVec3};
        let imu = EurocImu {
            body_from_imu: Pose::new(DQuat::from_rotation_y(0.2), DVec3::new(0.1, 0.0, 0.0)),
            ..EurocImu::adis16448()
        };
        let body_from_camera =
            Pose::new(DQuat::from_rotation_z(0.01), DVec3::new(-0.02, 0.005, 0.01));
        let text = rgbd_inertial_settings(&Intrinsics::TUM, 30.0, &body_from_camera, &imu);
        assert!(text.starts_with(&settings(&Intrinsics::TUM, None, 30.0)));
        let value = |key: &str| -> String {
            let found: Vec<&str> = text
                .lines()
                .filter(|l| l.starts_with(&format!("{key}:")))
                .collect();
            assert_eq!(found.len(), 1, "{key} in\n{text}");
            found[0][key.len() + 1..].trim().to_string()
        };
        for (key, want) in [
            ("IMU.NoiseGyro", "0.00016968"),
            ("IMU.NoiseAcc", "0.002"),
            ("IMU.GyroWalk", "0.000019393"),
            ("IMU.AccWalk", "0.003"),
            ("IMU.Frequency", "200.0"),
            ("IMU.InsertKFsWhenLost", "0"),
        ] {
            assert_eq!(value(key), want, "{key}");
        }
        assert_eq!(value("IMU.T_b_c1"), "!!opencv-matrix");
        let at = text.find("IMU.T_b_c1:").unwrap();
        let data =
            &text[at + text[at..].find('[').unwrap() + 1..at + text[at..].find(']').unwrap()];
        let numbers: Vec<f64> = data.split(',').map(|v| v.trim().parse().unwrap()).collect();
        let written = Pose::from_row_major(&numbers.try_into().unwrap());
        let want = imu.body_from_imu.inverse().compose(&body_from_camera);
        assert!((written.translation - want.translation).length() < 1e-12);
        assert!(written.rotation.angle_between(want.rotation) < 1e-9);
    }

    /// The coefficients land under the keys ORB-SLAM3's `Settings::readCamera1` reads for each
    /// camera type, exactly (the `{:e}` form round-trips an f64).
    #[test]
    fn distortion_is_written_under_the_keys_of_its_camera_type() {
        let value = |text: &str, key: &str| -> String {
            let line = text
                .lines()
                .find(|l| l.starts_with(&format!("{key}:")))
                .unwrap_or_else(|| panic!("no {key} in\n{text}"));
            line[key.len() + 1..].trim().to_string()
        };
        let radtan = Distortion::parse("radtan(-0.28,0.07,0.0002,-0.00003)").unwrap();
        let text = settings(&Intrinsics::TUM, Some(&radtan), 30.0);
        assert_eq!(value(&text, "Camera.type"), "\"PinHole\"");
        for (key, want) in [
            ("k1", -0.28),
            ("k2", 0.07),
            ("p1", 0.0002),
            ("p2", -0.00003),
            ("k3", 0.0),
        ] {
            let got: f64 = value(&text, &format!("Camera1.{key}")).parse().unwrap();
            assert_eq!(got, want, "{key}");
        }
        let fisheye = Distortion::parse("equidistant(0.1,-0.02,0.003,-0.0004)").unwrap();
        let text = settings(&Intrinsics::TUM, Some(&fisheye), 30.0);
        assert_eq!(value(&text, "Camera.type"), "\"KannalaBrandt8\"");
        for (key, want) in [("k1", 0.1), ("k2", -0.02), ("k3", 0.003), ("k4", -0.0004)] {
            let got: f64 = value(&text, &format!("Camera1.{key}")).parse().unwrap();
            assert_eq!(got, want, "{key}");
        }
        assert!(!text.contains("Camera1.p1"), "{text}");
        assert_eq!(value(&text, "Camera1.fx"), "525.000000");
    }
}
