//! People walking through a built-in scene (`actors`) and things moved through it (`objects`)
//! against the CPU ray-cast oracle: colour, depth and the instance mask where they are in view,
//! the static scene untouched elsewhere, and none of them ever touching the scene, another or
//! the camera at any instant (checked every 10 ms; a walker's footprint against the scene
//! every 50 ms).

mod fixtures;

use glam::{DVec3, Vec2, Vec3};
use obvhs::triangle::Triangle;
use rslam_core::{DepthImage, Intrinsics, Pose, SurfaceBvh};
use rslam_render::actors::{
    Actors, CameraTrack, ObjectParams, RigidOrigin, WalkerParams, World, CAMERA_CLEARANCE,
    SEEN_DISTANCE, SEEN_HALF_ANGLE,
};
use rslam_render::raster::{color_agreement, depth_agreement, edge_mask};
use rslam_render::raycast::RayCaster;
use rslam_render::{load_scene, Rasterizer, Scene};

const RATE_HZ: f64 = 20.0;
const FRAMES: usize = 400;
const CAMERA: Intrinsics = fixtures::SMALL_CAMERA;
const PARAMS: WalkerParams = WalkerParams {
    count: 3,
    speed_m_s: 1.1,
    near_m: 0.8,
    ahead_m: None,
};

fn walking(params: &WalkerParams) -> World<'_> {
    World {
        walkers: Some(params),
        ..World::default()
    }
}

fn moving(params: &ObjectParams) -> World<'_> {
    World {
        objects: Some(params),
        ..World::default()
    }
}

/// A built-in scene and the first poses of its default path.
fn along_path(name: &str) -> (Scene, Vec<Pose>, CameraTrack) {
    let scene = load_scene(name).expect("built-in scene");
    let poses: Vec<Pose> = scene.default_trajectory.as_ref().unwrap().poses[..FRAMES].to_vec();
    let track = CameraTrack {
        times: (0..FRAMES).map(|i| i as f64 / RATE_HZ).collect(),
        positions: poses.iter().map(|p| p.translation.as_vec3()).collect(),
        axes: (poses.iter())
            .map(|p| (p.rotation * DVec3::Z).as_vec3())
            .collect(),
    };
    (scene, poses, track)
}

/// The scene less the triangles the actors take over (a door that swings): the world that stays.
fn static_world(scene: &Scene, actors: &Actors) -> Scene {
    let mut world = scene.clone();
    world.mesh.indices = actors.scene_indices(scene).into_owned();
    world
}

/// The static world with the actors' triangles at `t` appended: what the oracle casts rays
/// into; and the instance-mask id of every triangle of it (0 the scene's, k + 1 actor k's).
fn with_actors_at(scene: &Scene, actors: &Actors, t: f64) -> (Scene, Vec<u16>) {
    let posed = actors.mesh_at(t);
    let scene = &static_world(scene, actors);
    let mut ids = vec![0u16; scene.mesh.triangle_count()];
    ids.extend((posed.mesh.indices.chunks(3)).map(|corners| {
        let vertex = corners[0] as usize;
        let walker = (posed.actor_vertices.iter()).position(|r| r.contains(&vertex));
        walker.expect("every vertex is a walker's") as u16 + 1
    }));
    let mut combined = scene.clone();
    let first = combined.mesh.vertices.len() as u32;
    combined.mesh.vertices.extend(posed.mesh.vertices);
    (combined.mesh.indices).extend(posed.mesh.indices.iter().map(|i| first + i));
    combined.textures.extend(actors.textures().iter().cloned());
    (combined, ids)
}

/// Frames whose camera sees a walker's chest nearest, in front and inside the image.
fn frames_with_walkers_in_view(actors: &Actors, poses: &[Pose], count: usize) -> Vec<usize> {
    let mut seen: Vec<(f64, usize)> = (0..poses.len())
        .step_by(4)
        .filter_map(|i| {
            let t = i as f64 / RATE_HZ;
            let camera_from_world = poses[i].inverse();
            (actors.poses_at(t).iter())
                .map(|w| {
                    camera_from_world.transform_point(DVec3::new(
                        w.position.x as f64,
                        w.position.y as f64,
                        1.2,
                    ))
                })
                .filter(|p| p.z > 0.6 && (p.x / p.z).abs() < 0.8 && (p.y / p.z).abs() < 0.4)
                .map(|p| p.z)
                .reduce(f64::min)
                .map(|z| (z, i))
        })
        .collect();
    seen.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Nearest first, frames at least a second apart.
    let mut chosen: Vec<usize> = Vec::new();
    for (_, i) in seen {
        if chosen.iter().all(|&c| c.abs_diff(i) >= 20) {
            chosen.push(i);
        }
        if chosen.len() == count {
            break;
        }
    }
    chosen
}

#[test]
fn walkers_in_view_match_the_oracle_and_leave_the_rest_of_the_frame_alone() {
    let (scene, poses, track) = along_path("room0");
    let actors =
        std::sync::Arc::new(Actors::plan(&scene, walking(&PARAMS), 8, &track).expect("walkers"));
    let tops: Vec<usize> = actors.walkers().iter().map(|w| w.top).collect();
    assert!(
        tops.contains(&0) && tops.iter().any(|&t| t != 0),
        "a plain top and a patterned one against the oracle: {tops:?}"
    );
    let frames = frames_with_walkers_in_view(&actors, &poses, 3);
    assert_eq!(frames.len(), 3, "walkers come into view: {frames:?}");
    matches_the_oracle(&scene, actors, &poses, &frames);
}

/// On each of `frames` along `poses`: colour, depth and mask against the oracle; depth outside
/// the actors equal to a render of the static world; and the actors hide some of it.
fn matches_the_oracle(
    scene: &Scene,
    actors: std::sync::Arc<Actors>,
    poses: &[Pose],
    frames: &[usize],
) {
    let views: Vec<Pose> = frames.iter().map(|&i| poses[i]).collect();
    let ctx = fixtures::gpu();
    let mut with =
        Rasterizer::with_actors(ctx, scene, CAMERA, Default::default(), Some(actors.clone()))
            .expect("upload");
    let rendered = fixtures::render_with_masks(ctx, &mut with, &views, |r, v| {
        r.pose_actors(ctx, frames[v] as f64 / RATE_HZ)
    });
    let world = static_world(scene, &actors);
    let mut without = Rasterizer::new(ctx, &world, CAMERA).expect("upload");
    let statics = fixtures::render_with(ctx, &mut without, &views, |_, _| {});
    let scene_triangles = world.mesh.triangle_count() as u32;
    for (v, &i) in frames.iter().enumerate() {
        let t = i as f64 / RATE_HZ;
        let (combined, triangle_ids) = with_actors_at(scene, &actors, t);
        let oracle = RayCaster::new(&combined);
        let expected = oracle.render(&views[v], &CAMERA);
        let on_actor: Vec<bool> = (expected.triangles.iter())
            .map(|t| t.is_some_and(|t| t >= scene_triangles))
            .collect();
        let actor_share = on_actor.iter().filter(|&&a| a).count() as f64 / on_actor.len() as f64;
        assert!(
            actor_share > 0.02,
            "frame {i}: actors cover {actor_share:.3} of the view"
        );
        let (rgb, depth, mask) = &rendered[v];
        let d = depth_agreement(depth, &expected.depth);
        assert!(
            d.max_relative_error < 1e-4 && d.mask_mismatches == 0,
            "frame {i}: {d:?}"
        );
        let edges = edge_mask(depth, &expected, &oracle.surface_edges(&expected));
        let c = color_agreement(rgb, depth, &expected, &edges, 3);
        eprintln!("frame {i}: actors {actor_share:.3} of the view; colour {c:?}");
        assert!(
            c.worst_mean_abs_error() < 0.75 && c.off_fraction() < 0.01,
            "frame {i}: {c:?}"
        );
        let near_actor = grown(&on_actor, CAMERA.width as usize, 2);
        let static_depth = &statics[v].1;
        let moved = (0..on_actor.len())
            .filter(|&p| !near_actor[p] && depth.data[p] != static_depth.data[p])
            .count();
        assert_eq!(moved, 0, "frame {i}: depth changed away from the actors");
        let hidden = (0..on_actor.len())
            .filter(|&p| on_actor[p] && !edges[p] && depth.data[p] < static_depth.data[p] - 1e-3)
            .count();
        assert!(hidden > 0, "frame {i}: the actors hide some of the room");
        check_depth_is_metric(depth);
        // The mask is the oracle's object id off surface edges (where a sliver of a triangle
        // through a pixel's centre may go either way), and on all but a few edge pixels.
        let expected_ids =
            (expected.triangles.iter()).map(|t| t.map_or(0, |t| triangle_ids[t as usize]));
        let wrong: Vec<usize> = (mask.data.iter().zip(expected_ids).enumerate())
            .filter(|(_, (got, want))| got != &want)
            .map(|(p, _)| p)
            .collect();
        let off_edges = wrong.iter().filter(|&&p| !edges[p]).count();
        assert_eq!(off_edges, 0, "frame {i}: mask ids unlike the oracle's");
        let actor_pixels = on_actor.iter().filter(|&&a| a).count();
        assert!(
            wrong.len() * 200 < actor_pixels,
            "frame {i}: {} edge pixels of {actor_pixels} unlike the oracle's",
            wrong.len()
        );
    }
}

/// `mask` with every pixel within `radius` of a set pixel set.
fn grown(mask: &[bool], width: usize, radius: i64) -> Vec<bool> {
    let height = mask.len() / width;
    (0..mask.len())
        .map(|p| {
            let (x, y) = ((p % width) as i64, (p / width) as i64);
            (-radius..=radius).any(|dy| {
                (-radius..=radius).any(|dx| {
                    let (nx, ny) = (x + dx, y + dy);
                    (0..width as i64).contains(&nx)
                        && (0..height as i64).contains(&ny)
                        && mask[ny as usize * width + nx as usize]
                })
            })
        })
        .collect()
}

fn check_depth_is_metric(depth: &DepthImage) {
    assert!(depth
        .data
        .iter()
        .all(|&z| z == 0.0 || (0.05..20.0).contains(&z)));
}

#[test]
fn walkers_never_touch_the_scene_each_other_or_the_camera_and_pass_near_it() {
    // A large office, room for three walkers passing the camera.
    let (scene, _, track) = along_path("office2");
    let actors = Actors::plan(&scene, walking(&PARAMS), 11, &track).expect("walkers");
    let closest = never_touch(&scene, &actors, &track);
    for (k, near) in closest.iter().enumerate() {
        assert!(
            *near <= PARAMS.near_m + 0.15 + SAMPLING,
            "walker {k} comes no nearer than {near} m"
        );
    }
}

/// Asserts that no walker of `actors` touches the scene, another walker or the camera on
/// `track` (every 10 ms, the scene every 50 ms) and that every posed vertex stays in its
/// walker's footprint; the closest each comes to the camera, metres.
fn never_touch(scene: &Scene, actors: &Actors, track: &CameraTrack) -> Vec<f32> {
    let obstacles = obstacles(scene);
    let duration = track.times.last().copied().unwrap();
    let mut closest = vec![f32::INFINITY; actors.walkers().len()];
    let steps = (duration / 0.01) as usize;
    for step in 0..=steps {
        let t = step as f64 * 0.01;
        let eye = track.at(t).truncate();
        let poses = actors.poses_at(t);
        let segments: Vec<Vec<Vec2>> = (actors.walkers().iter().zip(&poses))
            .map(|(w, p)| segment_points(w.footprint.segment(p.position, p.heading)))
            .collect();
        for (k, walker) in actors.walkers().iter().enumerate() {
            let to_eye = nearest(&segments[k], &[eye]);
            closest[k] = closest[k].min(to_eye - walker.footprint.radius);
            assert!(
                to_eye >= walker.footprint.radius + CAMERA_CLEARANCE - SAMPLING,
                "walker {k} at {t} s is {to_eye} m from the camera"
            );
            for (j, other) in actors.walkers().iter().enumerate().skip(k + 1) {
                let gap = nearest(&segments[k], &segments[j]);
                let touching = walker.footprint.radius + other.footprint.radius - SAMPLING;
                assert!(gap >= touching, "walkers {k} and {j} touch at {t} s");
            }
            // Every fifth instant: the scene keeps out of the footprint, at every height.
            if step % 5 != 0 {
                continue;
            }
            let mut z = 0.05;
            while z < walker.body.height() {
                for p in &segments[k] {
                    let gap =
                        (obstacles.nearest(p.extend(z))).map_or(f32::INFINITY, |n| n.distance);
                    assert!(
                        gap > walker.footprint.radius - SAMPLING,
                        "walker {k} meets the scene {gap} m from its footprint's axis at {p}, {z} m up, at {t} s"
                    );
                }
                z += 0.05;
            }
        }
        // Every tenth instant: each footprint holds its walker's posed vertices.
        if step % 10 == 0 {
            let posed = actors.mesh_at(t);
            let mut vertices = posed.mesh.vertices.iter();
            for (walker, pose) in actors.walkers().iter().zip(&poses) {
                let count = posed.mesh.vertices.len() / actors.walkers().len();
                for v in vertices.by_ref().take(count) {
                    let p = Vec2::new(v.position[0], v.position[1]);
                    assert!(
                        walker.footprint.holds(pose.position, pose.heading, p),
                        "a vertex leaves its footprint at {t} s"
                    );
                }
            }
        }
    }
    closest
}

/// A walker ahead (`COUNT/SPEED/NEAR/AHEAD`) keeps in front of the camera, as the person a
/// camera follows in Bonn's `person_tracking`: on office2, whose floor in view has room all
/// along, its centre stays within [`SEEN_HALF_ANGLE`] of the camera's axis over the floor and
/// under [`SEEN_DISTANCE`] at every instant checked, the manifest's share says so, and neither
/// it nor the walker passing ever touches the scene, the other or the camera. The walker drawn
/// to pass is in view under half the time.
#[test]
fn a_walker_ahead_keeps_in_front_of_the_camera() {
    let (scene, _, track) = along_path("office2");
    let params = WalkerParams {
        count: 2,
        speed_m_s: 1.2,
        near_m: 0.5,
        ahead_m: Some(1.5),
    };
    let duration = track.times.last().copied().unwrap();
    for seed in [3, 11] {
        let actors = Actors::plan(&scene, walking(&params), seed, &track).expect("walkers");
        let [ahead, passing] = actors.walkers() else {
            panic!("two walkers");
        };
        assert_eq!((ahead.ahead_m, passing.ahead_m), (Some(1.5), None));
        let steps = (duration / 0.01) as usize;
        let in_view = (0..=steps)
            .filter(|&step| {
                let t = step as f64 * 0.01;
                let position = ahead.path.at(t).position;
                in_front(&track, t, position)
                    && position.distance(track.at(t).truncate()) <= SEEN_DISTANCE
            })
            .count() as f32
            / (steps + 1) as f32;
        assert!(
            in_view >= 0.99,
            "seed {seed}: in view {in_view} of the time"
        );
        assert!(
            (ahead.in_view_share - in_view).abs() <= 0.01,
            "seed {seed}: reported in view {}, checked {in_view}",
            ahead.in_view_share
        );
        assert!(
            passing.in_view_share < 0.5,
            "seed {seed}: {}",
            passing.in_view_share
        );
        never_touch(&scene, &actors, &track);
    }
}

/// One walker at 1.2 m/s kept `ahead_m` in front of the camera.
fn one_walker_ahead(ahead_m: f32) -> WalkerParams {
    WalkerParams {
        count: 1,
        speed_m_s: 1.2,
        near_m: 0.8,
        ahead_m: Some(ahead_m),
    }
}

/// On room1, whose floor in view is narrow, a walker ahead that stopped anywhere its width
/// passes came to a stop face to the furniture on these seeds, and the plan was refused: it then
/// stops only where it can turn round, and still never touches the scene or the camera.
#[test]
fn a_walker_ahead_fits_a_small_room() {
    let (scene, _, track) = along_path("room1");
    for seed in [0, 3] {
        let actors = Actors::plan(&scene, walking(&one_walker_ahead(1.5)), seed, &track)
            .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        let [ahead] = actors.walkers() else {
            panic!("one walker");
        };
        assert!(
            ahead.in_view_share > 0.3,
            "seed {seed}: in view {} of the time",
            ahead.in_view_share
        );
        never_touch(&scene, &actors, &track);
    }
}

/// On room2 no way 2 m ahead keeps clear of the furniture and the camera: the walker ahead keeps
/// nearer, 0.25 m at a time, walks as if asked for that distance, says so in `ahead_m`, and
/// touches nothing.
#[test]
fn a_walker_ahead_keeps_nearer_where_the_floor_has_no_room_that_far() {
    let (scene, _, track) = along_path("room2");
    let actors =
        Actors::plan(&scene, walking(&one_walker_ahead(2.0)), 0, &track).expect("a walker ahead");
    let [ahead] = actors.walkers() else {
        panic!("one walker");
    };
    let kept = ahead.ahead_m.expect("the walker ahead");
    assert!((0.9..2.0).contains(&kept), "kept {kept} m ahead");
    let nearer =
        Actors::plan(&scene, walking(&one_walker_ahead(kept)), 0, &track).expect("a walker ahead");
    let duration = track.times.last().copied().unwrap();
    for step in 0..=(duration / 0.05) as usize {
        let t = step as f64 * 0.05;
        assert_eq!(actors.poses_at(t), nearer.poses_at(t), "at {t} s");
    }
    never_touch(&scene, &actors, &track);
}

/// A severity's walkers are those of the one below and one more (`actors:1` to `actors:3`, and
/// `actors:4` to `actors:5` with the first walker ahead): planned with the same seed, the first
/// COUNT walkers of COUNT + 1 walk exactly as the COUNT walkers do, since each walker gives way
/// to those planned before it and draws from a stream of its own.
#[test]
fn one_more_walker_leaves_the_others_walks_as_they_were() {
    let (scene, _, track) = along_path("office2");
    let duration = track.times.last().copied().unwrap();
    for (count, ahead_m) in [(1, None), (2, None), (2, Some(1.5))] {
        let params = |count| WalkerParams {
            count,
            speed_m_s: 1.2,
            near_m: 1.0,
            ahead_m,
        };
        let fewer = Actors::plan(&scene, walking(&params(count)), 5, &track).expect("walkers");
        let more = Actors::plan(&scene, walking(&params(count + 1)), 5, &track).expect("walkers");
        assert_eq!(more.walkers().len(), fewer.walkers().len() + 1);
        for step in 0..=(duration / 0.05) as usize {
            let t = step as f64 * 0.05;
            let (a, b) = (fewer.poses_at(t), more.poses_at(t));
            for (k, (a, b)) in a.iter().zip(&b).enumerate() {
                assert_eq!(
                    a, b,
                    "{count} walkers, ahead {ahead_m:?}: walker {k} at {t} s"
                );
            }
        }
    }
}

/// Each walker passes within NEAR of the camera in its view (the issue's "passing close to the
/// camera and occluding large parts of it"), not only beside or behind it: over a dozen seeds,
/// while its centre lies within [`SEEN_HALF_ANGLE`] of the camera's axis over the floor, it comes
/// within NEAR (and the tolerance giving way allows), and its `closest_in_view_m` says how near.
/// Meetings drawn all round the camera fail this on 2 of these 12 seeds.
#[test]
fn walkers_pass_near_the_camera_in_its_view() {
    // Room in front of the camera for one walker at every instant.
    let (scene, _, track) = along_path("office2");
    let params = WalkerParams {
        count: 1,
        speed_m_s: 1.2,
        near_m: 0.5,
        ahead_m: None,
    };
    let duration = track.times.last().copied().unwrap();
    for seed in 0..12 {
        let actors = Actors::plan(&scene, walking(&params), seed, &track).expect("walker");
        let walker = &actors.walkers()[0];
        let closest_in_view = (0..=(duration / 0.01) as usize)
            .filter_map(|step| {
                let t = step as f64 * 0.01;
                let pose = walker.path.at(t);
                let body = segment_points(walker.footprint.segment(pose.position, pose.heading));
                in_front(&track, t, pose.position)
                    .then(|| nearest(&body, &[track.at(t).truncate()]) - walker.footprint.radius)
            })
            .fold(f32::INFINITY, f32::min);
        assert!(
            closest_in_view <= params.near_m + 0.15 + SAMPLING,
            "seed {seed}: the walker comes no nearer than {closest_in_view} m in the camera's view"
        );
        // What the manifest reports: checked every 5 ms with the exact distance, so no farther
        // than this check's and no nearer than it by more than sampling and 10 ms of closing.
        let reported = walker.closest_in_view_m.expect("the walker passes in view");
        assert!(
            reported <= closest_in_view + 1e-4 && closest_in_view - reported <= SAMPLING + 0.03,
            "seed {seed}: closest in view reported {reported} m, checked {closest_in_view} m"
        );
    }
}

/// Every walker walks through the room: at severity 5's setting (three walkers at 1.4 m/s
/// passing 0.4 m from the camera) on office2, each moves at walking pace for at least 60 % of
/// 20 s and ranges over more than 1.5 m. Taking the first walk that fit, 6 of these 15 walkers
/// walked under 60 % of the time, four under half, giving way (the least now walks 72 %).
#[test]
fn walkers_keep_walking_and_range_over_the_room() {
    let (scene, _, track) = along_path("office2");
    let params = WalkerParams {
        count: 3,
        speed_m_s: 1.4,
        near_m: 0.4,
        ahead_m: None,
    };
    let duration = track.times.last().copied().unwrap();
    let steps = (duration / 0.05) as usize;
    for seed in 0..5 {
        let actors = Actors::plan(&scene, walking(&params), seed, &track).expect("walkers");
        for (k, walker) in actors.walkers().iter().enumerate() {
            let at: Vec<Vec2> = (0..=steps)
                .map(|i| walker.path.at(i as f64 * 0.05).position)
                .collect();
            let walking = (at.windows(2))
                .filter(|p| p[0].distance(p[1]) >= 0.5 * params.speed_m_s * 0.05)
                .count();
            assert!(
                walking as f64 >= 0.6 * steps as f64,
                "seed {seed}: walker {k} walks {walking} of {steps} steps of 50 ms"
            );
            let (low, high) = (at.iter())
                .fold((Vec2::INFINITY, Vec2::NEG_INFINITY), |(l, h), &p| {
                    (l.min(p), h.max(p))
                });
            let range = (high - low).max_element();
            assert!(
                range > 1.5,
                "seed {seed}: walker {k} stays within {range} m"
            );
        }
    }
}

/// room1, the most furnished room, with walkers passing 0.5 m from the camera over 20 s: where an
/// earlier walker's route leaves a later one no way, all of them are drawn again, so two walkers
/// plan on seeds 0–4 (without the redraws 12 of the first 20 seeds refused, among them 0, 1 and
/// 2, on 2026-11-29's planner). Three do not fit on seed 2: the job refuses, naming the walker
/// and why.
#[test]
fn a_crowded_room_draws_its_walkers_again_until_they_fit() {
    let (scene, _, track) = along_path("room1");
    let two = WalkerParams {
        count: 2,
        speed_m_s: 1.2,
        near_m: 0.5,
        ahead_m: None,
    };
    for seed in 0..5 {
        let planned = Actors::plan(&scene, walking(&two), seed, &track);
        assert!(planned.is_ok(), "seed {seed}: {:?}", planned.err());
    }
    let three = WalkerParams { count: 3, ..two };
    let refused = format!(
        "{:?}",
        Actors::plan(&scene, walking(&three), 2, &track).err()
    );
    assert!(
        refused.contains("walker 3 of 3") && refused.contains("walking a quarter of the time"),
        "three walkers, seed 2: {refused}"
    );
}

/// Metres between the points a footprint's segment is checked at, halved: what sampling can
/// miss of a distance.
const SAMPLING: f32 = 0.005;

/// Points along a segment no farther apart than twice [`SAMPLING`].
/// Whether the floor point `p` lies within [`SEEN_HALF_ANGLE`] of the camera's axis over the
/// floor at `t`.
fn in_front(track: &CameraTrack, t: f64, p: Vec2) -> bool {
    let forward = track.axis_at(t).truncate().normalize_or_zero();
    (p - track.at(t).truncate())
        .normalize_or_zero()
        .dot(forward)
        >= SEEN_HALF_ANGLE.cos()
}

fn segment_points([a, b]: [Vec2; 2]) -> Vec<Vec2> {
    let pieces = (a.distance(b) / (2.0 * SAMPLING)).ceil().max(1.0) as usize;
    (0..=pieces)
        .map(|i| a.lerp(b, i as f32 / pieces as f32))
        .collect()
}

/// The least distance between a point of `a` and a point of `b`.
fn nearest(a: &[Vec2], b: &[Vec2]) -> f32 {
    a.iter()
        .flat_map(|p| b.iter().map(move |q| p.distance(*q)))
        .fold(f32::INFINITY, f32::min)
}

/// The scene's triangles but the floor and what lies flat on it (rugs), which walkers stand on,
/// and what is above their heads.
fn obstacles(scene: &Scene) -> SurfaceBvh {
    let p = |i: u32| Vec3::from(scene.mesh.vertices[i as usize].position);
    let triangles = (scene.mesh.indices.chunks_exact(3))
        .map(|t| [p(t[0]), p(t[1]), p(t[2])])
        .filter(|[a, b, c]| {
            let flat = (*b - *a).cross(*c - *a).normalize().z.abs() > 0.9;
            !(flat && a.z.max(b.z).max(c.z) < 0.03) && a.z.min(b.z).min(c.z) < 2.05
        })
        .map(|[a, b, c]| Triangle {
            v0: a.into(),
            v1: b.into(),
            v2: c.into(),
        })
        .collect();
    SurfaceBvh::new(triangles)
}

#[test]
fn the_same_seed_gives_the_same_walkers_and_another_seed_others() {
    let (scene, _, track) = along_path("room0");
    let a = Actors::plan(&scene, walking(&PARAMS), 3, &track).unwrap();
    let b = Actors::plan(&scene, walking(&PARAMS), 3, &track).unwrap();
    let c = Actors::plan(&scene, walking(&PARAMS), 5, &track).unwrap();
    for t in [0.0, 3.3, 17.9] {
        assert_eq!(a.poses_at(t), b.poses_at(t));
        assert_ne!(a.poses_at(t), c.poses_at(t));
    }
    let position = |x: &Actors| x.poses_at(5.0)[0].position;
    assert!(position(&a).distance(position(&c)) > 0.0);
}

/// A stereo pair (11 cm baseline along the left camera's x, as EuRoC's) at one instant: a walker
/// pixel of the left view at depth z lands fx·b/z pixels to the left in the right view on the same
/// walker (98 % of those two pixels inside an outline) at the same depth (median within 0.5 %).
#[test]
fn a_stereo_pair_sees_each_walker_at_the_disparity_its_depth_gives() {
    const BASELINE_M: f64 = 0.11;
    let (scene, poses, track) = along_path("room0");
    let actors =
        std::sync::Arc::new(Actors::plan(&scene, walking(&PARAMS), 8, &track).expect("walkers"));
    let frames = frames_with_walkers_in_view(&actors, &poses, 2);
    let ctx = fixtures::gpu();
    let mut rasterizer =
        Rasterizer::with_actors(ctx, &scene, CAMERA, Default::default(), Some(actors))
            .expect("upload");
    for &i in &frames {
        let left = poses[i];
        let right = left.compose(&Pose::new(glam::DQuat::IDENTITY, DVec3::X * BASELINE_M));
        let t = i as f64 / RATE_HZ;
        let views = fixtures::render_with_masks(ctx, &mut rasterizer, &[left, right], |r, _| {
            r.pose_actors(ctx, t)
        });
        let ((_, left_depth, left_mask), (_, right_depth, right_mask)) = (&views[0], &views[1]);
        let (w, h) = (CAMERA.width as usize, CAMERA.height as usize);
        let (mut checked, mut agreed) = (0, 0);
        let mut depth_errors: Vec<f32> = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let p = y * w + x;
                let id = left_mask.data[p];
                let z = left_depth.data[p];
                // Inside a walker by two pixels each way: no outline of either view nearby.
                let inside = (x.saturating_sub(2)..(x + 3).min(w))
                    .all(|nx| left_mask.data[y * w + nx] == id);
                if id == 0 || !inside {
                    continue;
                }
                let xr = x as f64 - CAMERA.fx * BASELINE_M / f64::from(z);
                let xr = xr.round();
                if xr < 0.0 {
                    continue;
                }
                let q = y * w + xr as usize;
                checked += 1;
                if right_mask.data[q] == id {
                    agreed += 1;
                    depth_errors.push((right_depth.data[q] - z).abs() / z);
                }
            }
        }
        depth_errors.sort_by(f32::total_cmp);
        let median = depth_errors[depth_errors.len() / 2];
        assert!(checked > 100, "frame {i}: {checked} walker pixels");
        assert!(
            agreed as f64 > 0.98 * checked as f64,
            "frame {i}: {agreed} of {checked} walker pixels at their disparity"
        );
        assert!(
            median < 0.005,
            "frame {i}: median relative depth error {median}"
        );
    }
}

const OBJECTS: ObjectParams = ObjectParams {
    count: 3,
    speed_m_s: 0.6,
    near_m: 0.8,
};

/// For each moved object, the frame while it moves where its middle is nearest in front of the
/// camera and inside the image (none for one never seen moving).
fn frames_with_objects_moving_in_view(actors: &Actors, poses: &[Pose]) -> Vec<usize> {
    let mut chosen = Vec::new();
    for actor in actors.rigid_actors() {
        let RigidOrigin::Object(object) = &actor.origin else {
            continue;
        };
        let middle = (actor.mesh.vertices.iter())
            .map(|v| Vec3::from(v.position))
            .sum::<Vec3>()
            / actor.mesh.vertices.len() as f32;
        let moving = |t: f64| object.moves.iter().any(|m| (m[0]..m[1]).contains(&t));
        let nearest = (0..poses.len())
            .filter(|&i| moving(i as f64 / RATE_HZ))
            .filter_map(|i| {
                let (turn, at) = actor.pose_at(i as f64 / RATE_HZ);
                let p = poses[i]
                    .inverse()
                    .transform_point((at + turn * middle).as_dvec3());
                // Well inside the small camera's ±1 × ±0.56 of the image plane.
                let seen = p.z > 0.6 && (p.x / p.z).abs() < 0.9 && (p.y / p.z).abs() < 0.5;
                seen.then_some((p.z, i))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0));
        chosen.extend(nearest.map(|(_, i)| i));
    }
    chosen
}

fn kinds(actors: &Actors) -> Vec<&'static str> {
    (actors.rigid_actors().iter())
        .filter_map(|a| match &a.origin {
            RigidOrigin::Object(o) => Some(o.kind),
            RigidOrigin::Files { .. } => None,
        })
        .collect()
}

/// office1's door swinging, a chair pushed and a box carried, the door and the chair on the
/// frame each is nearest in view while it moves, the box on the frame its carrier is nearest in
/// view: colour, depth and mask against the oracle (the door's leaf lit as the scene baked it,
/// the opening it leaves dark), and depth elsewhere that of the scene less the door's leaf.
#[test]
fn a_swinging_door_a_pushed_chair_and_a_carried_box_match_the_oracle() {
    let (scene, poses, track) = along_path("office1");
    let actors =
        std::sync::Arc::new(Actors::plan(&scene, moving(&OBJECTS), 8, &track).expect("objects"));
    assert_eq!(kinds(&actors), ["door", "chair"]);
    assert!(actors.walkers().len() == 1 && actors.walkers()[0].body.carries());
    let mut frames = frames_with_objects_moving_in_view(&actors, &poses);
    assert_eq!(frames.len(), 2, "each object is seen moving: {frames:?}");
    frames.extend(frames_with_walkers_in_view(&actors, &poses, 1));
    matches_the_oracle(&scene, actors, &poses, &frames);
}

/// Every 10 ms of a crowded plan (office2, objects:5's parameters): each chair's footprint
/// circle keeps clear of the scene at every height, of the camera, of the other chairs, of the
/// box's carrier and of the door's leaf; the open leaf keeps clear of the furniture, the carrier
/// and the camera; the first chair comes within NEAR (and a little) of the camera.
#[test]
fn objects_never_touch_the_scene_each_other_or_the_camera() {
    let params = ObjectParams {
        count: 4,
        speed_m_s: 0.9,
        near_m: 0.5,
    };
    let (scene, _, track) = along_path("office2");
    let actors = Actors::plan(&scene, moving(&params), 2, &track).expect("objects");
    assert_eq!(kinds(&actors), ["door", "chair", "chair"]);
    let carrier = &actors.walkers()[0];
    assert!(carrier.body.carries());
    let door = scene
        .floor
        .and_then(|f| f.door)
        .expect("office2 has a door");
    let world = static_world(&scene, &actors);
    let obstacles = obstacles(&world);
    let rigid = actors.rigid_actors();
    let (hinge, along) = (Vec3::from(door.hinge), Vec2::from(door.along));
    let into = Vec2::from(door.into_room);
    let mut closest = f32::INFINITY;
    let duration = track.times.last().copied().unwrap();
    for step in 0..=(duration / 0.01) as usize {
        let t = step as f64 * 0.01;
        let eye = track.at(t).truncate();
        let (turn, _) = rigid[0].pose_at(t);
        let leaf = [
            hinge.truncate(),
            (hinge + turn * Vec3::X * door.width).truncate(),
        ];
        let open = (leaf[1] - leaf[0]).normalize().dot(along).acos();
        let leaf_points = segment_points(leaf);
        assert!(
            nearest(&leaf_points, &[eye]) >= CAMERA_CLEARANCE,
            "the door meets the camera at {t} s"
        );
        let stride = carrier.path.at(t);
        let carried = segment_points(carrier.footprint.segment(stride.position, stride.heading));
        assert!(
            nearest(&leaf_points, &carried) >= carrier.footprint.radius + 0.06,
            "the door meets the box's carrier at {t} s"
        );
        if open > 0.5 {
            let posed = actors.mesh_at(t);
            // The walkers' vertices come first: the door is the first rigid actor after them.
            let range = posed.actor_vertices[actors.walkers().len()].clone();
            for v in &posed.mesh.vertices[range.start..range.start + rigid[0].still_from] {
                let p = Vec3::from(v.position);
                if (p.truncate() - hinge.truncate()).dot(into) < 0.05 || p.z < 0.03 {
                    continue;
                }
                let gap = obstacles.nearest(p).map_or(f32::INFINITY, |n| n.distance);
                assert!(
                    gap > 0.01,
                    "the open door meets the scene at {p} at {t} s ({gap} m)"
                );
            }
        }
        let chairs: Vec<(Vec2, f32)> = (rigid[1..].iter())
            .map(|a| (a.pose_at(t).1.truncate(), a.radius))
            .collect();
        for (k, &(at, radius)) in chairs.iter().enumerate() {
            let to_eye = at.distance(eye);
            if k == 0 {
                closest = closest.min(to_eye - radius);
            }
            assert!(
                to_eye >= radius + CAMERA_CLEARANCE - SAMPLING,
                "chair {k} at {t} s is {to_eye} m from the camera"
            );
            assert!(
                nearest(&leaf_points, &[at]) >= radius + 0.06 - SAMPLING,
                "chair {k} meets the door at {t} s"
            );
            assert!(
                nearest(&carried, &[at]) >= radius + carrier.footprint.radius,
                "chair {k} meets the box's carrier at {t} s"
            );
            for &(other, other_radius) in &chairs[k + 1..] {
                assert!(
                    at.distance(other) >= radius + other_radius,
                    "chairs meet at {t} s"
                );
            }
            let mut z = 0.05;
            while z < 0.9 {
                let gap = (obstacles.nearest(at.extend(z))).map_or(f32::INFINITY, |n| n.distance);
                assert!(
                    gap > radius,
                    "chair {k} meets the scene {gap} m from its axis at {t} s"
                );
                z += 0.05;
            }
        }
    }
    assert!(
        closest <= params.near_m + 0.2 + SAMPLING,
        "the first chair comes no nearer than {closest} m"
    );
}

#[test]
fn the_same_seed_moves_the_same_objects_and_another_seed_others() {
    let (scene, _, track) = along_path("room0");
    let plan = |seed| Actors::plan(&scene, moving(&OBJECTS), seed, &track).unwrap();
    let (a, b, c) = (plan(3), plan(3), plan(4));
    let poses = |x: &Actors, t| {
        x.rigid_actors()
            .iter()
            .map(|r| r.pose_at(t))
            .collect::<Vec<_>>()
    };
    for t in [0.0, 6.1, 12.7, 19.0] {
        assert_eq!(poses(&a, t), poses(&b, t));
    }
    assert!((0..40).any(|k| poses(&a, k as f64 * 0.5) != poses(&c, k as f64 * 0.5)));
}
