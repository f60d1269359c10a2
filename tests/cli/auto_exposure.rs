//! `auto_exposure` end to end: rendering with it and perturbing the clean render with it write the
//! same frames (both run the frames in capture order with the same keys), the camera brings the
//! frames to 18 % grey, and `sensor_state.csv` records what each frame was taken with.

use crate::dataset_check::{files, mean_linear};
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

/// `sensor_state.csv`: its header and its rows of numbers (empty cells as NaN).
fn state_rows(path: &std::path::Path) -> (String, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut lines = text.lines();
    let header = lines.next().unwrap().to_string();
    let rows = lines
        .map(|line| {
            line.split(',')
                .map(|cell| cell.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    (header, rows)
}

#[test]
fn render_and_perturb_input_expose_alike_and_settle_at_18_percent_grey() {
    let ws = Workspace::new();
    let render = |out: &str, spec: Option<&str>| {
        let args = [
            "--camera",
            SMALL_CAMERA,
            "--frames",
            "12",
            "--format",
            "tum",
            "--seed",
            "3",
        ];
        ws.render_room0(out, &args, spec)
    };
    render("clean", None);
    render("direct", Some("auto_exposure:1"));
    ws.rslam(&[
        "perturb",
        "--input",
        "clean",
        "--perturb",
        "auto_exposure:1",
        "--seed",
        "3",
        "--out",
        "after",
    ])
    .success();
    let direct = files(&ws.path("direct/rgb"), "");
    let after = files(&ws.path("after/rgb"), "");
    assert_eq!(direct.len(), 12);
    assert_eq!(after.len(), 12);
    for (a, b) in direct.iter().zip(&after) {
        assert_eq!(a.file_name(), b.file_name());
        assert!(
            std::fs::read(a).unwrap() == std::fs::read(b).unwrap(),
            "{} differs between render and perturb --input",
            b.display()
        );
    }
    let (header, rows) = state_rows(&ws.path("direct/sensor_state.csv"));
    assert_eq!(
        header,
        "frame,timestamp,auto_exposure.exposure_ms,auto_exposure.gain,\
         auto_exposure.steered_ms,auto_exposure.metered_mean"
    );
    assert_eq!(rows.len(), 12);
    assert_eq!(
        std::fs::read(ws.path("direct/sensor_state.csv")).unwrap(),
        std::fs::read(ws.path("after/sensor_state.csv")).unwrap()
    );
    // The first frame is taken at the nominal 10 ms and unity gain; each later row holds what
    // the controller metered of the frame before it, which is that frame's mean as written.
    assert_eq!((rows[0][2], rows[0][3]), (10.0, 1.0), "{rows:?}");
    for k in 1..rows.len() {
        let written = mean_linear(&direct[k - 1]);
        assert!(
            (rows[k][5] - written).abs() < 1e-4,
            "row {k}: metered {} but frame {} has mean {written}",
            rows[k][5],
            k - 1
        );
    }
    let clean = files(&ws.path("clean/rgb"), "");
    let first = mean_linear(&clean[0]);
    let last = mean_linear(direct.last().unwrap());
    assert!(
        (first / 0.18 - 1.0).abs() > 0.2,
        "room0's first frame ({first:.3}) is already near 18 % grey: the test shows nothing"
    );
    assert!(
        (last / 0.18 - 1.0).abs() < 0.1,
        "last frame's mean linear brightness {last:.3}, target 0.18"
    );
}
