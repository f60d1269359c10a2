//! Checks of every built-in scene, by ray casting at 1/8 of the Replica resolution: the default
//! trajectory and those of further agents stay in free space with smooth, real motion, and every
//! view has valid depth and corners a feature tracker can hold on to. Like real rooms, views may be
//! mostly plain wall or ceiling; the sequence as a whole must still be mostly textured.

use std::f64::consts::PI;

use glam::{DVec3, Vec3};
use rayon::prelude::*;
use rslam_core::{Intrinsics, RgbImage};

use super::{agent_trajectory, build, trajectory, BUILTIN_SCENES};
use crate::raycast::{RayCastFrame, RayCaster};
use crate::Scene;

/// No camera centre closer than this to any surface (metres), and no depth below it.
const MIN_CLEARANCE: f32 = 0.3;
/// Depth beyond which a Replica depth PNG saturates.
const MAX_DEPTH: f32 = 10.0;
/// Views checked: every this many frames.
const VIEW_STRIDE: usize = 20;
/// Share of pixels that must have valid depth.
const MIN_VALID_DEPTH: f64 = 0.98;
/// Median over the views of the share of image cells (10 × 10 grid) that hold texture, the most
/// views allowed below [`PLAIN_VIEW`] of textured cells, and the gradient that counts.
const MIN_MEDIAN_TEXTURED_CELLS: f64 = 0.5;
const PLAIN_VIEW: f64 = 0.3;
const MAX_PLAIN_VIEWS: f64 = 0.15;
const CELL_GRADIENT: f32 = 4.0;
/// Corners (Shi–Tomasi) every 150 × 85 view must have: never a blank wall. Fewer than
/// [`FEW_CORNERS`] is allowed only for a moment facing a plain wall, as in real rooms: at most
/// [`MAX_FEW_CORNER_VIEWS`] of the views.
const MIN_CORNERS: usize = 6;
const FEW_CORNERS: usize = 12;
const MAX_FEW_CORNER_VIEWS: f64 = 0.02;
/// A furnished room is not a handful of boxes.
const MIN_TRIANGLES: usize = 10_000;
/// Hand-held limits: m/s and deg/s between consecutive frames.
const MAX_SPEED: f64 = 1.0;
const MAX_TURN_RATE: f64 = 90.0;

/// The Replica camera at 1/8 scale (pixel centres stay at integer coordinates).
pub fn eighth_scale() -> Intrinsics {
    let k = Intrinsics::REPLICA;
    let s = 8.0;
    Intrinsics {
        width: k.width / 8,
        height: k.height / 8,
        fx: k.fx / s,
        fy: k.fy / s,
        cx: (k.cx + 0.5) / s - 0.5,
        cy: (k.cy + 0.5) / s - 0.5,
    }
}

/// Agents whose paths are checked besides the default one (agent 0): those of a multi-agent
/// sequence must be as good as the default path.
const CHECKED_AGENTS: usize = 5;

fn check_scene(name: &str) {
    let scene = build(name).expect("built-in scene");
    check_geometry(&scene);
    let caster = RayCaster::new(&scene);
    let default = scene
        .default_trajectory
        .as_ref()
        .expect("default trajectory");
    assert_eq!(agent_trajectory(name, 0).as_ref(), Some(default));
    for agent in 0..CHECKED_AGENTS {
        let trajectory = agent_trajectory(name, agent).expect("built-in scene");
        check_path(&format!("{name} agent {agent}"), &caster, &trajectory);
    }
}

fn check_path(name: &str, caster: &RayCaster, trajectory: &rslam_core::Trajectory) {
    check_motion(name, trajectory);
    check_free_space(name, caster, trajectory);
    let k = eighth_scale();
    let views: Vec<(f64, usize, Option<String>)> = (0..trajectory.len())
        .into_par_iter()
        .step_by(VIEW_STRIDE)
        .map(|i| {
            let frame = caster.render(&trajectory.poses[i], &k);
            let (stats, textured, corners, problem) = view_stats(&frame);
            if i % 200 == 0 {
                eprintln!("{name} frame {i}: {stats}");
            }
            let problem = problem.map(|problem| {
                let path = std::env::temp_dir().join(format!(
                    "rslam-{}-frame{i:04}-actual.png",
                    name.replace(' ', "-")
                ));
                save_png(&frame.rgb, &path);
                format!("{name} frame {i}: {problem} (see {})", path.display())
            });
            (textured, corners, problem)
        })
        .collect();
    let mut failures: Vec<String> = views.iter().filter_map(|v| v.2.clone()).collect();
    let mut textured: Vec<f64> = views.iter().map(|v| v.0).collect();
    textured.sort_by(f64::total_cmp);
    let median = textured[textured.len() / 2];
    let plain = textured.iter().filter(|&&t| t < PLAIN_VIEW).count() as f64 / textured.len() as f64;
    eprintln!(
        "{name}: median textured cells {:.0} %, plain views {:.0} %",
        100.0 * median,
        100.0 * plain
    );
    if median < MIN_MEDIAN_TEXTURED_CELLS {
        failures.push(format!(
            "{name}: median textured cells only {:.0} %",
            100.0 * median
        ));
    }
    let few_corners =
        views.iter().filter(|v| v.1 < FEW_CORNERS).count() as f64 / views.len() as f64;
    if few_corners > MAX_FEW_CORNER_VIEWS {
        failures.push(format!(
            "{name}: {:.0} % of the views have fewer than {FEW_CORNERS} corners",
            100.0 * few_corners
        ));
    }
    if plain > MAX_PLAIN_VIEWS {
        failures.push(format!(
            "{name}: {:.0} % of the views are mostly plain",
            100.0 * plain
        ));
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

fn check_geometry(scene: &Scene) {
    let triangles = scene.mesh.triangle_count();
    assert!(
        (MIN_TRIANGLES..=200_000).contains(&triangles),
        "{}: {triangles} triangles",
        scene.name
    );
    assert!(
        scene.textures.len() > 15,
        "{}: only {} textures",
        scene.name,
        scene.textures.len()
    );
    let (mut lo, mut hi) = (Vec3::splat(f32::MAX), Vec3::splat(f32::MIN));
    for v in &scene.mesh.vertices {
        lo = lo.min(v.position.into());
        hi = hi.max(v.position.into());
    }
    let size = hi - lo;
    assert!(
        size.x >= 5.0 && size.x <= 9.1 && size.y >= 5.0 && size.y <= 9.1,
        "{}: extent {size}",
        scene.name
    );
}

fn check_motion(name: &str, t: &rslam_core::Trajectory) {
    assert_eq!(t.len(), trajectory::FRAMES);
    assert!((t.timestamps[1999] - 1999.0 / 20.0).abs() < 1e-9);
    let mut headings = Vec::new();
    let mut rolls = Vec::new();
    for (i, w) in t.poses.windows(2).enumerate() {
        let dt = t.timestamps[i + 1] - t.timestamps[i];
        let speed = (w[1].translation - w[0].translation).length() / dt;
        let turn = w[0].rotation.angle_between(w[1].rotation).to_degrees() / dt;
        assert!(speed <= MAX_SPEED, "{name} frame {i}: {speed:.2} m/s");
        assert!(turn <= MAX_TURN_RATE, "{name} frame {i}: {turn:.1} deg/s");
    }
    for p in &t.poses {
        let forward = p.rotation * DVec3::Z;
        headings.push(forward.y.atan2(forward.x));
        let right = p.rotation * DVec3::X;
        rolls.push(right.z.asin().to_degrees());
        let height = p.translation.z;
        assert!(
            (1.2..=1.9).contains(&height),
            "{name}: camera height {height}"
        );
    }
    let mean_speed = t.path_length() / (t.timestamps[t.len() - 1] - t.timestamps[0]);
    assert!(
        (0.12..=0.4).contains(&mean_speed),
        "{name}: mean speed {mean_speed:.2} m/s, not a hand-held walk"
    );
    let unwrapped_sweep = headings
        .windows(2)
        .map(|w| ((w[1] - w[0] + PI).rem_euclid(2.0 * PI) - PI).abs())
        .sum::<f64>()
        .to_degrees();
    assert!(
        unwrapped_sweep > 360.0,
        "{name}: heading sweeps only {unwrapped_sweep:.0} deg in total"
    );
    let roll_span = rolls.iter().cloned().fold(f64::MIN, f64::max)
        - rolls.iter().cloned().fold(f64::MAX, f64::min);
    assert!(
        roll_span > 2.0,
        "{name}: roll spans only {roll_span:.1} deg"
    );
}

fn check_free_space(name: &str, caster: &RayCaster, t: &rslam_core::Trajectory) {
    let positions: Vec<Vec3> = t.poses.iter().map(|p| p.translation.as_vec3()).collect();
    for (i, p) in positions.iter().enumerate() {
        let near = caster.nearest_surface(*p).expect("non-empty mesh");
        assert!(
            near.distance >= MIN_CLEARANCE,
            "{name} frame {i}: camera {:.2} m from a surface at {}",
            near.distance,
            near.point
        );
        if let Some(next) = positions.get(i + 1) {
            let step = *next - *p;
            assert!(
                caster.cast_within(*p, step, 1.0).is_none(),
                "{name} frame {i}: the path crosses a surface"
            );
        }
        if i % 50 == 0 {
            // Inside the room and outside every solid: rays in all directions meet front faces.
            for dir in [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z] {
                let hit = caster
                    .cast(*p, dir)
                    .unwrap_or_else(|| panic!("{name} frame {i}: ray {dir} escapes the room"));
                let facing = caster.triangle_normal(hit.triangle).dot(dir);
                assert!(
                    facing < 0.0,
                    "{name} frame {i}: ray {dir} meets a back face, the camera is inside a solid"
                );
            }
        }
    }
}

/// A summary of a view, its share of textured cells, its corners, and what is wrong with it, if
/// anything.
fn view_stats(frame: &RayCastFrame) -> (String, f64, usize, Option<String>) {
    let gray = luma(&frame.rgb);
    let (w, h) = (frame.rgb.width as usize, frame.rgb.height as usize);
    let mut depths: Vec<f32> = frame
        .depth
        .data
        .iter()
        .copied()
        .filter(|&z| z > 0.0)
        .collect();
    depths.sort_by(f32::total_cmp);
    let textured = textured_cells(&gray, w, h);
    let corners = corner_count(&gray, w, h);
    let stats = format!(
        "depth min {:.2} median {:.2} m, textured cells {:.0} %, {} corners",
        depths.first().copied().unwrap_or(0.0),
        depths.get(depths.len() / 2).copied().unwrap_or(0.0),
        100.0 * textured,
        corners
    );
    (stats, textured, corners, view_problem(frame, corners))
}

/// What is wrong with a view, if anything.
fn view_problem(frame: &RayCastFrame, corners: usize) -> Option<String> {
    let depth = &frame.depth.data;
    let valid: Vec<f32> = depth
        .iter()
        .copied()
        .filter(|&z| z > 0.0 && z <= MAX_DEPTH)
        .collect();
    let valid_share = valid.len() as f64 / depth.len() as f64;
    if valid_share < MIN_VALID_DEPTH {
        return Some(format!("only {:.1} % valid depth", 100.0 * valid_share));
    }
    let nearest = valid.iter().copied().fold(f32::MAX, f32::min);
    if nearest < MIN_CLEARANCE {
        return Some(format!("a surface at {nearest:.2} m"));
    }
    if corners < MIN_CORNERS {
        return Some(format!("only {corners} corners"));
    }
    None
}

fn luma(rgb: &RgbImage) -> Vec<f32> {
    rgb.data
        .chunks_exact(3)
        .map(|p| 0.299 * p[0] as f32 + 0.587 * p[1] as f32 + 0.114 * p[2] as f32)
        .collect()
}

fn gradient(g: &[f32], w: usize, x: usize, y: usize) -> (f32, f32) {
    let at = |x: usize, y: usize| g[y * w + x];
    (
        (at(x + 1, y) - at(x - 1, y)) * 0.5,
        (at(x, y + 1) - at(x, y - 1)) * 0.5,
    )
}

/// Share of cells of a 10 × 10 grid whose mean gradient magnitude exceeds [`CELL_GRADIENT`].
fn textured_cells(g: &[f32], w: usize, h: usize) -> f64 {
    let mut sums = [[0.0f32; 10]; 10];
    let mut counts = [[0u32; 10]; 10];
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let (gx, gy) = gradient(g, w, x, y);
            let (cx, cy) = (x * 10 / w, y * 10 / h);
            sums[cy][cx] += (gx * gx + gy * gy).sqrt();
            counts[cy][cx] += 1;
        }
    }
    let textured = (0..100)
        .filter(|i| sums[i / 10][i % 10] / counts[i / 10][i % 10].max(1) as f32 > CELL_GRADIENT)
        .count();
    textured as f64 / 100.0
}

/// Shi–Tomasi corners: local maxima (3 × 3) of the smaller structure-tensor eigenvalue over a
/// 3 × 3 window, above a fixed threshold.
fn corner_count(g: &[f32], w: usize, h: usize) -> usize {
    const THRESHOLD: f32 = 100.0;
    let mut grads = vec![(0.0f32, 0.0f32); w * h];
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            grads[y * w + x] = gradient(g, w, x, y);
        }
    }
    let mut score = vec![0.0f32; w * h];
    for y in 2..h - 2 {
        for x in 2..w - 2 {
            let (mut a, mut b, mut c) = (0.0, 0.0, 0.0);
            for dy in 0..3 {
                for dx in 0..3 {
                    let (gx, gy) = grads[(y + dy - 1) * w + x + dx - 1];
                    a += gx * gx;
                    b += gx * gy;
                    c += gy * gy;
                }
            }
            score[y * w + x] = (a + c) / 2.0 - (((a - c) / 2.0).powi(2) + b * b).sqrt();
        }
    }
    let mut count = 0;
    for y in 3..h - 3 {
        for x in 3..w - 3 {
            let s = score[y * w + x];
            let is_max = (0..9).all(|k| {
                let (dx, dy) = (k % 3, k / 3);
                score[(y + dy - 1) * w + x + dx - 1] <= s
            });
            if s > THRESHOLD && is_max {
                count += 1;
            }
        }
    }
    count
}

fn save_png(rgb: &RgbImage, path: &std::path::Path) {
    let img =
        image::RgbImage::from_raw(rgb.width, rgb.height, rgb.data.clone()).expect("buffer size");
    img.save(path).expect("write png");
}

#[test]
fn room0() {
    check_scene("room0");
}
#[test]
fn room1() {
    check_scene("room1");
}
#[test]
fn room2() {
    check_scene("room2");
}
#[test]
fn office0() {
    check_scene("office0");
}
#[test]
fn office1() {
    check_scene("office1");
}
#[test]
fn office2() {
    check_scene("office2");
}
#[test]
fn office3() {
    check_scene("office3");
}
#[test]
fn office4() {
    check_scene("office4");
}

#[test]
fn scenes_are_deterministic_and_distinct() {
    let a = build("office0").unwrap();
    let b = build("office0").unwrap();
    assert_eq!(a.content_hash(), b.content_hash());
    assert_eq!(a.default_trajectory, b.default_trajectory);
    let other = build("office1").unwrap();
    assert_ne!(a.content_hash(), other.content_hash());
    assert!(build("office9").is_none());
}

#[test]
fn agents_walk_paths_of_their_own_in_one_world_frame() {
    for name in ["room0", "office0"] {
        let paths: Vec<_> = (0..CHECKED_AGENTS)
            .map(|agent| agent_trajectory(name, agent).unwrap())
            .collect();
        assert_eq!(agent_trajectory(name, 1), Some(paths[1].clone()));
        for (a, first) in paths.iter().enumerate() {
            for second in &paths[a + 1..] {
                let apart = first
                    .poses
                    .iter()
                    .zip(&second.poses)
                    .map(|(p, q)| (p.translation - q.translation).length())
                    .sum::<f64>()
                    / first.len() as f64;
                assert!(
                    apart > 0.5,
                    "{name}: agents only {apart:.2} m apart on average"
                );
            }
        }
    }
    assert!(agent_trajectory("office9", 1).is_none());
}

/// Writes preview images of every scene (a plan view and four frames of the default
/// trajectory) to `$RSLAM_PREVIEW_DIR` or the temp dir. `cargo test -p rslam-render -- --ignored previews`
#[test]
#[ignore]
fn previews() {
    let dir = std::env::var_os("RSLAM_PREVIEW_DIR").map_or_else(
        || std::env::temp_dir().join("rslam-scene-previews"),
        Into::into,
    );
    std::fs::create_dir_all(&dir).unwrap();
    let quarter = Intrinsics {
        width: 300,
        height: 170,
        fx: 150.0,
        fy: 150.0,
        cx: 149.5,
        cy: 84.5,
    };
    for name in BUILTIN_SCENES {
        let start = std::time::Instant::now();
        let scene = build(name).unwrap();
        let seconds = start.elapsed().as_secs_f64();
        let (triangles, textures) = (scene.mesh.triangle_count(), scene.textures.len());
        eprintln!("{name}: {triangles} triangles, {textures} textures, built in {seconds:.2} s");
        let caster = RayCaster::new(&scene);
        let t = scene.default_trajectory.as_ref().unwrap();
        for i in [0, 500, 1000, 1500] {
            save_png(
                &caster.render(&t.poses[i], &quarter).rgb,
                &dir.join(format!("{name}-{i:04}.png")),
            );
        }
        let top = rslam_core::Pose::new(
            glam::DQuat::from_mat3(&glam::DMat3::from_cols(DVec3::X, -DVec3::Y, -DVec3::Z)),
            DVec3::new(0.0, 0.0, 2.45),
        );
        let plan = Intrinsics {
            width: 480,
            height: 400,
            fx: 90.0,
            fy: 90.0,
            cx: 239.5,
            cy: 199.5,
        };
        let mut image = caster.render(&top, &plan).rgb;
        // Trajectory in red, projected onto the plan view.
        for p in t.poses.iter().step_by(4) {
            let c = top.inverse().transform_point(p.translation);
            let (x, y) = (plan.fx * c.x / c.z + plan.cx, plan.fy * c.y / c.z + plan.cy);
            if x >= 0.0 && y >= 0.0 && (x as u32) < plan.width && (y as u32) < plan.height {
                let i = 3 * (y as usize * plan.width as usize + x as usize);
                image.data[i..i + 3].copy_from_slice(&[255, 0, 0]);
            }
        }
        save_png(&image, &dir.join(format!("{name}-plan.png")));
    }
}
