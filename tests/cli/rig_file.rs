//! `--rig FILE.toml`: a rig file that states the `stereo-imu` preset renders what the preset
//! renders; moving a camera in the file moves its images; a camera's time offset moves its
//! stamps.

use rslam_core::dataset::euroc::{read_euroc, EurocCamera};
use rslam_pipeline::rig::Rig;

use crate::harness::Workspace;
use crate::rig_calibration::{frames, grey, mean_abs_difference, median_disparity_ratio};

fn numbers(values: &[f64]) -> String {
    let text: Vec<String> = values.iter().map(|v| format!("{v:?}")).collect();
    format!("[{}]", text.join(", "))
}

fn camera_table(camera: &EurocCamera, extra: &str) -> String {
    let k = &camera.intrinsics;
    format!(
        "[[camera]]\nT_BS = {}\nrate_hz = {:?}\nresolution = [{}, {}]\nintrinsics = {}\ncomment = \"{}\"\n{extra}\n",
        numbers(&camera.body_from_camera.to_row_major()),
        camera.rate_hz,
        k.width,
        k.height,
        numbers(&[k.fx, k.fy, k.cx, k.cy]),
        camera.comment,
    )
}

/// The `stereo-imu` preset written out as a rig file, cam1 moved to `cam1` and given `extra`.
fn stereo_imu_file(cam1: &EurocCamera, extra: &str) -> String {
    let preset = Rig::stereo_imu();
    let imu = preset.imu.unwrap();
    format!(
        "{}{}[imu]\nrate_hz = {:?}\ngyroscope_noise_density = {:?}\ngyroscope_random_walk = {:?}\naccelerometer_noise_density = {:?}\naccelerometer_random_walk = {:?}\ncomment = \"{}\"\n",
        camera_table(&preset.cameras[0], ""),
        camera_table(cam1, extra),
        imu.rate_hz,
        imu.gyroscope_noise_density,
        imu.gyroscope_random_walk,
        imu.accelerometer_noise_density,
        imu.accelerometer_random_walk,
        imu.comment,
    )
}

fn render(ws: &Workspace, out: &str, rig: &str) {
    let args = ["--frames", "6", "--rig", rig, "--format", "euroc"];
    ws.render_room0(out, &args, Some("imu_noise:0"));
}

#[test]
fn a_rig_file_renders_what_it_states() {
    let ws = Workspace::new();
    let nominal_cam1 = Rig::stereo_imu().cameras[1].clone();
    ws.write("same.toml", &stereo_imu_file(&nominal_cam1, ""));
    let mut wide = nominal_cam1.clone();
    // cam0 at T_BS(cam0), cam1 0.15 m along cam0's x axis instead of 0.11 m
    let cam0 = Rig::stereo_imu().cameras[0].body_from_camera;
    wide.body_from_camera = cam0.compose(&rslam_core::Pose::new(
        glam::DQuat::IDENTITY,
        glam::DVec3::X * 0.15,
    ));
    ws.write("wide.toml", &stereo_imu_file(&wide, "time_offset_ms = 2.5"));
    render(&ws, "preset", "stereo-imu");
    render(&ws, "same", "same.toml");
    render(&ws, "wide", "wide.toml");
    let (preset, same, wide) = (
        read_euroc(&ws.path("preset")).unwrap(),
        read_euroc(&ws.path("same")).unwrap(),
        read_euroc(&ws.path("wide")).unwrap(),
    );

    // The same rig: the same sensors, stamps, IMU and ground truth; the same images up to the
    // last bit of a pose read back from decimal text.
    for (p, s) in preset.cameras.iter().zip(&same.cameras) {
        assert_eq!(p.camera.intrinsics, s.camera.intrinsics);
        assert!(
            (p.camera.body_from_camera.translation - s.camera.body_from_camera.translation)
                .length()
                < 1e-12
        );
        let stamps = |c: &rslam_core::dataset::euroc::EurocCameraFrames| -> Vec<u64> {
            c.frames.iter().map(|f| f.t_ns).collect()
        };
        assert_eq!(stamps(p), stamps(s));
        for (a, b) in p.frames.iter().zip(&s.frames) {
            let difference = mean_abs_difference(&grey(&a.path), &grey(&b.path));
            assert!(difference < 0.01, "{}: {difference}", a.path.display());
        }
    }
    let (p_imu, s_imu) = (preset.imu.unwrap(), same.imu.unwrap());
    assert_eq!(p_imu.imu, s_imu.imu);
    assert_eq!(p_imu.samples.len(), s_imu.samples.len());
    for (p, s) in p_imu.samples.iter().zip(&s_imu.samples) {
        assert_eq!(p.t_ns, s.t_ns);
        assert!((p.gyro - s.gyro).length() < 1e-9 && (p.accel - s.accel).length() < 1e-9);
    }

    // cam1 moved in the file: its disparity grows by 0.15 / 0.11, cam0 does not change.
    let left = grey(&frames(&ws.path("preset"), "cam0")[0]);
    assert_eq!(left, grey(&frames(&ws.path("wide"), "cam0")[0]));
    let (ratio, pixels) = median_disparity_ratio(
        &left,
        &grey(&frames(&ws.path("preset"), "cam1")[0]),
        &grey(&frames(&ws.path("wide"), "cam1")[0]),
    );
    assert!(pixels > 200, "{pixels}");
    assert!(
        (ratio / (0.15 / 0.11) - 1.0).abs() < 0.02,
        "disparity ratio {ratio}"
    );
    let written = wide.cameras[1].camera.body_from_camera.translation
        - wide.cameras[0].camera.body_from_camera.translation;
    assert!(
        (written.length() - 0.15).abs() < 1e-9,
        "sensor.yaml says where cam1 is"
    );

    // cam1's clock runs 2.5 ms ahead: its stamps are cam0's + 2.5 ms.
    for (c0, c1) in wide.cameras[0].frames.iter().zip(&wide.cameras[1].frames) {
        assert_eq!(c1.t_ns, c0.t_ns + 2_500_000);
    }
}
