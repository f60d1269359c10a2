use glam::Vec3;

use super::*;
use crate::scene::builtin::lighting::{Lighting, Window};
use crate::scene::builtin::mesh_builder::{Faces, Frame, Material, MeshBuilder, UvMap};

const GREY: Material = Material {
    layer: 0,
    tint: [0.5; 3],
    uv: UvMap::Fit,
    emissive: false,
};

/// A 4 × 4 m floor at z = 0 (facing up) and, optionally, a 1 m box standing on its centre.
fn floor_scene(with_box: bool) -> (Mesh, Vec<Vec3>, Vec<Vec3>, Vec<bool>) {
    let mut b = MeshBuilder::new(Lighting::default());
    let world = Frame::new(Vec3::ZERO, 0.0);
    b.quad(
        &world,
        Vec3::new(-2.0, 2.0, 0.0),
        Vec3::X * 4.0,
        -Vec3::Y * 4.0,
        &GREY,
    );
    if with_box {
        b.cuboid(
            &world,
            Vec3::new(-0.5, -0.5, 0.0),
            Vec3::new(0.5, 0.5, 1.0),
            Faces::all(GREY).without(Faces::BOTTOM),
        );
    }
    b.into_bake_parts()
}

fn irradiance_at(mesh: &Mesh, e: &[Vec3], p: Vec3) -> Vec3 {
    let (i, _) = mesh
        .vertices
        .iter()
        .enumerate()
        .map(|(i, v)| (i, (Vec3::from(v.position) - p).length()))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    e[i]
}

fn bake_of(
    mesh: &Mesh,
    normals: &[Vec3],
    albedo: &[Vec3],
    emissive: &[bool],
    l: &Lighting,
) -> Vec<Vec3> {
    bake_now(&BakeInput {
        mesh,
        normals,
        albedo,
        emissive,
        lighting: l,
    })
    .total
}

#[test]
fn a_lamp_lights_the_floor_by_the_inverse_square_law_and_cosine() {
    let l = Lighting {
        lamps: vec![Vec3::new(0.0, 0.0, 2.0)],
        windows: vec![],
    };
    let (mesh, n, _, g) = floor_scene(false);
    // No albedo: direct light only.
    let e = bake_of(&mesh, &n, &vec![Vec3::ZERO; n.len()], &g, &l);
    let below = irradiance_at(&mesh, &e, Vec3::ZERO).x / LAMP_INTENSITY.x;
    let aside = irradiance_at(&mesh, &e, Vec3::new(2.0, 0.0, 0.0)).x / LAMP_INTENSITY.x;
    // E = I cos θ / d²: 1/4 below; at 2 m aside cos θ = 2/√8 and d² = 8. The disc's finite size
    // changes either by well under 1 %.
    assert!((below - 0.25).abs() < 0.0025, "{below}");
    let expected = (2.0 / 8f32.sqrt()) / 8.0;
    assert!(
        (aside - expected).abs() < 0.01 * expected,
        "{aside} vs {expected}"
    );
}

#[test]
fn a_box_casts_a_shadow_and_its_top_is_brighter_than_the_floor() {
    let l = Lighting {
        lamps: vec![Vec3::new(0.0, 0.0, 2.5)],
        windows: vec![],
    };
    let (mesh, n, _, g) = floor_scene(true);
    let e = bake_of(&mesh, &n, &vec![Vec3::ZERO; n.len()], &g, &l);
    let hidden = irradiance_at(&mesh, &e, Vec3::new(0.0, 0.0, 0.0)).x;
    let open = irradiance_at(&mesh, &e, Vec3::new(1.5, 1.5, 0.0)).x;
    assert_eq!(hidden, 0.0, "the floor under the box sees no lamp");
    assert!(open > 0.05, "{open}");
    let top = irradiance_at(&mesh, &e, Vec3::new(0.0, 0.0, 1.0)).x;
    assert!(
        top > open,
        "the box top is nearer the lamp: {top} vs {open}"
    );
}

#[test]
fn reflected_light_reaches_faces_turned_away_from_every_light() {
    // The box's sides face sideways and the lamp is straight above its top: a side sees the lamp
    // (cos > 0 only from above its top edge) weakly; the floor is what lights it. With albedo 0
    // the side gets direct light only; with albedo 0.5 the floor's reflection adds to it.
    let l = Lighting {
        lamps: vec![Vec3::new(0.0, 0.0, 3.0)],
        windows: vec![],
    };
    let (mesh, n, _, g) = floor_scene(true);
    let side = Vec3::new(0.5, 0.0, 0.25);
    let dark = bake_of(&mesh, &n, &vec![Vec3::ZERO; n.len()], &g, &l);
    let grey = bake_of(&mesh, &n, &vec![Vec3::splat(0.5); n.len()], &g, &l);
    let (d, r) = (
        irradiance_at(&mesh, &dark, side).x,
        irradiance_at(&mesh, &grey, side).x,
    );
    assert!(
        d < 1e-6,
        "a vertical side below the lamp's horizon gets no direct light: {d}"
    );
    assert!(r > 0.01, "the floor's reflection lights it: {r}");
}

#[test]
fn a_window_lights_what_faces_it() {
    let window = Window {
        corner: Vec3::new(-0.5, 2.0, 2.0),
        right: Vec3::X,
        down: -Vec3::Z,
    };
    assert!((window.normal() - (-Vec3::Y)).length() < 1e-6);
    let l = Lighting {
        lamps: vec![],
        windows: vec![window],
    };
    let (mesh, n, _, g) = floor_scene(false);
    let e = bake_of(&mesh, &n, &vec![Vec3::ZERO; n.len()], &g, &l);
    let near = irradiance_at(&mesh, &e, Vec3::new(0.0, 1.5, 0.0)).x;
    let far = irradiance_at(&mesh, &e, Vec3::new(0.0, -2.0, 0.0)).x;
    assert!(near > 2.0 * far && far > 0.0, "{near} vs {far}");
}

#[test]
fn the_cache_returns_what_was_baked_and_misses_on_another_key() {
    let dir = tempfile::tempdir().unwrap();
    let a = blake3::hash(b"a");
    let e = Baked {
        total: vec![Vec3::new(1.0, 2.0, 3.0), Vec3::new(0.5, 0.25, 0.125)],
        layers: vec![vec![Vec3::ONE, Vec3::ZERO], vec![Vec3::X, Vec3::Y]],
    };
    cache::store(dir.path(), &a, &e);
    assert_eq!(cache::load(dir.path(), &a, 2, 2), Some(e));
    assert_eq!(
        cache::load(dir.path(), &a, 3, 2),
        None,
        "a vertex count that differs"
    );
    assert_eq!(cache::load(dir.path(), &a, 2, 1), None, "a layer count");
    assert_eq!(cache::load(dir.path(), &blake3::hash(b"b"), 2, 2), None);
}

#[test]
fn the_layers_are_each_lights_share_and_sum_to_the_total() {
    let window = Window {
        corner: Vec3::new(-0.5, 2.0, 2.0),
        right: Vec3::X,
        down: -Vec3::Z,
    };
    let l = Lighting {
        lamps: vec![Vec3::new(-1.0, 0.0, 2.5), Vec3::new(1.0, 0.0, 2.5)],
        windows: vec![window],
    };
    let (mesh, n, _, g) = floor_scene(true);
    let albedo = vec![Vec3::splat(0.5); n.len()];
    let input = |lighting| BakeInput {
        mesh: &mesh,
        normals: &n,
        albedo: &albedo,
        emissive: &g,
        lighting,
    };
    let all = bake_now(&input(&l));
    assert_eq!(all.layers.len(), 3);
    for (i, &total) in all.total.iter().enumerate() {
        let sum: Vec3 = all.layers.iter().map(|layer| layer[i]).sum();
        assert!((sum - total).abs().max_element() <= 1e-5 * (1.0 + total.max_element()));
    }
    // Each layer is what that light alone bakes (same sample patterns: the same light index).
    let alone = Lighting {
        lamps: vec![l.lamps[0]],
        windows: vec![],
    };
    let first = bake_now(&input(&alone));
    for (a, b) in all.layers[0].iter().zip(&first.total) {
        assert!((*a - *b).abs().max_element() <= 1e-5 * (1.0 + b.max_element()));
    }
    let daylight = Lighting {
        lamps: vec![],
        windows: vec![window],
    };
    let window_only = bake_now(&input(&daylight));
    for (a, b) in all.layers[2].iter().zip(&window_only.total) {
        assert!((*a - *b).abs().max_element() <= 1e-5 * (1.0 + b.max_element()));
    }
}
