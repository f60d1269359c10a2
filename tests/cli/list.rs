use crate::harness::Workspace;

#[test]
fn list_shows_every_group_with_parameters_per_severity() {
    let out = Workspace::new().rslam(&["list"]).success();
    for fragment in [
        "Image corruptions",
        "Depth corruptions",
        "Trajectory deviations",
        "Stream operations",
        "gaussian_noise",
        "σ=0.08 | σ=0.12 | σ=0.18 | σ=0.26 | σ=0.38",
        "depth_range:0.42-10",
        "[0.5, 3.8] m | [0.6, 3.6] m",
        "depth_sensor:kinect",
        "@smooth",
        "misalign:FRAMES[@dynamic]",
        "Sensor effects",
        "exposure:MS[@K]",
        "rolling_shutter:MS",
        "Calibration of a rig",
        "baseline:METRES[@dynamic|@calibration]",
        "[SENSOR:]extrinsic_rot:DEGREES[@dynamic|@calibration]",
        "[SENSOR:]extrinsic_trans:METRES[@dynamic|@calibration]",
        "IMU items",
        "imu_noise:K",
        "imu_bias_step:GYRO/ACC",
        "imu_saturation:GYRO/ACC",
        "imu_drop:P | imu_drop:P/L",
        "imu_jitter:MS",
        "cam_imu_offset:MS",
        "distortion:radtan(k1,k2,p1,p2) | distortion:equidistant(k1,k2,k3,k4)",
    ] {
        assert!(out.contains(fragment), "list lacks '{fragment}':\n{out}");
    }
    // Every item is shown under a heading.
    let json = Workspace::new().rslam(&["list", "--json"]).success();
    let entries: Vec<serde_json::Value> = serde_json::from_str(&json).unwrap();
    for entry in &entries {
        let name = entry["name"].as_str().unwrap();
        assert!(out.contains(&format!("  {name} ")), "list lacks {name}");
    }
}

#[test]
fn list_json_has_one_object_per_perturbation() {
    let out = Workspace::new().rslam(&["list", "--json"]).success();
    let entries: Vec<serde_json::Value> = serde_json::from_str(&out).expect("valid JSON");
    let names: Vec<&str> = entries.iter().filter_map(|e| e["name"].as_str()).collect();
    for name in [
        "gaussian_noise",
        "contrast",
        "pixelate",
        "depth_noise",
        "depth_edge_erosion",
        "depth_sensor",
        "rot",
        "trans",
        "fast",
        "misalign",
        "exposure",
        "rolling_shutter",
        "imu_noise",
        "cam_imu_offset",
    ] {
        assert_eq!(
            names.iter().filter(|&&n| n == name).count(),
            1,
            "{name} in {names:?}"
        );
    }
    let contrast = entries
        .iter()
        .find(|e| e["name"] == "contrast")
        .expect("contrast");
    assert_eq!(contrast["group"], "image");
    assert_eq!(contrast["parameters"].as_array().map(|p| p.len()), Some(5));
    assert_eq!(contrast["parameters"][4], "c=0.05");
}

/// The book's generated reference pages are what the binary prints now: a new item, parameter or
/// flag that is not in the checked-in page fails here. `RSLAM_BOOK=write` writes them anew.
#[test]
fn the_books_generated_reference_pages_match_the_binary() {
    let docs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/src/reference");
    let ws = Workspace::new();
    let mut stale = Vec::new();
    for (page, args) in [
        ("catalogue.md", &["list", "--markdown"][..]),
        ("cli.md", &["--markdown-help"][..]),
    ] {
        let printed = ws.rslam(args).success();
        let path = docs.join(page);
        if std::env::var("RSLAM_BOOK").as_deref() == Ok("write") {
            std::fs::write(&path, &printed).unwrap();
        }
        let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
        if checked_in != printed {
            stale.push(format!(
                "docs/src/reference/{page} differs from `rslam {}`; run RSLAM_BOOK=write cargo test -p rslam-cli --test cli generated_reference",
                args.join(" ")
            ));
        }
    }
    assert!(stale.is_empty(), "{}", stale.join("\n"));
}

#[test]
fn the_catalogue_page_has_every_item_with_its_severities() {
    let page = Workspace::new().rslam(&["list", "--markdown"]).success();
    let json = Workspace::new().rslam(&["list", "--json"]).success();
    let entries: Vec<serde_json::Value> = serde_json::from_str(&json).unwrap();
    assert!(entries.len() > 40, "{} items", entries.len());
    for entry in entries {
        let name = entry["name"].as_str().unwrap();
        assert!(page.contains(&format!("### `{name}`")), "{name} missing");
        for parameter in entry["parameters"].as_array().unwrap() {
            let cell = parameter.as_str().unwrap().replace('|', "\\|");
            assert!(page.contains(&format!("| {cell} |")), "{name}: {cell}");
        }
    }
}

/// A reader that has gone (`rslam list | head -1` once head has its line) ends rslam as it ends
/// `cat`, by SIGPIPE, without a panic message.
#[cfg(unix)]
#[test]
fn a_closed_stdout_ends_rslam_without_a_panic() {
    use std::os::unix::process::ExitStatusExt;
    let (reader, writer) = std::io::pipe().expect("pipe");
    drop(reader);
    let output = std::process::Command::new(env!("CARGO_BIN_EXE_rslam"))
        .args(["list", "--json"])
        .stdout(writer)
        .output()
        .expect("spawn rslam");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(
        output.status.signal(),
        Some(13),
        "{:?}: {stderr}",
        output.status
    );
    assert!(stderr.is_empty(), "{stderr}");
}
