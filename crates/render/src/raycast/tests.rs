use glam::{DQuat, DVec3};

use super::*;
use crate::Vertex;

/// Tolerance on ray-cast distances in metres (f32 intersection arithmetic at a few metres).
const DIST_EPS: f32 = 1e-5;

fn vertex(p: [f32; 3], uv: [f32; 2], layer: u32) -> Vertex {
    Vertex {
        position: p,
        uv,
        color: [255; 4],
        layer,
    }
}

/// The square [x0, x1] × [y0, y1] at height z, normal +z, uv spanning [0, 1]².
fn square(mesh: &mut Mesh, x: [f32; 2], y: [f32; 2], z: f32, layer: u32) {
    let base = mesh.vertices.len() as u32;
    mesh.vertices.extend([
        vertex([x[0], y[0], z], [0.0, 1.0], layer),
        vertex([x[1], y[0], z], [1.0, 1.0], layer),
        vertex([x[1], y[1], z], [1.0, 0.0], layer),
        vertex([x[0], y[1], z], [0.0, 0.0], layer),
    ]);
    mesh.indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
}

/// An axis-aligned box with outward normals, from min to max.
fn cube(min: Vec3, max: Vec3) -> Mesh {
    let mut mesh = Mesh::default();
    let c = |i: u32| {
        Vec3::new(
            if i & 1 == 0 { min.x } else { max.x },
            if i & 2 == 0 { min.y } else { max.y },
            if i & 4 == 0 { min.z } else { max.z },
        )
    };
    for i in 0..8 {
        mesh.vertices.push(vertex(c(i).into(), [0.0; 2], 0));
    }
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    for f in faces {
        mesh.indices.extend([f[0], f[1], f[2], f[0], f[2], f[3]]);
    }
    mesh
}

#[test]
fn cast_reports_distance_triangle_and_barycentrics() {
    let mut mesh = Mesh::default();
    square(&mut mesh, [-1.0, 1.0], [-1.0, 1.0], 2.0, 0);
    let rc = RayCaster::from_mesh(&mesh);
    let hit = rc.cast(Vec3::new(0.5, -0.5, 0.0), Vec3::Z).expect("hit");
    assert!((hit.distance - 2.0).abs() < DIST_EPS);
    let tri = hit.triangle as usize;
    let point: Vec3 = (0..3)
        .map(|k| {
            Vec3::from(mesh.vertices[mesh.indices[3 * tri + k] as usize].position)
                * hit.barycentrics[k]
        })
        .sum();
    assert!((point - Vec3::new(0.5, -0.5, 2.0)).length() < DIST_EPS);
    assert!(
        rc.cast(Vec3::new(0.0, 0.0, 3.0), Vec3::Z).is_none(),
        "nothing behind the origin"
    );
    assert!(
        rc.cast(Vec3::new(2.0, 0.0, 0.0), Vec3::Z).is_none(),
        "beside the square"
    );
    assert!(
        rc.cast_within(Vec3::ZERO, Vec3::Z, 1.5).is_none(),
        "beyond max distance"
    );
}

#[test]
fn rays_through_the_shared_diagonal_do_not_slip_through() {
    let mut mesh = Mesh::default();
    square(&mut mesh, [0.0, 1.0], [0.0, 1.0], 1.0, 0);
    let rc = RayCaster::from_mesh(&mesh);
    // Strictly inside the square: a ray lying in a bounding-box face plane is obvhs's edge case.
    for k in 1..64 {
        let t = k as f32 / 64.0;
        assert!(
            rc.cast(Vec3::new(t, t, 0.0), Vec3::Z).is_some(),
            "gap at {t}"
        );
    }
}

#[test]
fn depth_image_is_z_depth_of_a_tilted_plane_in_opencv_axes() {
    // Camera at the origin looking along world +x (z up): camera x = world −y, camera y = world −z.
    let forward = DQuat::from_mat3(&glam::DMat3::from_cols(-DVec3::Y, -DVec3::Z, DVec3::X));
    let pose = Pose::new(forward, DVec3::ZERO);
    // The plane x = 3 + 0.5·y (world), as a big quad.
    let mut mesh = Mesh::default();
    let p = |y: f32, z: f32| vertex([3.0 + 0.5 * y, y, z], [0.0; 2], 0);
    mesh.vertices.extend([
        p(-10.0, -10.0),
        p(10.0, -10.0),
        p(10.0, 10.0),
        p(-10.0, 10.0),
    ]);
    mesh.indices.extend([0, 1, 2, 0, 2, 3]);
    let k = Intrinsics {
        width: 16,
        height: 12,
        fx: 10.0,
        fy: 11.0,
        cx: 7.5,
        cy: 5.5,
    };
    let depth = RayCaster::from_mesh(&mesh).depth_image(&pose, &k);
    for y in 0..k.height {
        for x in 0..k.width {
            // Ray (a, b, 1) in camera = (1, −a, −b) in world hits x = 3 + 0.5·y at z_cam = 3 / (1 + 0.5·a).
            let a = (x as f64 - k.cx) / k.fx;
            let expected = 3.0 / (1.0 + 0.5 * a);
            let got = depth.at(x, y) as f64;
            assert!(
                (got - expected).abs() < 1e-5,
                "pixel ({x},{y}): {got} vs {expected}"
            );
        }
    }
}

#[test]
fn misses_give_zero_depth() {
    let mesh = cube(Vec3::new(4.0, -0.5, -0.5), Vec3::new(4.2, 0.5, 0.5));
    let pose = Pose::new(
        DQuat::from_mat3(&glam::DMat3::from_cols(-DVec3::Y, -DVec3::Z, DVec3::X)),
        DVec3::ZERO,
    );
    let k = Intrinsics {
        width: 21,
        height: 21,
        fx: 20.0,
        fy: 20.0,
        cx: 10.0,
        cy: 10.0,
    };
    let depth = RayCaster::from_mesh(&mesh).depth_image(&pose, &k);
    assert!(
        (depth.at(10, 10) - 4.0).abs() < DIST_EPS,
        "centre pixel sees the cube's face"
    );
    assert_eq!(depth.at(0, 0), 0.0);
    let valid = depth.data.iter().filter(|&&z| z > 0.0).count();
    assert!(valid > 1 && valid < 21 * 21 / 4, "{valid} valid pixels");
}

#[test]
fn nearest_surface_matches_brute_force() {
    let mut mesh = cube(Vec3::new(-1.0, -2.0, 0.0), Vec3::new(1.0, 2.0, 3.0));
    square(&mut mesh, [2.0, 3.0], [2.0, 3.0], 0.5, 0);
    let rc = RayCaster::from_mesh(&mesh);
    let mut rng = 12345u64;
    let mut next = || {
        rng = rng
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (rng >> 40) as f32 / (1u64 << 24) as f32 * 8.0 - 4.0
    };
    for _ in 0..200 {
        let q = Vec3::new(next(), next(), next());
        let got = rc.nearest_surface(q).unwrap();
        // Brute force: sample every triangle densely.
        let mut best = f32::INFINITY;
        for t in mesh.indices.chunks_exact(3) {
            let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(mesh.vertices[t[k] as usize].position));
            for i in 0..=40 {
                for j in 0..=(40 - i) {
                    let p = a + (b - a) * (i as f32 / 40.0) + (c - a) * (j as f32 / 40.0);
                    best = best.min(p.distance(q));
                }
            }
        }
        assert!(
            got.distance <= best + 1e-4,
            "{q}: {} > sampled {best}",
            got.distance
        );
        assert!(
            got.distance >= best - 0.1,
            "{q}: {} far below sampled {best}",
            got.distance
        );
        assert!((got.point.distance(q) - got.distance).abs() < 1e-4);
    }
}

/// One unit square at z = 1 (layer 1, vertex colour (255, 128, 255)) with a 2×2 black/white
/// checker: one texel is 0.5 m.
fn checker_scene() -> Scene {
    let mut mesh = Mesh::default();
    square(&mut mesh, [0.0, 1.0], [0.0, 1.0], 1.0, 1);
    for v in &mut mesh.vertices {
        v.color = [255, 128, 255, 255];
    }
    let checker = Texture {
        width: 2,
        height: 2,
        rgba: [[255; 4], [0, 0, 0, 255], [0, 0, 0, 255], [255; 4]].concat(),
    };
    Scene {
        name: "t".into(),
        mesh,
        textures: vec![Texture::white(), checker],
        default_trajectory: None,
        splats: None,
        floor: None,
        lights: None,
    }
}

/// uv steps of `texels` level-0 texels per pixel of the 2×2 checker, along x.
fn step(texels: f32) -> UvDerivatives {
    UvDerivatives {
        dx: [texels / 2.0, 0.0],
        dy: [0.0, 0.0],
    }
}

#[test]
fn colour_multiplies_vertex_colour_and_texture_and_filters_by_level_of_detail() {
    use crate::scene::srgb::{linear_to_srgb, srgb_to_linear};
    let rc = RayCaster::new(&checker_scene());
    // uv (0.25, 0.25) is the centre of the white top-left texel: y = 0.75 in this square.
    let hit = rc.cast(Vec3::new(0.25, 0.75, 0.0), Vec3::Z).unwrap();
    assert_eq!(rc.color_at(&hit, &UvDerivatives::ZERO), [255, 128, 255]);
    assert_eq!(
        rc.color_at(&hit, &step(1.0)),
        [255, 128, 255],
        "λ = 0: level 0"
    );
    let black = rc.cast(Vec3::new(0.75, 0.75, 0.0), Vec3::Z).unwrap();
    assert_eq!(rc.color_at(&black, &UvDerivatives::ZERO), [0, 0, 0]);
    // Half-way between the two texel centres: the linear-light mean.
    let g = srgb_to_linear(128);
    let between = rc.cast(Vec3::new(0.5, 0.75, 0.0), Vec3::Z).unwrap();
    let mean = [0.5, 0.5 * g, 0.5].map(linear_to_srgb);
    assert_eq!(rc.color_at(&between, &UvDerivatives::ZERO), mean);
    // Two texels per pixel (λ = 1) is the 1×1 level: 50 % linear grey (sRGB 188, as mip levels
    // are stored) × vertex colour; an sRGB-space average would give 128.
    assert_eq!(rc.color_at(&hit, &step(2.0)), [188, 93, 188]);
    assert_eq!(
        rc.color_at(&hit, &step(64.0)),
        [188, 93, 188],
        "beyond the last level"
    );
    // The longer of the two steps decides, whichever axis it is on.
    let along_y = UvDerivatives {
        dx: [0.01, 0.0],
        dy: [0.0, 1.0],
    };
    assert_eq!(rc.color_at(&hit, &along_y), [188, 93, 188]);
    // λ = 0.5 blends level 0 (white here) and level 1 (50 %) half and half, in linear light.
    let blend = [0.75, 0.75 * g, 0.75].map(linear_to_srgb);
    assert_eq!(rc.color_at(&hit, &step(2f32.sqrt())), blend);
}

/// A camera 2 m in front of the checker square (texture repeats every metre) sees uv change by
/// z / f per pixel; on a plane tilted about the camera's y axis the x step grows to the
/// right, and every pixel of a 2×2 quad gets its top-left pixel's derivatives.
#[test]
fn uv_derivatives_are_the_quads_differences_on_the_triangles_plane() {
    let rc = RayCaster::new(&checker_scene());
    let k = Intrinsics {
        width: 8,
        height: 8,
        fx: 40.0,
        fy: 40.0,
        cx: 3.5,
        cy: 3.5,
    };
    // Looking along +z from (0.5, 0.5, −1): camera axes are the world's.
    let pose = Pose::new(DQuat::IDENTITY, DVec3::new(0.5, 0.5, -1.0));
    let (origin, dir) = camera_ray(&pose, &k, 4, 4);
    let hit = rc.cast(origin, dir).unwrap();
    let d = rc.uv_derivatives(hit.triangle, &pose, &k, 4, 4);
    let expected = 2.0 / 40.0;
    // uv u grows with x; v = 1 − y in the square's layout, so it falls as pixel y grows.
    assert!(
        (d.dx[0] - expected).abs() < 1e-6 && d.dx[1].abs() < 1e-6,
        "{d:?}"
    );
    assert!(
        d.dy[0].abs() < 1e-6 && (d.dy[1] + expected).abs() < 1e-6,
        "{d:?}"
    );
    // Tilt the camera: derivatives change across the image but not within a quad.
    let tilted = Pose::new(DQuat::from_rotation_y(0.6), DVec3::new(-0.4, 0.5, -0.5));
    let at = |x: usize, y: usize| {
        let (o, d) = camera_ray(&tilted, &k, x, y);
        let hit = rc.cast(o, d).expect("tilted view still sees the square");
        rc.uv_derivatives(hit.triangle, &tilted, &k, x, y)
    };
    assert_eq!(at(2, 4), at(3, 5), "one quad, one level of detail");
    assert!(
        at(6, 4).dx[0] > at(2, 4).dx[0] * 1.05,
        "farther to the right"
    );
}

#[test]
fn surface_edges_mark_layer_plane_and_silhouette_changes_only() {
    // At z = 2: A (top left, layer 1), B (top right, layer 1: A continued), C (bottom left,
    // layer 2); D (bottom right) is a step forward to z = 1.5. Around them, nothing.
    let mut mesh = Mesh::default();
    square(&mut mesh, [-1.0, 0.0], [-1.0, 0.0], 2.0, 1);
    square(&mut mesh, [0.0, 1.0], [-1.0, 0.0], 2.0, 1);
    square(&mut mesh, [-1.0, 0.0], [0.0, 1.0], 2.0, 2);
    square(&mut mesh, [0.0, 1.0], [0.0, 1.0], 1.5, 1);
    let scene = Scene {
        name: "edges".into(),
        mesh,
        textures: vec![Texture::white(); 3],
        default_trajectory: None,
        splats: None,
        floor: None,
        lights: None,
    };
    let rc = RayCaster::new(&scene);
    let k = Intrinsics {
        width: 40,
        height: 40,
        fx: 20.0,
        fy: 20.0,
        cx: 19.5,
        cy: 19.5,
    };
    let frame = rc.render(&Pose::new(DQuat::IDENTITY, DVec3::ZERO), &k);
    let edges = rc.surface_edges(&frame);
    let at = |x: usize, y: usize| edges[y * 40 + x];
    // Camera axes are the world's; at z = 2 pixel x = 19.5 + 10·X: A is x, y in 10..=19.
    assert!(!at(14, 14), "inside A, across its diagonal");
    assert!(
        !at(19, 14) && !at(20, 14),
        "A continues into B: same layer, same plane"
    );
    assert!(at(14, 19) && at(14, 20), "A meets C: another layer");
    assert!(at(24, 19) && at(24, 20), "B meets D: another plane");
    assert!(at(9, 14) && at(10, 14), "the silhouette at X = −1");
    assert!(!at(14, 24) && !at(26, 26), "inside C and D");
    assert!(!at(2, 2), "nothing but misses");
    assert!(frame.triangles[2 * 40 + 2].is_none() && frame.triangles[14 * 40 + 14].is_some());
}
