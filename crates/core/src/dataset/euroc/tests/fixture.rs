//! A small two-camera + IMU + ground-truth dataset, written by [`EurocWriter`].

use std::path::Path;

use glam::{DQuat, DVec3};

use crate::dataset::euroc::{
    CameraColour, EurocCamera, EurocImu, EurocWriter, GroundTruthState, ImuSample, RadialTangential,
};
use crate::dataset::Manifest;
use crate::{Intrinsics, Pose, RgbImage};

pub const FRAMES: usize = 3;
pub const IMU_ROWS: usize = 10;
/// Start of the sequence, seconds (EuRoC's are Unix times).
pub const START_S: f64 = 1_403_636_579.0;
pub const CAMERA_RATE_HZ: f64 = 20.0;
pub const START_NS: u64 = 1_403_636_579_000_000_000;

/// A rotation with every quaternion component non-zero and w far from 1.
pub fn tilted() -> DQuat {
    DQuat::from_euler(glam::EulerRot::ZYX, 0.9, -0.4, 1.3)
}

pub fn cameras() -> Vec<EurocCamera> {
    let intrinsics = Intrinsics {
        width: 6,
        height: 4,
        fx: 458.654,
        fy: 457.296,
        cx: 2.5,
        cy: 1.5,
    };
    vec![
        EurocCamera {
            name: "cam0".into(),
            comment: "rslam left".into(),
            body_from_camera: Pose::new(
                tilted(),
                DVec3::new(-0.0216401454975, -0.064676986768, 0.00981073058949),
            ),
            rate_hz: CAMERA_RATE_HZ,
            intrinsics,
            distortion: RadialTangential {
                k1: -0.28340811,
                k2: 0.07395907,
                p1: 0.00019359,
                p2: 1.76187114e-05,
            },
            colour: CameraColour::Grey,
        },
        EurocCamera {
            name: "cam1".into(),
            comment: "rslam right".into(),
            body_from_camera: Pose::new(
                DQuat::from_rotation_z(-1.5),
                DVec3::new(0.09, -0.06, 0.01),
            ),
            rate_hz: CAMERA_RATE_HZ,
            intrinsics,
            distortion: RadialTangential::NONE,
            colour: CameraColour::Rgb,
        },
    ]
}

pub fn imu() -> EurocImu {
    EurocImu::adis16448()
}

pub fn image(seed: usize) -> RgbImage {
    let mut image = RgbImage::new(6, 4);
    for (i, v) in image.data.iter_mut().enumerate() {
        *v = ((i * 37 + seed * 91) % 256) as u8;
    }
    image
}

pub fn imu_samples() -> Vec<ImuSample> {
    (0..IMU_ROWS)
        .map(|i| ImuSample {
            t_ns: START_NS + i as u64 * 5_000_000,
            gyro: DVec3::new(
                -0.099_134_701_513_277_9,
                0.14730578886832138 + i as f64 * 1e-3,
                0.027,
            ),
            accel: DVec3::new(
                8.147_691_708_333_333,
                -0.375_921_583_333_333_3,
                -2.402_629_25 - i as f64 / 3.0,
            ),
        })
        .collect()
}

pub fn ground_truth() -> Vec<GroundTruthState> {
    (0..IMU_ROWS)
        .map(|i| GroundTruthState {
            t_ns: START_NS + i as u64 * 5_000_000,
            world_from_body: Pose::new(
                tilted() * DQuat::from_rotation_x(i as f64 * 0.01),
                DVec3::new(4.688319 + i as f64 * 1e-3, -1.786938, 0.783338),
            ),
            velocity: DVec3::new(-0.027876, 0.033207, 0.800006),
            gyro_bias: DVec3::new(-0.003172, 0.021267, 0.078502),
            accel_bias: DVec3::new(-0.025266, 0.136696, 0.075593),
        })
        .collect()
}

pub fn manifest() -> Manifest {
    Manifest {
        tool: "rslam".into(),
        tool_version: "test".into(),
        command: vec!["test".into()],
        source: "test".into(),
        source_hash: String::new(),
        format: None,
        camera: None,
        distortion: None,
        depth_png: Default::default(),
        bag: Default::default(),
        rate_hz: CAMERA_RATE_HZ,
        frame_count: FRAMES,
        seed: 0,
        perturbation: String::new(),
        perturbation_parsed: serde_json::Value::Null,
        severities: Vec::new(),
        rgb_source: Vec::new(),
        depth_source: Vec::new(),
        extra: serde_json::Value::Null,
        content_digest: String::new(),
    }
}

/// Frame `j` of each camera at `START_S + j / 20 Hz`; returns each frame's written `t_ns`.
pub fn write(root: &Path) -> Vec<u64> {
    let writer = EurocWriter::open(root, cameras(), Some(imu())).unwrap();
    let mut times = Vec::new();
    for j in 0..FRAMES {
        let t = START_S + j as f64 / CAMERA_RATE_HZ;
        let t0 = writer.write_frame(0, t, &image(2 * j)).unwrap();
        let t1 = writer.write_frame(1, t, &image(2 * j + 1)).unwrap();
        assert_eq!(t0, t1);
        times.push(t0);
    }
    // In two batches, as a renderer hands them over.
    let samples = imu_samples();
    writer.write_imu(&samples[..4]).unwrap();
    writer.write_imu(&samples[4..]).unwrap();
    writer.write_ground_truth(&ground_truth()).unwrap();
    writer.finish(manifest()).unwrap();
    times
}
