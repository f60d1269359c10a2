//! Dataset files that once slipped through or gave a multi-line error: each is now a one-line
//! error naming the file (regression tests for what fuzzing and review found).

use std::path::Path;

use rslam_core::dataset::{decode_rgb, encode_jpeg, read_dataset, Checksums, DatasetOverrides};
use rslam_core::{CoreError, Intrinsics, RgbImage};

fn tum_overrides() -> DatasetOverrides {
    DatasetOverrides {
        camera: Some(Intrinsics::TUM),
        rate_hz: Some(30.0),
    }
}

fn error_of(root: &Path, overrides: &DatasetOverrides) -> String {
    let message = read_dataset(root, overrides)
        .map(|_| ())
        .map_err(|e: CoreError| e.to_string())
        .expect_err("expected an error");
    assert!(!message.contains('\n'), "one line: {message}");
    message.replace(&root.display().to_string(), "D")
}

#[test]
fn nan_timestamps_in_associations_are_an_error_naming_the_line() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("rgb.txt"), "0 rgb/0.png\n").unwrap();
    std::fs::write(
        dir.path().join("associations.txt"),
        "0 rgb/0.png 0 depth/0.png\nnan rgb/1.png inf depth/1.png\n",
    )
    .unwrap();
    assert_eq!(
        error_of(dir.path(), &tum_overrides()),
        "D/associations.txt:2: expected 't_rgb rgb/<t>.png t_depth depth/<t>.png' with finite timestamps"
    );
}

#[test]
fn an_empty_association_list_is_named_not_rgb_txt() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("rgb.txt"), "0 rgb/0.png\n").unwrap();
    std::fs::write(dir.path().join("associations.txt"), "# nothing\n").unwrap();
    assert_eq!(
        error_of(dir.path(), &tum_overrides()),
        "D/associations.txt: lists no frames"
    );
}

#[test]
fn frame_times_too_close_for_a_finite_rate_are_an_error_naming_the_dataset() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("rgb.txt"),
        "0.000 rgb/0.png
1e-320 rgb/1.png
",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("depth.txt"),
        "0.000 depth/0.png
1e-320 depth/1.png
",
    )
    .unwrap();
    let measured = DatasetOverrides {
        rate_hz: None,
        ..tum_overrides()
    };
    assert_eq!(
        error_of(dir.path(), &measured),
        "D: frame rate inf Hz (given, from rslam.json or from the frame times): expected a positive finite rate"
    );
}

fn replica_with_camera(camera_json: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("results")).unwrap();
    std::fs::write(dir.path().join("results/frame000000.jpg"), b"").unwrap();
    std::fs::write(dir.path().join("cam_params.json"), camera_json).unwrap();
    dir
}

#[test]
fn a_camera_past_the_image_limit_is_refused() {
    let rate = DatasetOverrides {
        camera: None,
        rate_hz: Some(20.0),
    };
    let dir = replica_with_camera(
        r#"{"camera": {"w": 100000, "h": 680, "fx": 600, "fy": 600, "cx": 599.5, "cy": 339.5}}"#,
    );
    assert_eq!(
        error_of(dir.path(), &rate),
        "D/cam_params.json: expected a whole number of pixels from 1 to 16384 at camera.w, got 100000"
    );
    let dir = replica_with_camera(
        r#"{"camera": {"w": 64, "h": 48, "fx": 600, "fy": 1e400, "cx": 31.5, "cy": 23.5}}"#,
    );
    assert!(error_of(dir.path(), &rate).starts_with("D/cam_params.json: not JSON"));
}

#[test]
fn a_manifest_camera_with_a_zero_focal_length_is_refused() {
    let dir = replica_with_camera("{}");
    let manifest = r#"{"tool": "rslam", "tool_version": "0.1.0", "command": [], "source": "room0",
        "source_hash": "", "format": "replica", "rate_hz": 20.0, "frame_count": 1, "seed": 0,
        "camera": {"width": 64, "height": 48, "fx": 0.0, "fy": 50.0, "cx": 31.5, "cy": 23.5},
        "perturbation": "", "perturbation_parsed": null, "severities": [], "rgb_source": [],
        "depth_source": [], "extra": null}"#;
    std::fs::write(dir.path().join("rslam.json"), manifest).unwrap();
    assert_eq!(
        error_of(dir.path(), &DatasetOverrides::default()),
        "D/rslam.json: camera.fx 0: expected a positive finite focal length"
    );
}

#[test]
fn a_checksum_list_naming_files_outside_the_dataset_is_refused() {
    let hex = "0".repeat(64);
    for outside in ["../secret", "/etc/passwd", "results/../../x"] {
        let err = Checksums::parse(Path::new("rslam.b3sum"), &format!("{hex}  {outside}\n"))
            .unwrap_err()
            .to_string();
        assert_eq!(
            err,
            "rslam.b3sum:1: expected a path relative to the dataset, without '..' (b3sum format)"
        );
    }
    assert!(Checksums::parse(
        Path::new("s"),
        &format!("{hex}  ./results/frame000000.jpg\n")
    )
    .is_ok());
}

/// The image decoder's own messages can end in a line break; every cut of a JPEG gives one line.
#[test]
fn every_truncated_jpeg_is_a_one_line_error() {
    let image = RgbImage {
        width: 8,
        height: 4,
        data: (0..96).map(|i| (i * 7) as u8).collect(),
    };
    let jpeg = encode_jpeg(&image, 90).unwrap();
    for cut in 0..jpeg.len() - 1 {
        if let Err(message) = decode_rgb(&jpeg[..cut]) {
            assert!(!message.contains(['\n', '\r']), "cut at {cut}: {message:?}");
        }
    }
}
