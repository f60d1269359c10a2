//! Culling on scenes made here: a room seen through one wall, and a plane hidden behind a wall.

use std::f64::consts::FRAC_PI_2;

use glam::{DQuat, DVec3};
use rslam_core::dataset::{DatasetViews, View, ViewCamera};
use rslam_core::{Intrinsics, Pose};

use super::tests::{options, Files, SAMPLES};
use super::*;

/// A square of side `2·half` in the plane x = `x`, centred on the x axis.
fn wall(x: f32, half: f32, first: u32) -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let corners = [[-half, -half], [half, -half], [half, half], [-half, half]];
    let positions = corners.iter().map(|&[y, z]| [x, y, z]).collect();
    let faces = vec![[first, first + 1, first + 2], [first, first + 2, first + 3]];
    (positions, faces)
}

/// The six faces of the cube [0, 4]³, two triangles each.
fn room() -> (Vec<[f32; 3]>, Vec<[u32; 3]>) {
    let mut positions = Vec::new();
    for i in 0..8u32 {
        positions.push([i & 1, (i >> 1) & 1, (i >> 2) & 1].map(|b| b as f32 * 4.0));
    }
    let quads = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let faces = quads
        .iter()
        .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
        .collect();
    (positions, faces)
}

/// A 100×100 camera with a 90° field of view whose depth files reach 10 m.
fn camera() -> ViewCamera {
    ViewCamera {
        name: "rgb".into(),
        intrinsics: Intrinsics {
            width: 100,
            height: 100,
            fx: 50.0,
            fy: 50.0,
            cx: 49.5,
            cy: 49.5,
        },
        max_depth_m: Some(10.0),
    }
}

/// Cameras at `positions` looking along world +x (`true`) or −x.
fn views(at: &[(DVec3, bool)]) -> DatasetViews {
    DatasetViews {
        cameras: vec![camera()],
        views: at
            .iter()
            .map(|&(position, along_x)| View {
                camera: 0,
                world_from_camera: Pose::new(
                    DQuat::from_rotation_y(if along_x { FRAC_PI_2 } else { -FRAC_PI_2 }),
                    position,
                ),
            })
            .collect(),
    }
}

fn culled(culling: Culling) -> ReconOptions {
    ReconOptions {
        culling,
        ..options()
    }
}

#[test]
fn culled_to_the_observed_wall_the_room_against_itself_and_the_wall_alone_are_perfect() {
    let files = Files::new();
    let (v, f) = room();
    let gt = files.ply("room.ply", &v, &f, false);
    let (v, f) = wall(4.0, 2.0, 0);
    let shifted: Vec<[f32; 3]> = v.iter().map(|p| [p[0], p[1] + 2.0, p[2] + 2.0]).collect();
    let seen_wall = files.ply("wall.ply", &shifted, &f, false);
    // Two poses near the room's centre, both facing the wall x = 4 and seeing nothing else.
    let path = views(&[
        (DVec3::new(2.0, 2.0, 2.0), true),
        (DVec3::new(2.1, 2.0, 2.0), true),
    ]);

    for culling in [Culling::Frustum, Culling::Visible] {
        let itself = evaluate_reconstruction(&gt, &gt, &culled(culling), Some(&path)).unwrap();
        assert!(itself.accuracy_cm < 1e-4, "{culling}: {itself:?}");
        assert!(itself.completion_cm < 1e-4, "{culling}");
        assert_eq!(itself.completion_ratio_percent, 100.0, "{culling}");
        assert_eq!(itself.views, 2);
        // The wall is a sixth of the room; the frustums take 3.96² of its 4² m².
        let kept = itself.ground_truth.kept_percent();
        assert!((16.335 - kept).abs() < 0.5, "{culling}: {kept}");

        let wall_only = evaluate_reconstruction(&seen_wall, &gt, &culled(culling), Some(&path));
        let wall_only = wall_only.unwrap();
        assert!(wall_only.accuracy_cm < 1e-4, "{wall_only:?}");
        assert!(wall_only.completion_cm < 1e-4, "{wall_only:?}");
        assert_eq!(wall_only.completion_ratio_percent, 100.0);
    }

    let uncut = evaluate_reconstruction(&seen_wall, &gt, &culled(Culling::None), None).unwrap();
    assert!(uncut.accuracy_cm < 1e-4);
    assert!(uncut.completion_cm > 100.0, "{uncut:?}");
    assert!(uncut.completion_ratio_percent < 20.0, "{uncut:?}");
    assert_eq!(uncut.ground_truth.kept, SAMPLES);
}

#[test]
fn a_plane_behind_a_wall_is_culled_by_visible_and_kept_by_frustum_until_a_view_sees_it() {
    let files = Files::new();
    let (mut v, mut f) = wall(2.0, 1.0, 0);
    let (hidden_v, hidden_f) = wall(4.0, 1.0, 4);
    v.extend(hidden_v);
    f.extend(hidden_f);
    let gt = files.ply("wall_and_plane.ply", &v, &f, false);
    let (v, f) = wall(2.0, 1.0, 0);
    let front_wall = files.ply("front_wall.ply", &v, &f, false);
    let front_only = views(&[(DVec3::ZERO, true)]);

    let frustum = evaluate_reconstruction(
        &front_wall,
        &gt,
        &culled(Culling::Frustum),
        Some(&front_only),
    );
    let frustum = frustum.unwrap();
    assert_eq!(
        frustum.ground_truth.kept, SAMPLES,
        "both planes are in view"
    );
    assert!(
        (frustum.completion_ratio_percent - 50.0).abs() < 2.0,
        "{frustum:?}"
    );

    let visible = evaluate_reconstruction(
        &front_wall,
        &gt,
        &culled(Culling::Visible),
        Some(&front_only),
    );
    let visible = visible.unwrap();
    let kept = visible.ground_truth.kept_percent();
    assert!(
        (kept - 50.0).abs() < 2.0,
        "only the front wall is seen: {kept}"
    );
    assert_eq!(visible.completion_ratio_percent, 100.0, "{visible:?}");
    assert!(visible.completion_cm < 1e-4);

    // A second camera behind the plane, facing it, sees what the wall hid from the first.
    let both_sides = views(&[(DVec3::ZERO, true), (DVec3::new(6.0, 0.0, 0.0), false)]);
    let seen = evaluate_reconstruction(&gt, &gt, &culled(Culling::Visible), Some(&both_sides));
    assert_eq!(seen.unwrap().ground_truth.kept, SAMPLES);
}

#[test]
fn culling_without_views_or_outside_them_is_a_one_line_error() {
    let files = Files::new();
    let (v, f) = wall(2.0, 1.0, 0);
    let gt = files.ply("wall.ply", &v, &f, false);
    let err = evaluate_reconstruction(&gt, &gt, &culled(Culling::Visible), None).unwrap_err();
    assert_eq!(
        err.to_string(),
        "culling = visible: expected the ground-truth cameras of the dataset (--dataset DIR), or culling none"
    );
    let looking_away = views(&[(DVec3::ZERO, false)]);
    let err = evaluate_reconstruction(&gt, &gt, &culled(Culling::Frustum), Some(&looking_away));
    let message = err.unwrap_err().to_string();
    assert!(
        message.contains("wall.ply")
            && message.contains("no point of it lies in what the ground-truth cameras saw"),
        "{message}"
    );
    assert!(!message.contains('\n'));
}
