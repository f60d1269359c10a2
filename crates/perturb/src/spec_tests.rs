use super::*;

fn err(text: &str) -> String {
    PerturbSpec::parse(text).unwrap_err().to_string()
}

#[test]
fn parses_every_item_kind_into_its_group() {
    let spec = PerturbSpec::parse(
        "gaussian_noise:2,depth_missing:5,rot:1,trans:0.025@smooth,fast:2,misalign:10@dynamic,brightness:high@dynamic,depth_range:0.42-10",
    )
    .unwrap();
    let names: Vec<&str> = spec.image.iter().map(|i| i.name.as_str()).collect();
    assert_eq!(names, ["gaussian_noise", "brightness"]);
    assert_eq!(
        spec.image[1].level,
        Level::Severity {
            severity: 5,
            dynamic: true
        }
    );
    assert_eq!(
        spec.depth[0].level,
        Level::Severity {
            severity: 5,
            dynamic: false
        }
    );
    assert_eq!(
        spec.depth[1].level,
        Level::Explicit {
            values: vec![0.42, 10.0]
        }
    );
    assert_eq!(
        spec.rotation,
        Some(Deviation {
            sigma: 1.0,
            smooth: false
        })
    );
    assert_eq!(
        spec.translation,
        Some(Deviation {
            sigma: 0.025,
            smooth: true
        })
    );
    assert_eq!(spec.fast, Some(2));
    assert_eq!(
        spec.misalign,
        Some(Misalign {
            frames: 10,
            dynamic: true
        })
    );
    assert!(spec.needs_scene());
}

#[test]
fn aliases_map_to_severities() {
    for (alias, severity) in [("low", 1), ("mid", 3), ("high", 5), ("4", 4)] {
        let spec = PerturbSpec::parse(&format!("contrast:{alias}")).unwrap();
        assert_eq!(
            spec.image[0].level,
            Level::Severity {
                severity,
                dynamic: false
            }
        );
    }
}

#[test]
fn display_is_canonical_and_round_trips() {
    let spec = PerturbSpec::parse(
        " misalign:5 , depth_range:0.42-10,pixelate:mid@static,rot:3@smooth,gaussian_noise:1@dynamic,fast:4,trans:0.05",
    )
    .unwrap();
    let text = spec.to_string();
    assert_eq!(
        text,
        "rot:3@smooth,trans:0.05,pixelate:3,gaussian_noise:1@dynamic,depth_range:0.42-10,fast:4,misalign:5"
    );
    assert_eq!(PerturbSpec::parse(&text).unwrap(), spec);
    let json = serde_json::to_string(&spec).unwrap();
    assert_eq!(serde_json::from_str::<PerturbSpec>(&json).unwrap(), spec);
}

#[test]
fn bad_items_are_named_with_the_valid_choices() {
    let e = err("fgo:3");
    assert!(
        e.contains("'fgo:3'") && e.contains("gaussian_noise") && e.contains("misalign"),
        "{e}"
    );
    let e = err("brightness:6");
    assert!(
        e.contains("'brightness:6'") && e.contains("1-5") && e.contains("low/mid/high"),
        "{e}"
    );
    let e = err("brightness:3@sometimes");
    assert!(e.contains("@dynamic"), "{e}");
    let e = err("depth_range:5-1");
    assert!(
        e.contains("MIN < MAX") && e.contains("depth_range:0.42-10"),
        "{e}"
    );
    let e = err("depth_range:0.4-3@dynamic");
    assert!(e.contains("no mode"), "{e}");
    assert!(err("brightness").contains("NAME:VALUE"));
    assert!(err("brightness:1,,fast:2").contains("empty item"));
    assert!(err("").contains("empty item"));
    assert!(err("fast:0").contains("K ≥ 1"));
    assert!(err("fast:2@dynamic").contains("no mode"));
    assert!(err("rot:-1").contains("degrees"));
    assert!(err("trans:x").contains("metres"));
    assert!(err("rot:1@dynamic").contains("@smooth"));
    assert!(err("misalign:2.5").contains("whole number"));
    assert!(err("brightness:1,brightness:2").contains("twice"));
}

#[test]
fn every_catalogue_entry_parses_at_every_severity() {
    for name in all_names() {
        if crate::find(name).is_some() {
            for severity in 1..=5 {
                PerturbSpec::parse(&format!("{name}:{severity}@dynamic")).unwrap();
            }
        }
    }
}

/// Found by fuzzing: an item holding a line break was quoted as is, and the error spanned lines.
#[test]
fn errors_quote_line_breaks_as_escapes() {
    let err = PerturbSpec::parse("fog:3,depth_range:x\r2")
        .unwrap_err()
        .to_string();
    assert!(err.starts_with("spec item 'depth_range:x\\r2': "), "{err}");
    let err = PerturbSpec::parse("fo\ng:3").unwrap_err().to_string();
    assert!(
        err.starts_with("spec item 'fo\\ng:3': unknown perturbation 'fo\\ng'"),
        "{err}"
    );
}

#[test]
fn sensor_items_parse_need_a_scene_and_print_in_pipeline_order() {
    let spec = PerturbSpec::parse("fog:2,rolling_shutter:30,exposure:20@8").unwrap();
    assert_eq!(
        spec.exposure,
        Some(Exposure {
            ms: 20.0,
            subframes: Some(8)
        })
    );
    assert_eq!(spec.rolling_shutter, Some(RollingShutter { ms: 30.0 }));
    assert!(spec.needs_scene());
    assert_eq!(spec.scene_items(), ["exposure:20@8", "rolling_shutter:30"]);
    assert_eq!(spec.to_string(), "exposure:20@8,rolling_shutter:30,fog:2");
    assert_eq!(PerturbSpec::parse(&spec.to_string()).unwrap(), spec);
    let e = err("exposure:20@0");
    assert!(
        e.contains("exposure:20@0") && e.contains("sub-frame count"),
        "{e}"
    );
    assert!(err("rolling_shutter:fast").contains("milliseconds"));
    assert!(
        err("nope:1").contains("rolling_shutter"),
        "sensor names are listed"
    );
}

#[test]
fn imu_items_go_to_their_own_field_print_last_and_round_trip() {
    let spec =
        PerturbSpec::parse("cam_imu_offset:-3,fog:2,imu_jitter:0.2,imu_noise:2,imu_drop:0.01/5")
            .unwrap();
    assert_eq!(spec.imu.noise_scale, Some(2.0));
    assert_eq!(spec.imu.cam_imu_offset_ms, Some(-3.0));
    assert_eq!(spec.image.len(), 1);
    assert!(!spec.needs_scene());
    assert_eq!(
        spec.to_string(),
        "fog:2,imu_noise:2,imu_drop:0.01/5,imu_jitter:0.2,cam_imu_offset:-3"
    );
    assert_eq!(PerturbSpec::parse(&spec.to_string()).unwrap(), spec);
    let json = serde_json::to_string(&spec).unwrap();
    assert_eq!(serde_json::from_str::<PerturbSpec>(&json).unwrap(), spec);
    // Specs without IMU items serialise as before (manifests of earlier runs stay the same).
    let plain = serde_json::to_string(&PerturbSpec::parse("fog:2").unwrap()).unwrap();
    assert!(!plain.contains("imu"), "{plain}");
    assert!(!plain.contains("distortion"), "{plain}");
    assert!(!plain.contains("calibration"), "{plain}");
    let e = err("imu_saturation:2");
    assert!(
        e.starts_with("spec item 'imu_saturation:2': '2': expected GYRO/ACC"),
        "{e}"
    );
    assert!(err("imu_noise:1,imu_noise:2").contains("twice"));
    assert!(
        err("nope:1").contains("cam_imu_offset"),
        "IMU names are listed"
    );
}

#[test]
fn items_addressed_to_a_camera_reach_only_that_camera() {
    let spec =
        PerturbSpec::parse("cam1:fog:3,gaussian_noise:2,cam0:motion_blur:2@dynamic").unwrap();
    assert_eq!(spec.image[0].sensor.as_deref(), Some("cam1"));
    assert_eq!(spec.image[1].sensor, None);
    let names =
        |s: &PerturbSpec| -> Vec<String> { s.image.iter().map(|i| i.to_string()).collect() };
    // Written order kept, the sensor dropped.
    assert_eq!(
        names(&spec.for_camera("cam0")),
        ["gaussian_noise:2", "motion_blur:2@dynamic"]
    );
    assert_eq!(
        names(&spec.for_camera("cam1")),
        ["fog:3", "gaussian_noise:2"]
    );
    assert_eq!(names(&spec.for_camera("cam2")), ["gaussian_noise:2"]);
    assert_eq!(
        spec.to_string(),
        "cam1:fog:3,gaussian_noise:2,cam0:motion_blur:2@dynamic"
    );
    assert_eq!(PerturbSpec::parse(&spec.to_string()).unwrap(), spec);
    let json = serde_json::to_string(&spec).unwrap();
    assert_eq!(serde_json::from_str::<PerturbSpec>(&json).unwrap(), spec);
    // An unaddressed spec serialises as before the sensor field existed.
    let plain = serde_json::to_string(&PerturbSpec::parse("fog:3").unwrap()).unwrap();
    assert!(
        !plain.contains("sensor") && !plain.contains("calibration"),
        "{plain}"
    );
}

#[test]
fn calibration_items_parse_with_their_modes_and_round_trip() {
    let spec = PerturbSpec::parse(
        "fog:1,baseline:0.01@dynamic,cam1:extrinsic_rot:0.5@calibration,imu0:extrinsic_trans:0.01,extrinsic_trans:0.002,cam0:extrinsic_rot:0.5@dynamic",
    )
    .unwrap();
    use crate::calibration::CalibrationMode::{Calibration, Rendered};
    let got: Vec<(Option<&str>, &str, f64, _, bool)> = spec
        .calibration
        .iter()
        .map(|i| {
            (
                i.sensor.as_deref(),
                i.name.as_str(),
                i.sigma,
                i.mode,
                i.dynamic,
            )
        })
        .collect();
    assert_eq!(
        got,
        [
            (None, "baseline", 0.01, Rendered, true),
            (Some("cam1"), "extrinsic_rot", 0.5, Calibration, false),
            (Some("imu0"), "extrinsic_trans", 0.01, Rendered, false),
            (None, "extrinsic_trans", 0.002, Rendered, false),
            (Some("cam0"), "extrinsic_rot", 0.5, Rendered, true),
        ]
    );
    assert_eq!(
        spec.to_string(),
        "baseline:0.01@dynamic,cam1:extrinsic_rot:0.5@calibration,imu0:extrinsic_trans:0.01,extrinsic_trans:0.002,cam0:extrinsic_rot:0.5@dynamic,fog:1"
    );
    assert_eq!(PerturbSpec::parse(&spec.to_string()).unwrap(), spec);
    let every_camera = PerturbSpec::parse("extrinsic_trans:0.01@dynamic").unwrap();
    assert!(every_camera.calibration[0].dynamic && every_camera.calibration[0].sensor.is_none());
    assert_eq!(every_camera.to_string(), "extrinsic_trans:0.01@dynamic");
    assert!(!spec.needs_scene());
    assert!(spec.for_camera("cam0").calibration.is_empty());
}

#[test]
fn sensor_and_calibration_errors_name_the_item_and_what_was_expected() {
    let e = err("cam1:rot:1");
    assert!(
        e.starts_with("spec item 'cam1:rot:1': 'rot' applies to the whole rig"),
        "{e}"
    );
    let e = err("imu0:fog:3");
    assert!(
        e.contains("expected a camera (cam0, cam1, …), not imu0"),
        "{e}"
    );
    assert!(err("cam1:fog").contains("SENSOR:NAME:VALUE"));
    assert!(err("cam1:fgo:3").contains("unknown perturbation 'fgo'"));
    assert!(err("cam1:fog:3,cam1:fog:2").contains("'fog' is given twice"));
    let e = err("fog:2,cam1:fog:4");
    assert!(
        e.contains("for every camera and for one") && e.contains("cam0:fog:"),
        "{e}"
    );
    PerturbSpec::parse("cam0:fog:2,cam1:fog:4").unwrap();
    assert!(err("cam1:baseline:0.01").contains("takes no sensor"));
    assert!(err("baseline:-0.01").contains("metres ≥ 0"));
    assert!(err("extrinsic_rot:x").contains("degrees ≥ 0"));
    let e = err("imu0:extrinsic_rot:1@dynamic");
    assert!(
        e.starts_with("spec item 'imu0:extrinsic_rot:1@dynamic': @dynamic moves a camera")
            && e.ends_with("use imu0:extrinsic_rot:1 (once per sequence)"),
        "{e}"
    );
    for text in [
        "cam1:extrinsic_trans:0.01@dynamic@calibration",
        "baseline:0.01@calibration@dynamic",
    ] {
        let e = err(text);
        assert!(
            e.contains("@dynamic and @calibration exclude each other"),
            "{e}"
        );
    }
    assert!(err("extrinsic_rot:1@smooth").contains("valid: @calibration, @dynamic"));
    assert!(err("baseline:0.1@smooth").contains("@calibration, @dynamic"));
    assert!(err("baseline:0.01,baseline:0.02@calibration").contains("twice"));
    for text in ["cam1:fog:3", "baseline:0.01", "cam0:extrinsic_rot:1"] {
        assert!(!err(text.split(':').next().unwrap()).contains('\n'));
    }
}

#[test]
fn a_one_camera_input_takes_cam0_items_and_refuses_other_sensors_and_calibration() {
    let one = |text: &str| {
        PerturbSpec::parse(text)
            .unwrap()
            .one_camera_problem()
            .map(|e| e.to_string())
    };
    assert_eq!(one("cam0:fog:3,gaussian_noise:1"), None);
    let e = one("gaussian_noise:1,cam1:fog:3").unwrap();
    assert!(
        e.starts_with("spec item 'cam1:fog:3': this input has one camera, cam0"),
        "{e}"
    );
    let e = one("baseline:0.01@calibration").unwrap();
    assert!(
        e.starts_with("spec item 'baseline:0.01@calibration': a calibration item needs a rig"),
        "{e}"
    );
    let spec = PerturbSpec::parse("cam2:fog:1,imu0:extrinsic_rot:1").unwrap();
    let e = spec.unknown_sensor(&["cam0", "cam1"]).unwrap().to_string();
    assert_eq!(
        e,
        "spec item 'cam2:fog:1': no sensor 'cam2' here; the sensors are cam0, cam1"
    );
    let e = spec
        .unknown_sensor(&["cam0", "cam1", "cam2"])
        .unwrap()
        .to_string();
    assert!(
        e.contains("'imu0:extrinsic_rot:1': no sensor 'imu0'"),
        "{e}"
    );
    assert!(spec
        .unknown_sensor(&["cam0", "cam1", "cam2", "imu0"])
        .is_none());
}

#[test]
fn distortion_keeps_its_commas_and_round_trips() {
    let spec =
        PerturbSpec::parse("fog:2, distortion:radtan(-0.28, 0.07,2e-4,-3e-5),exposure:20").unwrap();
    assert_eq!(
        spec.distortion,
        Some(rslam_core::Distortion::Radtan {
            k1: -0.28,
            k2: 0.07,
            p1: 2e-4,
            p2: -3e-5
        })
    );
    assert_eq!(spec.image.len(), 1);
    assert!(spec.needs_scene());
    assert_eq!(
        spec.to_string(),
        "exposure:20,distortion:radtan(-0.28,0.07,0.0002,-0.00003),fog:2"
    );
    assert_eq!(PerturbSpec::parse(&spec.to_string()).unwrap(), spec);
    let fisheye = PerturbSpec::parse("distortion:equidistant(0.1,-0.02,0.003,-0.0004)").unwrap();
    assert!(matches!(
        fisheye.distortion,
        Some(rslam_core::Distortion::Equidistant { k4, .. }) if k4 == -0.0004
    ));
    for (bad, says) in [
        ("distortion:radtan(1,2,3)", "3 coefficients"),
        ("distortion:radtan(1,2,3,4", "unbalanced parentheses"),
        ("distortion:radtan(1,2,3,4))", "unbalanced parentheses"),
        (
            "distortion:pinhole(1,2,3,4)",
            "unknown lens model 'pinhole'",
        ),
        ("distortion:radtan(1,2,3,4)@x", "takes no mode"),
        ("distortion:3", "expected radtan(k1,k2,p1,p2)"),
    ] {
        let e = err(bad);
        assert!(e.contains(says) && !e.contains('\n'), "{bad}: {e}");
    }
    assert!(err("distortion:radtan(1,x,3,4)").starts_with("spec item 'distortion:radtan(1,x,3,4)'"));
}
