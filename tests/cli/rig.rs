//! `rslam render --rig NAME --format euroc`: a stereo-IMU rig written in the EuRoC layout, and
//! the flags' one-line errors.

use crate::harness::Workspace;

const RIG_RENDER: [&str; 11] = [
    "render",
    "--scene",
    "room0",
    "--frames",
    "4",
    "--rig",
    "stereo-imu",
    "--format",
    "euroc",
    "--out",
    "rig",
];

/// The one `error:` line of a failed run (clap adds usage lines after its own).
fn error_line(stderr: &str) -> String {
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "{stderr}");
    errors[0].to_string()
}

#[test]
fn stereo_imu_rig_writes_the_euroc_layout() {
    let ws = Workspace::new();
    let run = ws.rslam(&RIG_RENDER);
    run.success();
    for file in [
        "mav0/cam0/data.csv",
        "mav0/cam1/data.csv",
        "mav0/cam0/sensor.yaml",
        "mav0/cam1/sensor.yaml",
        "mav0/imu0/data.csv",
        "mav0/imu0/sensor.yaml",
        "mav0/state_groundtruth_estimate0/data.csv",
        "rslam.json",
    ] {
        assert!(ws.path("rig").join(file).is_file(), "{file} missing");
    }
    // 4 path poses at 20 Hz: the spline is valid from the second to the third, 2 frames each.
    let stderr = run.stderr();
    assert!(
        stderr.contains("wrote 2 frames from cam0, 2 frames from cam1, 11 IMU samples to rig"),
        "{stderr}"
    );
    let frames = std::fs::read_dir(ws.path("rig/mav0/cam1/data"))
        .unwrap()
        .count();
    assert_eq!(frames, 2);
    let again = ws.rslam(&RIG_RENDER);
    again.success();
    assert!(
        again.stderr().contains("already complete"),
        "{}",
        again.stderr()
    );
}

#[test]
fn rig_flags_fail_with_one_line_errors_naming_the_flag() {
    let ws = Workspace::new();
    let base = ["render", "--scene", "room0", "--frames", "4", "--out", "x"];
    let run = |extra: &[&str]| ws.rslam(&[&base[..], extra].concat());

    let err = run(&["--rig", "stereo-imu"]).fails_with(2, &["--rig", "--format euroc"]);
    assert_eq!(err.lines().count(), 1, "{err}");
    let err = run(&["--rig", "stereo-imu", "--format", "tum"]).fails_with(2, &["--rig"]);
    assert_eq!(err.lines().count(), 1, "{err}");
    let err = run(&["--rig", "bogus", "--format", "euroc"]).fails_with(
        2,
        &["--rig: 'bogus': expected one of rgbd, rgbd-imu, stereo, stereo-imu, a rig file (FILE.toml)"],
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    let err = run(&["--format", "euroc"]).fails_with(2, &["--format euroc", "--rig"]);
    assert_eq!(err.lines().count(), 1, "{err}");
    let err = run(&["--rig", "stereo", "--format", "euroc", "--camera", "tum"]).fails_with(2, &[]);
    let line = error_line(&err);
    assert!(line.contains("--camera") && line.contains("--rig"), "{err}");
    let err = run(&[
        "--rig",
        "stereo",
        "--format",
        "euroc",
        "--perturb",
        "fog:2,misalign:2",
    ])
    .fails_with(2, &[]);
    assert!(
        error_line(&err)
            .contains("--perturb item 'misalign:2': misalign delays depth against colour, and the 'stereo' rig's cameras have no depth stream"),
        "{err}"
    );
    assert!(!ws.path("x").exists());
}

#[test]
fn a_folder_of_other_files_is_refused() {
    let ws = Workspace::new();
    ws.write("rig/notes.txt", "mine");
    let err = ws
        .rslam(&RIG_RENDER)
        .fails_with(2, &["holds no rslam output"]);
    error_line(&err);
    assert_eq!(
        std::fs::read_to_string(ws.path("rig/notes.txt")).unwrap(),
        "mine"
    );
}

/// A killed rig render resumes frame by frame (each camera from its first missing frame) to the
/// bytes of an uninterrupted one: frames, data.csv files, IMU, ground truth and checksums.
#[test]
fn a_killed_rig_render_resumes_to_the_same_bytes() {
    let mut args = RIG_RENDER.to_vec();
    args[4] = "100"; // --frames
    args.extend(["--perturb", "gaussian_noise:2,imu_noise:2"]);
    let whole = Workspace::new();
    whole.rslam(&args).success();
    let killed = Workspace::new();
    crate::resume::kill_mid_run(&killed, &args, "rig", "mav0/cam0/data", "");
    let resumed = killed.rslam(&args);
    resumed.success();
    let said = resumed.stderr();
    let made: usize = said
        .split("resumed rig: ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{said}"));
    // 98 frames per camera; cam0 had more than 40 files on disk when the run was killed, one
    // of them perhaps a frame still being written (under a temporary name)
    assert!(made <= 2 * 98 - 40, "{said}");
    crate::dataset_check::assert_same_tree(&whole.path("rig"), &killed.path("rig"));
}

/// `distortion:radtan` on a EuRoC rig: every camera sees through the lens, and sensor.yaml and
/// ORB-SLAM3's stereo settings state it. A clean pixel (x, y) lands where the radial-tangential
/// model sends it: sampling the lens frame there gives the clean frame back.
#[test]
fn a_stereo_rig_through_a_radtan_lens_states_it_in_every_camera_file() {
    const LENS: [f64; 4] = [-0.28, 0.07, 0.0002, 0.00002];
    let ws = Workspace::new();
    let args = ["--frames", "4", "--rig", "stereo", "--format", "euroc"];
    ws.render_room0("clean", &args, None);
    let item = "distortion:radtan(-0.28,0.07,0.0002,0.00002)";
    ws.render_room0("lens", &args, Some(item));
    let lens = rslam_core::dataset::euroc::read_euroc(&ws.path("lens")).unwrap();
    let clean = rslam_core::dataset::euroc::read_euroc(&ws.path("clean")).unwrap();
    for camera in &lens.cameras {
        assert_eq!(
            camera.camera.distortion.to_array(),
            LENS,
            "{}",
            camera.camera.name
        );
    }
    let settings = std::fs::read_to_string(ws.path("lens/orbslam3_stereo.yaml")).unwrap();
    for key in [
        "Camera1.k1: -0.28",
        "Camera2.k1: -0.28",
        "Camera2.p2: 0.00002",
    ] {
        assert!(settings.contains(key), "{key}:\n{settings}");
    }
    let manifest = crate::dataset_check::manifest(&ws.path("lens"));
    assert_eq!(
        manifest.perturbation_parsed["distortion"]["model"],
        "radtan"
    );

    for (c, l) in clean.cameras.iter().zip(&lens.cameras) {
        let k = c.camera.intrinsics;
        let (sharp, seen) = (
            crate::rig_calibration::grey(&c.frames[0].path),
            crate::rig_calibration::grey(&l.frames[0].path),
        );
        let bilinear = |x: f64, y: f64| -> f64 {
            let (x0, y0) = (x.floor(), y.floor());
            let (fx, fy) = (x - x0, y - y0);
            let at =
                |dx: f64, dy: f64| seen.get_pixel((x0 + dx) as u32, (y0 + dy) as u32)[0] as f64;
            (at(0.0, 0.0) * (1.0 - fx) + at(1.0, 0.0) * fx) * (1.0 - fy)
                + (at(0.0, 1.0) * (1.0 - fx) + at(1.0, 1.0) * fx) * fy
        };
        let (mut through_lens, mut unmoved, mut pixels) = (0.0, 0.0, 0.0);
        for v in (40..k.height - 40).step_by(4) {
            for u in (60..k.width - 60).step_by(4) {
                let (x, y) = ((u as f64 - k.cx) / k.fx, (v as f64 - k.cy) / k.fy);
                let r2 = x * x + y * y;
                let radial = 1.0 + LENS[0] * r2 + LENS[1] * r2 * r2;
                let xd = x * radial + 2.0 * LENS[2] * x * y + LENS[3] * (r2 + 2.0 * x * x);
                let yd = y * radial + LENS[2] * (r2 + 2.0 * y * y) + 2.0 * LENS[3] * x * y;
                let (ud, vd) = (k.fx * xd + k.cx, k.fy * yd + k.cy);
                let clean_value = sharp.get_pixel(u, v)[0] as f64;
                through_lens += (bilinear(ud, vd) - clean_value).abs();
                unmoved += (seen.get_pixel(u, v)[0] as f64 - clean_value).abs();
                pixels += 1.0;
            }
        }
        let (through_lens, unmoved) = (through_lens / pixels, unmoved / pixels);
        assert!(
            through_lens < 3.0 && unmoved > 3.0 * through_lens,
            "{}: {through_lens} grey levels through the model, {unmoved} without",
            c.camera.name
        );
    }
}

/// A killed `rslam perturb --input` of a EuRoC dataset resumes frame by frame to the bytes of an
/// uninterrupted one.
#[test]
fn a_killed_euroc_perturb_resumes_to_the_same_bytes() {
    let ws = Workspace::new();
    let mut render = RIG_RENDER.to_vec();
    render[4] = "100"; // --frames
    render[6] = "stereo"; // --rig
    ws.rslam(&render).success();
    let args = [
        "perturb",
        "--input",
        "rig",
        "--out",
        "noisy",
        "--perturb",
        "gaussian_noise:2",
    ];
    ws.rslam(&args).success();
    std::fs::rename(ws.path("noisy"), ws.path("whole")).unwrap();
    crate::resume::kill_mid_run(&ws, &args, "noisy", "mav0/cam0/data", "");
    let resumed = ws.rslam(&args);
    resumed.success();
    let said = resumed.stderr();
    assert!(said.contains("resumed noisy: "), "{said}");
    crate::dataset_check::assert_same_tree(&ws.path("whole"), &ws.path("noisy"));
}
