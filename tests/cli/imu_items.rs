//! IMU items and `cam_imu_offset` end to end: on a published-style EuRoC sequence (`rslam
//! perturb --input`) and on a rendered `stereo-imu` rig, read back from the files; and their
//! one-line refusals where there is no IMU.

use std::path::Path;

use crate::harness::Workspace;
use crate::perturb_euroc::{write_published_style, STAMPS};

const IMU_HEADER: &str = "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]";
const GT_HEADER: &str = "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z [], v_RS_R_x [m s^-1], v_RS_R_y [m s^-1], v_RS_R_z [m s^-1], b_w_RS_S_x [rad s^-1], b_w_RS_S_y [rad s^-1], b_w_RS_S_z [rad s^-1], b_a_RS_S_x [m s^-2], b_a_RS_S_y [m s^-2], b_a_RS_S_z [m s^-2]";
const IMU_PERIOD_NS: u64 = 5_000_000;
/// MH_01_easy's first IMU stamp.
const IMU_START_NS: u64 = 1_403_636_579_758_555_392;
const IMU_SAMPLES: u64 = 2000;

/// The rows of a EuRoC data.csv: the stamp, then the numbers.
pub(crate) fn rows(path: &Path) -> Vec<(u64, Vec<f64>)> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let mut fields = l.split(',').map(str::trim);
            let t = fields.next().unwrap().parse().unwrap();
            // A camera's second column is a file name, not a number: skipped.
            (t, fields.filter_map(|f| f.parse().ok()).collect())
        })
        .collect()
}

pub(crate) fn manifest(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("rslam.json")).unwrap()).unwrap()
}

pub(crate) fn vector(value: &serde_json::Value) -> [f64; 3] {
    std::array::from_fn(|i| value[i].as_f64().unwrap())
}

/// A MH_01-style sequence with 10 s of IMU at 200 Hz (published number formatting, CRLF lines)
/// and ground truth at its own stamps, 1 µs after each IMU sample, as EuRoC's are not the IMU's.
fn write_sequence(root: &Path) {
    write_published_style(root);
    let mav = root.join("mav0");
    let (mut imu, mut gt) = (format!("{IMU_HEADER}\r\n"), format!("{GT_HEADER}\n"));
    for k in 0..IMU_SAMPLES {
        let t = IMU_START_NS + k * IMU_PERIOD_NS;
        let s = (k as f64 * 0.01).sin();
        imu.push_str(&format!(
            "{t},{:.17},0.14730578886832138,0.02722713633111154,{:.16},-0.37592158333333331,-2.4026292499999999\r\n",
            -0.099 + 0.05 * s,
            8.147_691_708_333_333 + s
        ));
        gt.push_str(&format!(
            "{},4.688319,-1.786938,0.783338,0.534108,-0.153029,-0.827383,-0.082152,-0.027876,0.033207,0.800006,-0.003172,0.021267,{:.6},-0.025266,0.136696,0.075593\n",
            t + 1_000,
            0.078502 + k as f64 * 1e-6
        ));
    }
    std::fs::write(mav.join("imu0/data.csv"), imu).unwrap();
    std::fs::write(mav.join("state_groundtruth_estimate0/data.csv"), gt).unwrap();
}

/// Readings and biases differ from the input's by the recorded step from its time on, and by
/// nothing before; the camera frames are the same bytes under stamps moved by the offset.
#[test]
fn a_euroc_sequence_gets_a_bias_step_and_a_camera_offset_with_frames_untouched() {
    let ws = Workspace::new();
    write_sequence(&ws.path("seq"));
    let spec = "imu_bias_step:0.02/0.3,cam_imu_offset:2.5";
    let args = [
        "perturb",
        "--input",
        "seq",
        "--out",
        "out",
        "--perturb",
        spec,
    ];
    ws.rslam(&args).success();
    let (input, out) = (ws.path("seq/mav0"), ws.path("out/mav0"));
    for cam in ["cam0", "cam1"] {
        let stamps: Vec<u64> = rows(&out.join(cam).join("data.csv"))
            .iter()
            .map(|r| r.0)
            .collect();
        let shifted: Vec<u64> = STAMPS.iter().map(|t| t + 2_500_000).collect();
        assert_eq!(stamps, shifted, "{cam}: stamps moved by exactly 2.5 ms");
        for (before, after) in STAMPS.iter().zip(&shifted) {
            assert_eq!(
                std::fs::read(out.join(cam).join(format!("data/{after}.png"))).unwrap(),
                std::fs::read(input.join(cam).join(format!("data/{before}.png"))).unwrap(),
                "{cam}: frame {before} copied byte for byte as {after}"
            );
        }
        let files = std::fs::read_dir(out.join(cam).join("data"))
            .unwrap()
            .count();
        assert_eq!(files, STAMPS.len());
    }
    for file in ["imu0/sensor.yaml", "cam0/sensor.yaml"] {
        assert_eq!(
            std::fs::read(out.join(file)).unwrap(),
            std::fs::read(input.join(file)).unwrap(),
            "{file}: the calibration says what it said"
        );
    }

    let m = manifest(&ws.path("out"));
    let report = &m["extra"]["imu_perturbation"];
    assert_eq!(report["cam_imu_offset_ns"], 2_500_000);
    let step = &report["bias_step"];
    let at_ns = step["at_ns"].as_u64().unwrap();
    let (gyro, accel) = (vector(&step["gyroscope"]), vector(&step["accelerometer"]));
    let norm = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!((norm(gyro) - 0.02).abs() < 1e-12 && (norm(accel) - 0.3).abs() < 1e-12);
    let span = (IMU_SAMPLES - 1) * IMU_PERIOD_NS;
    assert!(at_ns >= IMU_START_NS + span / 10 && at_ns <= IMU_START_NS + span * 9 / 10);

    let expected = |t: u64| {
        if t >= at_ns {
            (gyro, accel)
        } else {
            ([0.0; 3], [0.0; 3])
        }
    };
    let (imu_in, imu_out) = (
        rows(&input.join("imu0/data.csv")),
        rows(&out.join("imu0/data.csv")),
    );
    assert_eq!(imu_in.len(), imu_out.len());
    let mut stepped = 0;
    for ((t, before), (t_out, after)) in imu_in.iter().zip(&imu_out) {
        assert_eq!(t, t_out, "IMU stamps stay");
        let (g, a) = expected(*t);
        for axis in 0..3 {
            assert!((after[axis] - before[axis] - g[axis]).abs() < 1e-12, "{t}");
            assert!(
                (after[3 + axis] - before[3 + axis] - a[axis]).abs() < 1e-12,
                "{t}"
            );
        }
        stepped += usize::from(*t >= at_ns);
    }
    assert!(stepped > 0 && stepped < imu_in.len());
    // The true biases (columns 11–16 after the stamp, 0-based 10–15) take the step with the
    // last IMU sample at or before each state; the states are 1 µs after the samples.
    let gt = "state_groundtruth_estimate0/data.csv";
    let (gt_in, gt_out) = (rows(&input.join(gt)), rows(&out.join(gt)));
    assert_eq!(gt_in.len(), gt_out.len());
    for ((t, before), (t_out, after)) in gt_in.iter().zip(&gt_out) {
        assert_eq!(t, t_out);
        let (g, a) = expected(t - 1_000);
        for axis in 0..3 {
            assert!(
                (after[10 + axis] - before[10 + axis] - g[axis]).abs() < 1e-12,
                "{t}"
            );
            assert!(
                (after[13 + axis] - before[13 + axis] - a[axis]).abs() < 1e-12,
                "{t}"
            );
        }
        for c in 0..3 {
            assert!((after[c] - before[c]).abs() < 1e-12, "positions stay");
        }
    }
    let verify = ws.rslam(&["verify", "out"]);
    assert!(verify.success().contains("out: ok"), "{}", verify.stdout());

    // The offset alone leaves the IMU and the ground truth files as they were.
    let args = [
        "perturb",
        "--input",
        "seq",
        "--out",
        "offset",
        "--perturb",
        "cam_imu_offset:-1",
    ];
    ws.rslam(&args).success();
    for file in ["imu0/data.csv", "state_groundtruth_estimate0/data.csv"] {
        assert_eq!(
            std::fs::read(ws.path("offset/mav0").join(file)).unwrap(),
            std::fs::read(input.join(file)).unwrap(),
            "{file}"
        );
    }
    let stamps: Vec<u64> = rows(&ws.path("offset/mav0/cam1/data.csv"))
        .iter()
        .map(|r| r.0)
        .collect();
    assert_eq!(stamps, STAMPS.map(|t| t - 1_000_000));
}

/// Drops and jitter: the manifest's counts match the file, stamps stay strictly increasing, the
/// ground truth is copied as it was, and the jitter's spread is what was asked.
#[test]
fn a_euroc_sequence_loses_and_jitters_imu_samples() {
    let ws = Workspace::new();
    write_sequence(&ws.path("seq"));
    let args = [
        "perturb",
        "--input",
        "seq",
        "--out",
        "out",
        "--perturb",
        "imu_drop:0.2,imu_jitter:0.5",
    ];
    let run = ws.rslam(&args);
    run.success();
    let (input, out) = (ws.path("seq/mav0"), ws.path("out/mav0"));
    let report = manifest(&ws.path("out"))["extra"]["imu_perturbation"].clone();
    let dropped = report["dropped"]["dropped"].as_u64().unwrap();
    let imu = rows(&out.join("imu0/data.csv"));
    assert_eq!(imu.len() as u64, IMU_SAMPLES - dropped);
    // 2000 samples at P = 0.2: 400 ± 18 (σ); five σ.
    assert!((dropped as f64 - 400.0).abs() < 90.0, "{dropped}");
    assert!(
        imu.windows(2).all(|w| w[0].0 < w[1].0),
        "strictly increasing"
    );
    assert!(run.stderr().contains(&format!("{} IMU samples", imu.len())));
    // Each kept sample is an input sample moved by its jitter: the nearest input stamp (2.5 ms
    // away at most) has the same readings.
    let input_rows = rows(&input.join("imu0/data.csv"));
    let mut moves = Vec::new();
    for (t, values) in &imu {
        let k = ((*t as f64 - IMU_START_NS as f64) / IMU_PERIOD_NS as f64).round() as usize;
        assert_eq!(&input_rows[k].1, values, "readings stay as they were");
        // In i64: f64 holds these 19-digit stamps to 256 ns only.
        moves.push((*t as i64 - input_rows[k].0 as i64) as f64);
    }
    let std = (moves.iter().map(|m| m * m).sum::<f64>() / moves.len() as f64).sqrt();
    // 1600 draws: the std's relative standard error is 1.8 %; five of them.
    assert!((std / 0.5e6 - 1.0).abs() < 0.09, "jitter std {std} ns");
    assert!((report["jitter"]["std_ns"].as_f64().unwrap() - std).abs() < 1e-6 * std);
    let gt = "state_groundtruth_estimate0/data.csv";
    assert_eq!(
        std::fs::read(out.join(gt)).unwrap(),
        std::fs::read(input.join(gt)).unwrap()
    );
}

/// A rendered rig with a bias step and a camera offset against the same render without: the
/// frames are the same bytes under stamps 10 ms earlier, the readings and the true biases differ
/// by the recorded step from its time on, the poses not at all.
#[test]
fn a_rendered_rig_carries_the_bias_step_in_its_ground_truth_and_the_offset_in_its_stamps() {
    let ws = Workspace::new();
    let render = |out: &str, spec: Option<&str>| {
        let args = ["--frames", "5", "--rig", "stereo-imu", "--format", "euroc"];
        ws.render_room0(out, &args, spec)
    };
    render("clean", None);
    render("moved", Some("imu_bias_step:0.05/0.5,cam_imu_offset:-10"));
    let (clean, moved) = (ws.path("clean/mav0"), ws.path("moved/mav0"));
    let report = manifest(&ws.path("moved"))["extra"]["imu_perturbation"].clone();
    let step = &report["bias_step"];
    let at_ns = step["at_ns"].as_u64().unwrap();
    let (gyro, accel) = (vector(&step["gyroscope"]), vector(&step["accelerometer"]));
    for cam in ["cam0", "cam1"] {
        let (a, b) = (
            rows(&clean.join(cam).join("data.csv")),
            rows(&moved.join(cam).join("data.csv")),
        );
        assert_eq!(a.len(), b.len());
        for ((t, _), (u, _)) in a.iter().zip(&b) {
            assert_eq!(*u + 10_000_000, *t, "{cam}: 10 ms earlier");
            assert_eq!(
                std::fs::read(clean.join(cam).join(format!("data/{t}.png"))).unwrap(),
                std::fs::read(moved.join(cam).join(format!("data/{u}.png"))).unwrap(),
            );
        }
    }
    let (a, b) = (
        rows(&clean.join("imu0/data.csv")),
        rows(&moved.join("imu0/data.csv")),
    );
    assert_eq!(a.len(), b.len());
    let stepped = a.iter().filter(|r| r.0 >= at_ns).count();
    assert!(stepped > 0 && stepped < a.len(), "{stepped} of {}", a.len());
    let gt = "state_groundtruth_estimate0/data.csv";
    let (ga, gb) = (rows(&clean.join(gt)), rows(&moved.join(gt)));
    for (((t, x), (_, y)), ((_, p), (_, q))) in a.iter().zip(&b).zip(ga.iter().zip(&gb)) {
        let (g, acc) = if *t >= at_ns {
            (gyro, accel)
        } else {
            ([0.0; 3], [0.0; 3])
        };
        for axis in 0..3 {
            assert!((y[axis] - x[axis] - g[axis]).abs() < 1e-12);
            assert!((y[3 + axis] - x[3 + axis] - acc[axis]).abs() < 1e-12);
            assert!((q[10 + axis] - p[10 + axis] - g[axis]).abs() < 1e-12);
            assert!((q[13 + axis] - p[13 + axis] - acc[axis]).abs() < 1e-12);
        }
        assert_eq!(&p[..10], &q[..10], "poses and velocities stay");
    }
}

/// The one `error:` line of a failed run (the adapter line may come before it).
fn error_line(stderr: &str) -> String {
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "{stderr}");
    errors[0].to_string()
}

#[test]
fn imu_items_without_an_imu_are_one_line_errors() {
    let ws = Workspace::new();
    write_published_style(&ws.path("seq"));
    std::fs::remove_dir_all(ws.path("seq/mav0/imu0")).unwrap();
    let err = ws
        .rslam(&[
            "perturb",
            "--input",
            "seq",
            "--out",
            "x",
            "--perturb",
            "fog:1,imu_drop:0.1",
        ])
        .fails_with(
            2,
            &[
                "--perturb item 'imu_drop:0.1': IMU items need an IMU",
                "(no imu0/)",
            ],
        );
    error_line(&err);
    let render = [
        "render",
        "--scene",
        "room0",
        "--frames",
        "4",
        "--out",
        "x",
        "--perturb",
    ];
    let err = ws
        .rslam(&[&render[..], &["imu_noise:2"]].concat())
        .fails_with(
            2,
            &["'imu_noise:2': IMU items need an IMU, and a one-camera render has none"],
        );
    error_line(&err);
    let err = ws
        .rslam(
            &[
                &render[..],
                &["cam_imu_offset:3", "--rig", "stereo", "--format", "euroc"],
            ]
            .concat(),
        )
        .fails_with(
            2,
            &["'cam_imu_offset:3': IMU items need an IMU, and the 'stereo' rig has none"],
        );
    error_line(&err);
    let err = ws
        .rslam(&[&render[..], &["imu_saturation:2"]].concat())
        .fails_with(2, &["imu_saturation:2", "expected GYRO/ACC"]);
    error_line(&err);
    assert!(!ws.path("x").exists());
}
