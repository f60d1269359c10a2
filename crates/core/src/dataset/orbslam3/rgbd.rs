//! ORB-SLAM3 v1.0 RGB-D settings for a camera, with every key its loader and viewer read.

use crate::Intrinsics;

/// `orbslam3.yaml` of the TUM layout: the camera without distortion, depth in 1/5000 m.
pub fn settings(k: &Intrinsics, rate_hz: f64) -> String {
    format!(
        r#"%YAML:1.0
# ORB-SLAM3 RGB-D settings written by rslam for this dataset's camera (no distortion).
File.version: "1.0"

Camera.type: "PinHole"
Camera1.fx: {fx:.6}
Camera1.fy: {fy:.6}
Camera1.cx: {cx:.6}
Camera1.cy: {cy:.6}
Camera1.k1: 0.0
Camera1.k2: 0.0
Camera1.p1: 0.0
Camera1.p2: 0.0
Camera1.k3: 0.0
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
        assert_eq!(settings(&Intrinsics::REPLICA, 20.0), REPLICA_20_HZ);
        // FNV-1a 64 of the TUM preset's file, taken before the stereo settings were added.
        let tum = settings(&Intrinsics::TUM, 30.0);
        assert_eq!(fnv1a64(tum.as_bytes()), 0x8eb1_f531_8bd5_b75d, "{tum}");
    }
}
