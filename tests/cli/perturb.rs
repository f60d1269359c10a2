//! `rslam perturb` on images: a folder (mixed sizes and formats, pipelined through the GPU) and a
//! single file, checked against the contrast formula computed here.

use std::path::Path;

use crate::harness::Workspace;

/// imagecorruptions' contrast factor at severity 5.
const CONTRAST_5: f64 = 0.05;

fn pattern(width: u32, height: u32, offset: u32) -> image::RgbImage {
    image::RgbImage::from_fn(width, height, |x, y| {
        image::Rgb([
            ((x * 3 + offset) % 256) as u8,
            ((y * 5 + 2 * offset) % 256) as u8,
            ((x + y + 3 * offset) % 256) as u8,
        ])
    })
}

/// (x - mean) * c + mean per channel, in [0, 1], truncated to 8 bits.
fn contrast(input: &image::RgbImage, c: f64) -> image::RgbImage {
    let n = (input.width() * input.height()) as f64;
    let mut mean = [0.0f64; 3];
    for p in input.pixels() {
        for k in 0..3 {
            mean[k] += p[k] as f64 / 255.0 / n;
        }
    }
    image::RgbImage::from_fn(input.width(), input.height(), |x, y| {
        let p = input.get_pixel(x, y);
        image::Rgb(std::array::from_fn(|k| {
            let v = (p[k] as f64 / 255.0 - mean[k]) * c + mean[k];
            (v.clamp(0.0, 1.0) * 255.0) as u8
        }))
    })
}

fn assert_close(path: &Path, expected: &image::RgbImage, tolerance: i32) {
    let got = image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgb8();
    assert_eq!(
        got.dimensions(),
        expected.dimensions(),
        "{}",
        path.display()
    );
    let worst = got
        .as_raw()
        .iter()
        .zip(expected.as_raw())
        .map(|(&a, &b)| (a as i32 - b as i32).abs())
        .max()
        .unwrap_or(0);
    assert!(
        worst <= tolerance,
        "{}: off by {worst} levels",
        path.display()
    );
}

#[test]
fn image_folder_keeps_names_formats_and_order_across_sizes() {
    let ws = Workspace::new();
    std::fs::create_dir_all(ws.path("in")).unwrap();
    // Two runs of 64x48 around other sizes; 33 wide is not a multiple of the shaders' runs of 8.
    let inputs = [
        ("a.png", pattern(64, 48, 10)),
        ("b.png", pattern(64, 48, 60)),
        ("c.jpg", pattern(40, 30, 90)),
        ("d.png", pattern(64, 48, 120)),
        ("e.png", pattern(33, 21, 200)),
    ];
    for (name, image) in &inputs {
        image.save(ws.path(&format!("in/{name}"))).unwrap();
    }
    ws.rslam(&[
        "perturb",
        "--input",
        "in",
        "--out",
        "out",
        "--perturb",
        "contrast:5",
    ])
    .success();
    for (name, image) in &inputs {
        let out = ws.path(&format!("out/{name}"));
        if name.ends_with(".png") {
            assert_close(&out, &contrast(image, CONTRAST_5), 1);
        } else {
            assert_eq!(
                &std::fs::read(&out).unwrap()[..2],
                &[0xFF, 0xD8],
                "JPEG out"
            );
            // The input and output JPEG encodings each lose a little.
            let decoded_input = image::open(ws.path("in/c.jpg")).unwrap().to_rgb8();
            assert_close(&out, &contrast(&decoded_input, CONTRAST_5), 4);
        }
    }
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(ws.path("out/rslam.json")).unwrap()).unwrap();
    assert_eq!(manifest["frame_count"], 5);
    assert_eq!(manifest["severities"][0]["per_frame"], "55555");
}

#[test]
fn one_image_is_written_to_out_and_depth_corruptions_are_refused() {
    let ws = Workspace::new();
    let image = pattern(50, 20, 7);
    image.save(ws.path("frame.png")).unwrap();
    ws.rslam(&[
        "perturb",
        "--input",
        "frame.png",
        "--out",
        "low.png",
        "--perturb",
        "contrast:5",
    ])
    .success();
    assert_close(&ws.path("low.png"), &contrast(&image, CONTRAST_5), 1);
    ws.rslam(&[
        "perturb",
        "--input",
        "frame.png",
        "--out",
        "x.png",
        "--perturb",
        "depth_missing:3",
    ])
    .fails_with(
        2,
        &["depth corruptions need depth, and an image input has none"],
    );
    assert!(!ws.path("x.png").exists());
}

#[test]
fn a_dataset_without_camera_file_needs_camera_and_a_corrupt_frame_is_named() {
    let ws = Workspace::new();
    ws.rslam(&[
        "render",
        "--scene",
        "room0",
        "--frames",
        "6",
        "--camera",
        "64,48,60,60,31.5,23.5",
        "--format",
        "tum",
        "--out",
        "seq",
    ])
    .success();
    // A TUM sequence as published: no rslam.json, hence no camera anywhere.
    std::fs::remove_file(ws.path("seq/rslam.json")).unwrap();
    let perturb = |extra: &[&str]| {
        let args = [
            &["perturb", "--input", "seq", "--perturb", "brightness:2"][..],
            extra,
        ]
        .concat();
        ws.rslam(&args)
    };
    perturb(&["--out", "a"]).fails_with(2, &["seq", "no camera intrinsics", "--camera"]);
    assert!(
        !ws.path("a").exists(),
        "nothing written before the camera is known"
    );
    perturb(&["--out", "a", "--camera", "64,48,60,60,31.5,23.5"]).success();
    let manifest: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(ws.path("a/rslam.json")).unwrap()).unwrap();
    assert_eq!(manifest["camera"]["fx"], 60.0);
    let yaml = std::fs::read_to_string(ws.path("a/orbslam3.yaml")).unwrap();
    assert!(yaml.contains("Camera1.fx: 60.000000"), "{yaml}");

    let rgb = crate::dataset_check::files(&ws.path("seq/rgb"), "");
    std::fs::write(&rgb[3], b"\x89PNG\r\n\x1a\n truncated").unwrap();
    let name = rgb[3].file_name().unwrap().to_string_lossy().into_owned();
    let err = perturb(&["--out", "b", "--camera", "64,48,60,60,31.5,23.5"]).fails_with(2, &[&name]);
    assert_eq!(
        err.trim()
            .lines()
            .filter(|l| l.starts_with("error"))
            .count(),
        1,
        "{err}"
    );
    assert!(
        !ws.path("b/rslam.json").exists(),
        "a failed run never looks complete"
    );
    assert!(ws.path("b/rslam.run.json").exists());
}

/// A real severity is rendered and recorded as one: the manifest keeps `2.5` in the spec and the
/// per-frame draws of `@dynamic` as numbers; severity 0 writes the clean frames, bytes for bytes.
#[test]
fn real_severities_are_recorded_and_severity_zero_is_clean() {
    use crate::dataset_check::{files, manifest};
    use crate::render::SMALL_CAMERA;
    let ws = Workspace::new();
    let args = ["--frames", "4", "--camera", SMALL_CAMERA];
    ws.render_room0("clean", &args, None);
    ws.render_room0("zero", &args, Some("fog:0,depth_noise:0"));
    let frames = |dir: &str| -> Vec<Vec<u8>> {
        files(&ws.path(&format!("{dir}/results")), "")
            .iter()
            .map(|f| std::fs::read(f).unwrap())
            .collect()
    };
    assert_eq!(frames("zero"), frames("clean"));
    assert_eq!(manifest(&ws.path("zero")).severities[0].per_frame, "0000");

    ws.render_room0(
        "real",
        &args,
        Some("gaussian_noise:2.5@dynamic,depth_missing:1.5"),
    );
    let written = manifest(&ws.path("real"));
    assert_eq!(
        written.perturbation,
        "gaussian_noise:2.5@dynamic,depth_missing:1.5"
    );
    let parsed = written.perturbation_parsed.to_string();
    assert!(parsed.contains(r#""severity":2.5"#), "{parsed}");
    let drawn = written.severities[0].values().unwrap();
    assert_eq!(drawn.len(), 4);
    assert!(drawn.iter().all(|s| (0.0..=2.5).contains(s)), "{drawn:?}");
    assert_eq!(written.severities[1].per_frame, "1.5 1.5 1.5 1.5");
    assert_ne!(frames("real"), frames("clean"));
}
