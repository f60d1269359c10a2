//! Known answers on meshes written here: planes, spheres, a mesh against itself, point clouds.

use std::f64::consts::PI;
use std::path::PathBuf;

use super::*;

/// Fewer than the default: debug-build tests, and the answers below are exact or bounded.
pub(super) const SAMPLES: usize = 20_000;

/// Without culling: these answers are about the distances.
pub(super) fn options() -> ReconOptions {
    ReconOptions {
        samples: SAMPLES,
        culling: Culling::None,
        ..ReconOptions::default()
    }
}

pub(super) struct Files(tempfile::TempDir);

impl Files {
    pub(super) fn new() -> Self {
        Self(tempfile::tempdir().unwrap())
    }

    /// Binary little-endian PLY (ASCII with `ascii`); no faces makes a point cloud.
    pub(super) fn ply(
        &self,
        name: &str,
        positions: &[[f32; 3]],
        faces: &[[u32; 3]],
        ascii: bool,
    ) -> PathBuf {
        let format = if ascii {
            "ascii"
        } else {
            "binary_little_endian"
        };
        let mut bytes = format!(
            "ply\nformat {format} 1.0\nelement vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
             element face {}\nproperty list uchar int vertex_indices\nend_header\n",
            positions.len(),
            faces.len()
        )
        .into_bytes();
        for p in positions {
            if ascii {
                bytes.extend(format!("{} {} {}\n", p[0], p[1], p[2]).bytes());
            } else {
                p.iter().for_each(|c| bytes.extend(c.to_le_bytes()));
            }
        }
        for f in faces {
            if ascii {
                bytes.extend(format!("3 {} {} {}\n", f[0], f[1], f[2]).bytes());
            } else {
                bytes.push(3);
                f.iter()
                    .for_each(|&i| bytes.extend((i as i32).to_le_bytes()));
            }
        }
        self.write(name, &bytes)
    }

    fn write(&self, name: &str, bytes: &[u8]) -> PathBuf {
        let path = self.0.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        path
    }
}

/// The unit square [0,1]² at height z, two triangles.
fn square(z: f32) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    (
        vec![[0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z]],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

/// A UV sphere of radius 1 about the origin with `rings` latitude bands; vertices on the sphere.
fn sphere(rings: u32) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let segments = 2 * rings;
    let mut positions = Vec::new();
    for i in 0..=rings {
        let theta = PI * i as f64 / rings as f64;
        for j in 0..segments {
            let phi = 2.0 * PI * j as f64 / segments as f64;
            positions.push(
                [
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                ]
                .map(|c| c as f32),
            );
        }
    }
    let at = |i: u32, j: u32| i * segments + j % segments;
    let mut faces = Vec::new();
    for i in 0..rings {
        // The first and last rows of vertices sit at the poles: one triangle per cell there.
        for j in 0..segments {
            if i + 1 < rings {
                faces.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            }
            if i > 0 {
                faces.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
    }
    (positions, faces)
}

/// The most any point of a triangle lies inside the unit sphere: 1 − its plane's distance to
/// the centre (triangles with all corners on the sphere).
fn deepest_chord(positions: &[[f32; 3]], faces: &[[u32; 3]]) -> f64 {
    faces
        .iter()
        .filter_map(|f| {
            let [a, b, c] = f.map(|i| glam::DVec3::from(positions[i as usize].map(f64::from)));
            let n = (b - a).cross(c - a).try_normalize()?;
            Some(1.0 - n.dot(a).abs())
        })
        .fold(0.0, f64::max)
}

#[test]
fn a_plane_against_a_shifted_plane_is_off_by_the_shift() {
    let files = Files::new();
    let (gt_v, gt_f) = square(0.0);
    let gt = files.ply("gt.ply", &gt_v, &gt_f, false);
    for (shift_m, ratio) in [(0.02, 100.0), (0.08, 0.0)] {
        let (v, f) = square(shift_m as f32);
        let rec = files.ply("rec.ply", &v, &f, false);
        let m = evaluate_reconstruction(&rec, &gt, &options(), None).unwrap();
        let shift_cm = shift_m * 100.0;
        assert!((m.accuracy_cm - shift_cm).abs() < 1e-4, "{m:?}");
        assert!((m.completion_cm - shift_cm).abs() < 1e-4, "{m:?}");
        assert_eq!(m.completion_ratio_percent, ratio);
        assert_eq!(m.reconstruction.samples, SAMPLES);
        assert_eq!(m.ground_truth.kind, SurfaceKind::Mesh);
    }
}

#[test]
fn a_mesh_against_itself_gives_zero_and_full_completion() {
    let files = Files::new();
    let (v, f) = sphere(24);
    let path = files.ply("sphere.ply", &v, &f, false);
    let m = evaluate_reconstruction(&path, &path, &options(), None).unwrap();
    assert!(m.accuracy_cm < 1e-4, "{m:?}");
    assert!(m.completion_cm < 1e-4, "{m:?}");
    assert_eq!(m.completion_ratio_percent, 100.0);
}

#[test]
fn a_coarser_sphere_is_off_by_less_than_its_deepest_chord() {
    let files = Files::new();
    let (fine_v, fine_f) = sphere(64);
    let (coarse_v, coarse_f) = sphere(12);
    let gt = files.ply("fine.ply", &fine_v, &fine_f, false);
    let rec = files.ply("coarse.ply", &coarse_v, &coarse_f, true);
    // Both surfaces lie between radius 1 − (deepest chord) and 1, so along any ray from the
    // centre they are at most that far apart.
    let bound_cm = deepest_chord(&coarse_v, &coarse_f).max(deepest_chord(&fine_v, &fine_f)) * 100.0;
    assert!(bound_cm > 1.0 && bound_cm < 5.0, "{bound_cm}");
    let m = evaluate_reconstruction(&rec, &gt, &options(), None).unwrap();
    for value in [m.accuracy_cm, m.completion_cm] {
        assert!(
            value > 0.1 && value < bound_cm,
            "{value} vs {bound_cm}: {m:?}"
        );
    }
    assert_eq!(m.completion_ratio_percent, 100.0);
    // The roles swapped: the same distances, measured from the other side.
    let swapped = evaluate_reconstruction(&gt, &rec, &options(), None).unwrap();
    assert!((swapped.accuracy_cm - m.completion_cm).abs() < 0.02 * m.completion_cm);
    assert!((swapped.completion_cm - m.accuracy_cm).abs() < 0.02 * m.accuracy_cm);
}

#[test]
fn a_point_cloud_is_measured_by_its_points() {
    let files = Files::new();
    let (gt_v, gt_f) = square(0.0);
    let gt = files.ply("gt.ply", &gt_v, &gt_f, false);
    let (shift, grid) = (0.01f32, 41);
    let spacing = 1.0 / (grid - 1) as f64;
    let cloud: Vec<[f32; 3]> = (0..grid * grid)
        .map(|k| [(k % grid) as f32, (k / grid) as f32, 0.0].map(|c| c * spacing as f32))
        .map(|[x, y, _]| [x, y, shift])
        .collect();
    let rec = files.ply("cloud.ply", &cloud, &[], true);
    let m = evaluate_reconstruction(&rec, &gt, &options(), None).unwrap();
    assert_eq!(m.reconstruction.kind, SurfaceKind::PointCloud);
    assert_eq!(m.reconstruction.samples, cloud.len());
    assert!((m.accuracy_cm - 1.0).abs() < 1e-4, "{m:?}");
    // A ground-truth point is at most half a grid diagonal beside its nearest cloud point.
    let farthest_cm = ((shift as f64).powi(2) + spacing * spacing / 2.0).sqrt() * 100.0;
    assert!(
        m.completion_cm > 1.0 && m.completion_cm < farthest_cm,
        "{m:?}"
    );
    assert_eq!(m.completion_ratio_percent, 100.0);

    let few = ReconOptions {
        samples: 500,
        ..options()
    };
    let subsampled = evaluate_reconstruction(&rec, &gt, &few, None).unwrap();
    assert_eq!(subsampled.reconstruction.samples, 500);
    assert!((subsampled.accuracy_cm - 1.0).abs() < 1e-4);
}

#[test]
fn the_seed_alone_fixes_the_numbers_whatever_the_thread_count() {
    let files = Files::new();
    let (fine_v, fine_f) = sphere(32);
    let (coarse_v, coarse_f) = sphere(8);
    let gt = files.ply("fine.ply", &fine_v, &fine_f, false);
    let rec = files.ply("coarse.ply", &coarse_v, &coarse_f, false);
    let run = |threads: usize, seed: u64| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            evaluate_reconstruction(&rec, &gt, &ReconOptions { seed, ..options() }, None).unwrap()
        })
    };
    assert_eq!(run(1, 7), run(3, 7));
    assert_ne!(run(1, 7).accuracy_cm, run(1, 8).accuracy_cm);
}

#[test]
fn bad_input_is_a_one_line_error_naming_the_file() {
    let files = Files::new();
    let (v, f) = square(0.0);
    let gt = files.ply("gt.ply", &v, &f, false);
    let cases = [
        (files.ply("empty.ply", &[], &[], true), "no vertices: expected a mesh or a point cloud"),
        (
            files.write(
                "no_vertex_element.ply",
                b"ply\nformat ascii 1.0\ncomment nothing\nend_header\n",
            ),
            "no vertices",
        ),
        (
            files.write(
                "nan.ply",
                b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n0 inf 0\n",
            ),
            "vertex 0: coordinate y = inf is not a finite 32-bit float",
        ),
        (
            files.ply("flat.ply", &[[0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0]], &[[0, 1, 2]], false),
            "every triangle has zero area",
        ),
        (files.write("rec.obj", b"v 0 0 0\n"), "expected a .ply file"),
        (files.0.path().join("missing.ply"), "missing.ply"),
    ];
    for (rec, expected) in cases {
        let err = evaluate_reconstruction(&rec, &gt, &options(), None)
            .unwrap_err()
            .to_string();
        assert!(err.contains(expected), "expected '{expected}' in '{err}'");
        assert!(err.contains(&rec.display().to_string()), "{err}");
        assert!(!err.contains('\n'), "one line: {err}");
    }
    let cloud = files.ply("cloud.ply", &v, &[], false);
    let err = evaluate_reconstruction(&gt, &cloud, &options(), None).unwrap_err();
    assert!(
        err.to_string()
            .contains("no faces: expected the ground-truth mesh"),
        "{err}"
    );
    for bad in [
        ReconOptions {
            samples: 0,
            ..options()
        },
        ReconOptions {
            threshold_cm: -1.0,
            ..options()
        },
    ] {
        let err = evaluate_reconstruction(&gt, &gt, &bad, None).unwrap_err();
        assert!(matches!(err, EvalError::BadOption { .. }), "{err}");
    }
}
