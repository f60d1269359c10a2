//! What rslam writes, it reads back as it was: trajectories (TUM, Replica), checksum lists,
//! manifests, suite files, exported meshes; for any content the writers accept.

use std::path::Path;

use glam::{DQuat, DVec3};
use proptest::collection::vec;
use proptest::prelude::*;
use rslam_core::dataset::{Checksums, Manifest};
use rslam_core::mesh_io::parse_ply;
use rslam_core::trajectory_io::{read_trajectory, write_replica, write_tum, TrajectoryFormat};
use rslam_core::{Intrinsics, Pose, Trajectory};
use rslam_render::scene::export::ply_bytes;
use rslam_render::{Mesh, Scene, Texture, Vertex};
use rslam_suite::{SequenceFields, SuiteFile};

/// Poses read back from text: the quaternion is normalised again, so it may move by an ulp or
/// two, and the Replica matrix goes through a quaternion-to-matrix conversion and back.
const POSE_TOLERANCE: f64 = 1e-12;

fn pose() -> impl Strategy<Value = Pose> {
    (vec(-1.0f64..1.0, 4), vec(-1e3f64..1e3, 3)).prop_filter_map("a rotation", |(q, t)| {
        let q = DQuat::from_xyzw(q[0], q[1], q[2], q[3]);
        (q.length() > 1e-3).then(|| Pose::new(q, DVec3::new(t[0], t[1], t[2])))
    })
}

fn assert_poses_close(a: &[Pose], b: &[Pose]) -> Result<(), TestCaseError> {
    prop_assert_eq!(a.len(), b.len());
    for (i, (a, b)) in a.iter().zip(b).enumerate() {
        let same_rotation = a.rotation.dot(b.rotation).abs() > 1.0 - POSE_TOLERANCE;
        let translation = (a.translation - b.translation).length();
        prop_assert!(
            same_rotation && translation <= POSE_TOLERANCE * (1.0 + a.translation.length()),
            "pose {}: {:?} read back as {:?}",
            i,
            a,
            b
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig { failure_persistence: None, ..ProptestConfig::default() })]

    /// TUM keeps microsecond timestamps (whole microseconds here) and every pose.
    #[test]
    fn tum_trajectories_read_back(
        poses in vec(pose(), 1..20),
        start_us in 0u64..4_000_000_000_000_000,
    ) {
        let timestamps = (0..poses.len() as u64)
            .map(|i| (start_us + 33_333 * i) as f64 / 1e6)
            .collect();
        let written = Trajectory::new(timestamps, poses);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("groundtruth.txt");
        write_tum(&path, &written).unwrap();
        let read = read_trajectory(&path, None).unwrap();
        prop_assert_eq!(read.format, TrajectoryFormat::Tum);
        for (a, b) in written.timestamps.iter().zip(&read.trajectory.timestamps) {
            prop_assert!((a - b).abs() <= 1e-6 * 0.5 + a.abs() * f64::EPSILON, "{} read as {}", a, b);
        }
        assert_poses_close(&written.poses, &read.trajectory.poses)?;
    }

    #[test]
    fn replica_trajectories_read_back(poses in vec(pose(), 1..20)) {
        let written = Trajectory::from_poses_at_rate(poses, 20.0);
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("traj.txt");
        write_replica(&path, &written).unwrap();
        let read = read_trajectory(&path, None).unwrap();
        prop_assert_eq!(read.format, TrajectoryFormat::Replica);
        prop_assert_eq!(&read.trajectory.timestamps, &written.timestamps);
        assert_poses_close(&written.poses, &read.trajectory.poses)?;
    }

    /// Any relative file names (of the characters file names take) and hashes.
    #[test]
    fn checksum_lists_read_back(entries in vec(("[a-z0-9_.-]{1,12}(/[a-z0-9_-]{1,12}){0,2}", "[0-9a-f]{64}"), 0..20)) {
        let mut sums = Checksums::default();
        for (name, hex) in entries.into_iter().filter(|(name, _)| !name.split('/').any(|c| c == ".." || c == ".")) {
            sums.insert(name, hex);
        }
        let read = Checksums::parse(Path::new("rslam.b3sum"), &sums.text()).unwrap();
        prop_assert_eq!(read, sums);
    }

    #[test]
    fn manifests_read_back(
        command in vec(".*", 0..6),
        perturbation in ".*",
        rate_hz in 0.001f64..1000.0,
        seed in any::<u64>(),
        width in 1u32..=16384,
        height in 1u32..=16384,
        focal in 0.001f64..1e5,
    ) {
        let manifest: Manifest = serde_json::from_value(serde_json::json!({
            "tool": "rslam", "tool_version": "0.1.0", "command": command, "source": "room0",
            "source_hash": "", "format": "tum", "rate_hz": rate_hz, "frame_count": 3, "seed": seed,
            "camera": Intrinsics { width, height, fx: focal, fy: focal, cx: 0.5, cy: -0.5 },
            "perturbation": perturbation, "perturbation_parsed": null, "severities": [],
            "rgb_source": [0, 1, 2], "depth_source": [0, 0, 1], "extra": {"adapter": "lavapipe"}
        })).unwrap();
        let dir = tempfile::tempdir().unwrap();
        manifest.write(dir.path()).unwrap();
        prop_assert_eq!(Manifest::read(dir.path()).unwrap(), manifest);
    }

    #[test]
    fn suite_files_read_back(
        seed in any::<u64>(),
        rows in vec(("[a-z0-9]{1,8}__[a-z0-9-]{1,8}", proptest::option::of(".*"), proptest::option::of(1usize..100_000), proptest::option::of(0.5f64..100.0)), 0..8),
        frames in proptest::option::of(1usize..1000),
    ) {
        let file = SuiteFile {
            seed,
            defaults: SequenceFields { frames, ..SequenceFields::default() },
            sequences: rows
                .into_iter()
                .map(|(name, perturb, frames, rate)| {
                    toml::Spanned::new(0..0, SequenceFields {
                        name: Some(name),
                        scene: Some("room0".into()),
                        perturb,
                        frames,
                        rate,
                        ..SequenceFields::default()
                    })
                })
                .collect(),
        };
        let text = file.to_text("written by a property test").unwrap();
        let read = SuiteFile::parse(Path::new("suite.toml"), &text).unwrap();
        prop_assert_eq!(read.seed, file.seed);
        prop_assert_eq!(&read.defaults, &file.defaults);
        let rows = |f: &SuiteFile| f.sequences.iter().map(|r| r.get_ref().clone()).collect::<Vec<_>>();
        prop_assert_eq!(rows(&read), rows(&file));
    }

    /// The exported ground-truth mesh reads back with its positions and triangles, whatever the
    /// scene is called (its name goes into a header comment).
    #[test]
    fn exported_meshes_read_back(
        name in prop_oneof![Just("end_header".to_string()), ".*"],
        positions in vec(vec(-1e4f32..1e4, 3), 3..30),
        triangles in vec(vec(any::<u32>(), 3), 0..30),
    ) {
        let count = positions.len() as u32;
        let vertices: Vec<Vertex> = positions
            .iter()
            .map(|p| Vertex { position: [p[0], p[1], p[2]], uv: [0.0; 2], color: [10, 20, 30, 255], layer: 0 })
            .collect();
        let indices: Vec<u32> = triangles.iter().flatten().map(|i| i % count).collect();
        let scene = Scene {
            name,
            mesh: Mesh { vertices, indices: indices.clone() },
            textures: vec![Texture::white()],
            default_trajectory: None,
            splats: None,
            floor: None,
            lights: None,
        };
        let read = parse_ply(&ply_bytes(&scene)).map_err(TestCaseError::fail)?;
        let written: Vec<[f32; 3]> = scene.mesh.vertices.iter().map(|v| v.position).collect();
        prop_assert_eq!(read.positions, written);
        prop_assert_eq!(read.indices, indices);
    }
}
