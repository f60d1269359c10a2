//! The dataset writer's output read back by the project's own reader, for both layouts, and the
//! malformed inputs a user meets: each is a one-line error naming the file (and line).

use std::path::Path;

use glam::{DQuat, DVec3};
use rslam_core::dataset::{
    read_dataset, read_rgb, DatasetFormat, DatasetOverrides, DatasetWriter, DepthPng, Manifest,
    OutputFrame,
};
use rslam_core::{DepthImage, Distortion, Intrinsics, Pose, RgbImage, Trajectory};

const CAMERA: Intrinsics = Intrinsics {
    width: 8,
    height: 6,
    fx: 7.0,
    fy: 7.5,
    cx: 3.5,
    cy: 2.5,
};
const RATE_HZ: f64 = 20.0;
const FRAMES: usize = 5;
/// Output frame j carries the depth captured with frame j − 1 (as under `misalign:1`).
const DEPTH_LAG: usize = 1;

fn frames() -> Vec<OutputFrame> {
    (0..FRAMES)
        .map(|j| OutputFrame {
            rgb_time: 100.0 + j as f64 / RATE_HZ,
            depth_time: 100.0 + j.saturating_sub(DEPTH_LAG) as f64 / RATE_HZ,
        })
        .collect()
}

fn poses() -> Vec<Pose> {
    (0..FRAMES)
        .map(|j| {
            Pose::new(
                DQuat::from_rotation_z(0.1 * j as f64),
                DVec3::new(j as f64 * 0.01, 0.5, 1.25),
            )
        })
        .collect()
}

fn depth_of(j: usize) -> DepthImage {
    let mut depth = DepthImage::new(CAMERA.width, CAMERA.height);
    for (i, z) in depth.data.iter_mut().enumerate() {
        *z = 0.5 + j as f32 + 0.01 * i as f32;
    }
    depth
}

fn manifest(format: DatasetFormat, depth_png: DepthPng) -> Manifest {
    Manifest {
        tool: "rslam".into(),
        tool_version: "test".into(),
        command: vec!["test".into()],
        source: "test".into(),
        source_hash: String::new(),
        format: Some(format),
        camera: Some(CAMERA),
        distortion: None,
        depth_png,
        bag: Default::default(),
        rate_hz: RATE_HZ,
        frame_count: FRAMES,
        seed: 0,
        perturbation: String::new(),
        perturbation_parsed: serde_json::Value::Null,
        severities: Vec::new(),
        rgb_source: (0..FRAMES).collect(),
        depth_source: (0..FRAMES).map(|j| j.saturating_sub(DEPTH_LAG)).collect(),
        extra: serde_json::Value::Null,
        content_digest: String::new(),
    }
}

fn write(root: &Path, format: DatasetFormat) {
    write_encoded(root, format, DepthPng::Fast);
}

fn write_encoded(root: &Path, format: DatasetFormat, depth_png: DepthPng) {
    write_through(root, format, depth_png, None);
}

fn write_through(
    root: &Path,
    format: DatasetFormat,
    depth_png: DepthPng,
    distortion: Option<Distortion>,
) {
    let writer = DatasetWriter::open(root, format, CAMERA, depth_png)
        .unwrap()
        .with_distortion(distortion);
    let frames = frames();
    for (j, frame) in frames.iter().enumerate() {
        let mut color = RgbImage::new(CAMERA.width, CAMERA.height);
        color.data.fill(40 * j as u8);
        writer.write_rgb(j, frame, &color).unwrap();
        let outputs: Vec<(usize, OutputFrame)> = (0..FRAMES)
            .filter(|&k| k.saturating_sub(DEPTH_LAG) == j)
            .map(|k| (k, frames[k]))
            .collect();
        if !outputs.is_empty() {
            writer.write_depth(&outputs, &depth_of(j)).unwrap();
        }
    }
    let gt = Trajectory::new(frames.iter().map(|f| f.rgb_time).collect(), poses());
    let manifest = Manifest {
        distortion,
        ..manifest(format, depth_png)
    };
    writer.finish(&frames, &gt, manifest).unwrap();
}

fn assert_poses_close(a: &[Pose], b: &[Pose], tolerance: f64) {
    assert_eq!(a.len(), b.len());
    for (i, (p, q)) in a.iter().zip(b).enumerate() {
        let dt = (p.translation - q.translation).length();
        let dr = p.rotation.angle_between(q.rotation);
        assert!(dt < tolerance && dr < tolerance, "pose {i}: {p:?} vs {q:?}");
    }
}

#[test]
fn both_layouts_read_back_what_was_written() {
    for format in [DatasetFormat::Replica, DatasetFormat::Tum] {
        let dir = tempfile::tempdir().unwrap();
        write(dir.path(), format);
        let back = read_dataset(dir.path(), &DatasetOverrides::default()).unwrap();
        assert_eq!(back.format, format);
        assert_eq!(back.intrinsics, CAMERA, "{format}");
        assert_eq!(back.rate_hz, RATE_HZ, "{format}");
        assert_eq!(back.frames.len(), FRAMES, "{format}");
        let written = frames();
        for (j, frame) in back.frames.iter().enumerate() {
            // Replica frames carry no timestamps: frame j is j / rate from 0.
            let expected_rgb = if format == DatasetFormat::Replica {
                j as f64 / RATE_HZ
            } else {
                written[j].rgb_time
            };
            assert!(
                (frame.rgb_time - expected_rgb).abs() < 1e-6,
                "{format} frame {j}"
            );
            let depth_path = frame.depth.as_ref().expect("every frame has depth");
            let depth =
                rslam_core::dataset::decode_depth_png(depth_path, format.depth_scale()).unwrap();
            let source = j.saturating_sub(DEPTH_LAG);
            let step = 0.5 / format.depth_scale() as f32 + 1e-6;
            for (got, want) in depth.data.iter().zip(&depth_of(source).data) {
                assert!(
                    (got - want).abs() <= step,
                    "{format} frame {j}: {got} vs {want}"
                );
            }
            if format == DatasetFormat::Tum {
                assert!((frame.depth_time - written[j].depth_time).abs() < 1e-6);
            }
            let color = read_rgb(&frame.rgb).unwrap();
            assert!(
                color.data.iter().all(|&v| v.abs_diff(40 * j as u8) <= 1),
                "{format} {j}"
            );
        }
        let gt = back.ground_truth.expect("ground truth");
        assert_poses_close(&gt.poses, &poses(), 1e-6);
        if format == DatasetFormat::Tum {
            for (t, f) in gt.timestamps.iter().zip(&written) {
                assert!((t - f.rgb_time).abs() < 1e-6);
            }
        }
    }
}

/// A lens goes into cam_params.json in OpenCV's coefficient order, exactly, and reads back from
/// the manifest or, without one, from cam_params.json; a dataset without one keeps the plain
/// Replica file.
#[test]
fn cam_params_carry_the_lens() {
    let camera_json = |root: &Path| -> serde_json::Value {
        let text = std::fs::read_to_string(root.join("cam_params.json")).unwrap();
        serde_json::from_str::<serde_json::Value>(&text).unwrap()["camera"].clone()
    };
    for (text, model) in [
        ("radtan(-0.28,0.07,0.0002,-0.00003)", "radtan"),
        ("equidistant(0.1,-0.02,0.003,-0.0004)", "equidistant"),
    ] {
        let lens = Distortion::parse(text).unwrap();
        let dir = tempfile::tempdir().unwrap();
        write_through(
            dir.path(),
            DatasetFormat::Replica,
            DepthPng::Fast,
            Some(lens),
        );
        let camera = camera_json(dir.path());
        assert_eq!(camera["distortion_model"], model);
        let written: Vec<f64> = serde_json::from_value(camera["distortion"].clone()).unwrap();
        assert_eq!(written, lens.coefficients());
        assert_eq!(camera["fx"], CAMERA.fx);
        let rate = DatasetOverrides {
            rate_hz: Some(RATE_HZ),
            ..DatasetOverrides::default()
        };
        assert_eq!(
            read_dataset(dir.path(), &rate).unwrap().distortion,
            Some(lens)
        );
        std::fs::remove_file(dir.path().join("rslam.json")).unwrap();
        assert_eq!(
            read_dataset(dir.path(), &rate).unwrap().distortion,
            Some(lens)
        );
    }
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), DatasetFormat::Replica);
    let camera = camera_json(dir.path());
    assert!(camera.get("distortion").is_none() && camera.get("distortion_model").is_none());
    let manifest = std::fs::read_to_string(dir.path().join("rslam.json")).unwrap();
    assert!(!manifest.contains("distortion"), "{manifest}");
}

#[test]
fn small_depth_pngs_read_back_as_the_samples_fast_ones_hold() {
    for format in [DatasetFormat::Replica, DatasetFormat::Tum] {
        let (fast, small) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
        write_encoded(fast.path(), format, DepthPng::Fast);
        write_encoded(small.path(), format, DepthPng::Small);
        assert_eq!(
            Manifest::read(small.path()).unwrap().depth_png,
            DepthPng::Small
        );
        let none = DatasetOverrides::default();
        let (fast, small) = (
            read_dataset(fast.path(), &none).unwrap(),
            read_dataset(small.path(), &none).unwrap(),
        );
        assert_eq!(small.frames.len(), FRAMES, "{format}");
        for (a, b) in fast.frames.iter().zip(&small.frames) {
            let depth = |frame: &rslam_core::dataset::DatasetFrame| {
                let path = frame.depth.as_ref().expect("every frame has depth");
                rslam_core::dataset::decode_depth_png(path, format.depth_scale()).unwrap()
            };
            assert_eq!(depth(a), depth(b), "{format}");
        }
    }
}

/// Asserts `read_dataset` fails with one line that contains every fragment.
fn assert_one_line_error(root: &Path, overrides: &DatasetOverrides, fragments: &[&str]) {
    let message = match read_dataset(root, overrides) {
        Ok(_) => panic!("{}: read without error", root.display()),
        Err(e) => e.to_string(),
    };
    assert!(!message.contains('\n'), "not one line: {message}");
    for f in fragments {
        assert!(message.contains(f), "'{message}' lacks '{f}'");
    }
}

#[test]
fn malformed_datasets_are_one_line_errors_naming_the_file() {
    let none = DatasetOverrides::default();

    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), DatasetFormat::Tum);
    let associations = dir.path().join("associations.txt");
    let mut text = std::fs::read_to_string(&associations).unwrap();
    text = text.replacen("\n", "\n100.05 rgb/x.png\n", 1);
    std::fs::write(&associations, text).unwrap();
    assert_one_line_error(dir.path(), &none, &["associations.txt:2:"]);

    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), DatasetFormat::Replica);
    std::fs::remove_file(dir.path().join("results/depth000002.png")).unwrap();
    assert_one_line_error(
        dir.path(),
        &none,
        &["results", "5 colour frames but 4 depth"],
    );

    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), DatasetFormat::Replica);
    std::fs::remove_file(dir.path().join("rslam.json")).unwrap();
    let cam = dir.path().join("cam_params.json");
    std::fs::write(
        &cam,
        r#"{"camera": {"w": 8, "h": 6, "fx": "seven", "fy": 7, "cx": 3.5, "cy": 2.5}}"#,
    )
    .unwrap();
    let with_rate = DatasetOverrides {
        rate_hz: Some(20.0),
        ..DatasetOverrides::default()
    };
    assert_one_line_error(dir.path(), &with_rate, &["cam_params.json", "camera.fx"]);
    std::fs::write(
        &cam,
        r#"{"camera": {"w": 8.5, "h": 6, "fx": 7, "fy": 7, "cx": 3.5, "cy": 2.5}}"#,
    )
    .unwrap();
    assert_one_line_error(dir.path(), &with_rate, &["cam_params.json", "camera.w"]);
    for lens in [
        r#""distortion_model": "radtan", "distortion": [0.1, 0.2, 0.3]"#,
        r#""distortion_model": "fisheye", "distortion": [0.1, 0.2, 0.3, 0.4]"#,
        r#""distortion": [0.1, 0.2, 0.3, 0.4]"#,
    ] {
        let text = format!(
            r#"{{"camera": {{"w": 8, "h": 6, "fx": 7, "fy": 7, "cx": 3.5, "cy": 2.5, {lens}}}}}"#
        );
        std::fs::write(&cam, text).unwrap();
        assert_one_line_error(
            dir.path(),
            &with_rate,
            &["cam_params.json", "distortion_model"],
        );
    }

    let rgb = dir.path().join("results/frame000002.jpg");
    std::fs::write(&rgb, b"\xff\xd8 not a jpeg").unwrap();
    let message = read_rgb(&rgb).unwrap_err().to_string();
    assert!(
        message.contains("frame000002.jpg") && !message.contains('\n'),
        "{message}"
    );
}

#[test]
fn camera_and_rate_are_never_guessed() {
    let none = DatasetOverrides::default();
    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), DatasetFormat::Tum);
    std::fs::remove_file(dir.path().join("rslam.json")).unwrap();
    assert_one_line_error(dir.path(), &none, &["no camera intrinsics", "--camera"]);
    let given = DatasetOverrides {
        camera: Some(Intrinsics::TUM),
        ..DatasetOverrides::default()
    };
    let back = read_dataset(dir.path(), &given).unwrap();
    assert_eq!(back.intrinsics, Intrinsics::TUM);
    assert!(
        (back.rate_hz - RATE_HZ).abs() < 1e-6,
        "measured from the timestamps"
    );

    let dir = tempfile::tempdir().unwrap();
    write(dir.path(), DatasetFormat::Replica);
    std::fs::remove_file(dir.path().join("rslam.json")).unwrap();
    assert_one_line_error(dir.path(), &none, &["unknown frame rate", "--rate"]);
    let with_rate = DatasetOverrides {
        rate_hz: Some(30.0),
        ..DatasetOverrides::default()
    };
    let back = read_dataset(dir.path(), &with_rate).unwrap();
    assert_eq!(back.intrinsics, CAMERA, "from cam_params.json");
    assert_eq!(back.frames[3].rgb_time, 0.1);
    std::fs::remove_file(dir.path().join("cam_params.json")).unwrap();
    assert_one_line_error(
        dir.path(),
        &with_rate,
        &["no camera intrinsics", "cam_params.json"],
    );
}
