//! The rasterizer's depth against the CPU ray-cast oracle, per pixel, for a built-in scene and
//! for a mesh loaded through each loader (PLY binary with quads, PLY ASCII, OBJ+MTL, GLB).

mod fixtures;

use rslam_core::{Intrinsics, Pose};
use rslam_render::raster::{depth_agreement, DepthAgreement};
use rslam_render::raycast::RayCaster;
use rslam_render::{load_scene, Scene};

/// Relative depth error allowed where both hit (the bar).
const MAX_RELATIVE_ERROR: f32 = 1e-4;

fn camera() -> Intrinsics {
    fixtures::SMALL_CAMERA
}

fn assert_agrees(scene: &Scene, poses: &[Pose]) {
    let k = camera();
    let oracle = RayCaster::new(scene);
    for (i, ((_, depth), pose)) in fixtures::render(scene, poses, k)
        .iter()
        .zip(poses)
        .enumerate()
    {
        let expected = oracle.depth_image(pose, &k);
        let a: DepthAgreement = depth_agreement(depth, &expected);
        let pixels = k.pixel_count();
        assert!(
            a.compared > pixels / 2,
            "{} pose {i}: too few comparable pixels: {a:?}",
            scene.name
        );
        assert!(
            a.max_relative_error < MAX_RELATIVE_ERROR,
            "{} pose {i}: depth differs from the oracle: {a:?}",
            scene.name
        );
        assert_eq!(
            a.mask_mismatches, 0,
            "{} pose {i}: hit/miss masks differ off silhouettes: {a:?}",
            scene.name
        );
    }
}

#[test]
fn builtin_scene_depth_matches_ray_cast() {
    let scene = load_scene("room0").expect("built-in scene");
    let traj = scene
        .default_trajectory
        .as_ref()
        .expect("default trajectory");
    let poses: Vec<Pose> = traj.poses.iter().step_by(250).copied().collect();
    assert_agrees(&scene, &poses);
}

#[test]
fn every_loader_renders_depth_matching_ray_cast() {
    let dir = tempfile::tempdir().unwrap();
    let room = fixtures::FixtureRoom::new();
    for path in room.write_all(dir.path()) {
        let scene = load_scene(path.to_str().unwrap())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        assert_eq!(
            scene.mesh.triangle_count(),
            room.triangle_count(),
            "{}",
            path.display()
        );
        assert_agrees(&scene, &room.poses());
    }
}
