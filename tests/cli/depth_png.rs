//! `--depth-png small`: the samples of `fast` in fewer bytes, as standard 16-bit PNGs; recorded in
//! the manifest, so that it is another job for resume; read back by `rslam perturb`.

use std::path::PathBuf;

use rslam_core::dataset::DepthPng;

use crate::dataset_check::{files, manifest};
use crate::harness::Workspace;
use crate::render::SMALL_CAMERA;

fn render_args<'a>(depth_png: &'a str, out: &'a str) -> Vec<&'a str> {
    vec![
        "render",
        "--scene",
        "room0",
        "--frames",
        "4",
        "--camera",
        SMALL_CAMERA,
        "--depth-png",
        depth_png,
        "--out",
        out,
    ]
}

fn depth_files(ws: &Workspace, dataset: &str) -> Vec<PathBuf> {
    files(&ws.path(&format!("{dataset}/results")), "depth")
}

fn total_bytes(paths: &[PathBuf]) -> u64 {
    paths
        .iter()
        .map(|p| std::fs::metadata(p).unwrap().len())
        .sum()
}

#[test]
fn small_depth_pngs_hold_the_samples_of_fast_ones_in_fewer_bytes() {
    let ws = Workspace::new();
    ws.rslam(&render_args("fast", "fast")).success();
    ws.rslam(&render_args("small", "small")).success();
    let (fast, small) = (depth_files(&ws, "fast"), depth_files(&ws, "small"));
    assert_eq!(fast.len(), 4);
    for (a, b) in fast.iter().zip(&small) {
        let (a, b) = (image::open(a).unwrap(), image::open(b).unwrap());
        assert_eq!(b.color(), image::ColorType::L16, "16-bit grayscale");
        assert_eq!(a.into_luma16(), b.into_luma16());
    }
    let (fast_bytes, small_bytes) = (total_bytes(&fast), total_bytes(&small));
    assert!(small_bytes < fast_bytes, "{small_bytes} vs {fast_bytes}");
    assert_eq!(manifest(&ws.path("fast")).depth_png, DepthPng::Fast);
    assert_eq!(manifest(&ws.path("small")).depth_png, DepthPng::Small);

    ws.rslam(&render_args("small", "fast"))
        .fails_with(2, &["another job", "differs in depth_png", "--force"]);
    ws.rslam(&render_args("fast", "fast")).success();
}

#[test]
fn perturb_reads_small_depth_and_writes_the_encoding_asked_for() {
    let ws = Workspace::new();
    ws.rslam(&render_args("fast", "fast")).success();
    ws.rslam(&render_args("small", "small")).success();
    // A colour-only corruption passes depth through: the same samples, encoded afresh.
    let perturb = |out: &str, extra: &[&str]| {
        let args = [
            &["perturb", "--input", "small", "--perturb", "brightness:1"][..],
            &["--out", out],
            extra,
        ]
        .concat();
        ws.rslam(&args).success();
    };
    perturb("p_fast", &[]);
    perturb("p_small", &["--depth-png", "small"]);
    assert_eq!(manifest(&ws.path("p_fast")).depth_png, DepthPng::Fast);
    assert_eq!(manifest(&ws.path("p_small")).depth_png, DepthPng::Small);
    let bytes = |dataset: &str| -> Vec<Vec<u8>> {
        depth_files(&ws, dataset)
            .iter()
            .map(|p| std::fs::read(p).unwrap())
            .collect()
    };
    assert_eq!(bytes("p_fast"), bytes("fast"));
    assert_eq!(bytes("p_small"), bytes("small"));
}

#[test]
fn a_bad_value_or_one_for_images_names_the_flag() {
    let ws = Workspace::new();
    ws.rslam(&render_args("tiny", "ds"))
        .fails_with(2, &["--depth-png", "tiny", "fast or small"]);
    assert!(!ws.path("ds").exists());
    ws.rslam(&render_args("fast", "ds")).success();
    let frames = ws.path("ds/results").display().to_string();
    ws.rslam(&[
        "perturb",
        "--input",
        &frames,
        "--perturb",
        "brightness:1",
        "--depth-png",
        "small",
        "--out",
        "images",
    ])
    .fails_with(2, &["--depth-png", "a folder of images, not a dataset"]);
    assert!(!ws.path("images").exists());
}
