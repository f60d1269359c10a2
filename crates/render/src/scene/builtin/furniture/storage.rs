//! Bookcases full of books, wardrobes, wall shelves and cardboard boxes.

use glam::Vec3;

use super::super::mesh_builder::{Faces, Frame};
use super::super::scene_builder::SceneBuilder;
use super::super::textures::{hsv, Pattern};
use super::decor;
use super::Style;

/// Book spine designs shared by all books (each book is tinted its own colour).
pub const SPINE_DESIGNS: i64 = 6;

/// A bookcase `width × depth × height` with `shelves` shelves, filled with books and a few
/// objects.
pub fn bookcase(
    b: &mut SceneBuilder,
    s: &Style,
    f: &Frame,
    width: f32,
    depth: f32,
    height: f32,
    shelves: u32,
) {
    let (hw, hd, t) = (width / 2.0, depth / 2.0, 0.025);
    let carcass = Faces::all(s.wood).without(Faces::BOTTOM);
    b.cuboid(
        f,
        Vec3::new(-hw, -hd, 0.0),
        Vec3::new(-hw + t, hd, height),
        carcass,
    );
    b.cuboid(
        f,
        Vec3::new(hw - t, -hd, 0.0),
        Vec3::new(hw, hd, height),
        carcass,
    );
    b.cuboid(
        f,
        Vec3::new(-hw + t, hd - 0.01, 0.0),
        Vec3::new(hw - t, hd, height),
        s.dark_wood,
    );
    let step = (height - t) / shelves as f32;
    for k in 0..=shelves {
        let z = k as f32 * step;
        b.cuboid(
            f,
            Vec3::new(-hw + t, -hd, z),
            Vec3::new(hw - t, hd - 0.01, z + t),
            s.wood,
        );
        if k < shelves {
            books(
                b,
                s,
                f,
                [-hw + t + 0.01, hw - t - 0.01],
                -hd + 0.02,
                z + t,
                step - t - 0.03,
            );
        }
    }
}

/// One row of books standing on a shelf from x = `span[0]` to `span[1]`, spines at y = `front`,
/// on height `z`, at most `max_h` tall; gaps hold small objects.
pub fn books(
    b: &mut SceneBuilder,
    s: &Style,
    f: &Frame,
    span: [f32; 2],
    front: f32,
    z: f32,
    max_h: f32,
) {
    let mut rng = b.sub_rng();
    let mut x = span[0];
    while x < span[1] - 0.03 {
        if rng.chance(0.07) && span[1] - x > 0.22 {
            let g = f.then(Vec3::new(x + 0.1, front + 0.1, z), 0.0);
            decor::trinket(b, s, &g, max_h.min(0.25));
            x += 0.22;
            continue;
        }
        let thick = rng.range(0.018, 0.05).min(span[1] - x);
        let h = rng.range(0.6, 1.0) * max_h.min(0.32);
        let d = rng.range(0.14, 0.21);
        let tint = hsv(rng.f32(), rng.range(0.3, 0.8), rng.range(0.35, 0.85));
        let spine = b.fitted(Pattern::BookSpine, rng.int(0, SPINE_DESIGNS) as u64, tint);
        let cover = super::tinted(spine, tint);
        let faces = Faces::all(cover)
            .with(Faces::FRONT, spine)
            .with(Faces::TOP, s.pages)
            .without(Faces::BOTTOM);
        b.cuboid(
            f,
            Vec3::new(x, front, z),
            Vec3::new(x + thick, front + d, z + h),
            faces,
        );
        x += thick + 0.002;
    }
}

/// A tall wardrobe with two doors and a cornice.
pub fn wardrobe(b: &mut SceneBuilder, s: &Style, f: &Frame, width: f32, depth: f32, height: f32) {
    let (hw, hd) = (width / 2.0, depth / 2.0);
    b.cuboid(
        f,
        Vec3::new(-hw, -hd, 0.0),
        Vec3::new(hw, hd, height),
        Faces::all(s.wood).without(Faces::BOTTOM),
    );
    b.cuboid(
        f,
        Vec3::new(-hw - 0.03, -hd - 0.03, height),
        Vec3::new(hw + 0.03, hd, height + 0.05),
        s.dark_wood,
    );
    for side in [-1.0f32, 1.0] {
        let (x0, x1) = if side < 0.0 {
            (-hw + 0.02, -0.01)
        } else {
            (0.01, hw - 0.02)
        };
        let door = b.unique(Pattern::Door);
        b.cuboid(
            f,
            Vec3::new(x0, -hd - 0.015, 0.1),
            Vec3::new(x1, -hd, height - 0.05),
            Faces::all(s.dark_wood)
                .with(Faces::FRONT, door)
                .without(Faces::BACK),
        );
        let hx = -side * 0.05;
        b.cuboid(
            f,
            Vec3::new(hx - 0.01, -hd - 0.04, height * 0.45),
            Vec3::new(hx + 0.01, -hd - 0.015, height * 0.6),
            s.metal,
        );
    }
}

/// A floating wall shelf at height `z` (frame on the wall), with books and a trinket.
pub fn wall_shelf(b: &mut SceneBuilder, s: &Style, wall: &Frame, width: f32, z: f32) {
    let hw = width / 2.0;
    b.cuboid(
        wall,
        Vec3::new(-hw, -0.24, z - 0.03),
        Vec3::new(hw, 0.0, z),
        s.wood,
    );
    books(b, s, wall, [-hw + 0.02, hw * 0.3], -0.22, z, 0.3);
    let g = wall.then(Vec3::new(hw * 0.65, -0.12, z), 0.0);
    decor::trinket(b, s, &g, 0.25);
}

/// Box face designs shared by all cardboard boxes.
pub const CARDBOARD_DESIGNS: i64 = 4;

/// A stack of cardboard boxes, each turned a little.
pub fn boxes(b: &mut SceneBuilder, f: &Frame, count: u32) {
    let mut rng = b.sub_rng();
    let mut z = 0.0;
    let mut size = rng.range(0.45, 0.6);
    for _ in 0..count {
        let h = size * rng.range(0.5, 0.8);
        let g = f.then(
            Vec3::new(rng.range(-0.04, 0.04), rng.range(-0.04, 0.04), z),
            rng.range(-0.25, 0.25),
        );
        let face = b.fitted(
            Pattern::Cardboard,
            rng.int(0, CARDBOARD_DESIGNS) as u64,
            [1.0; 3],
        );
        b.cuboid(
            &g,
            Vec3::new(-size / 2.0, -size / 2.5, 0.0),
            Vec3::new(size / 2.0, size / 2.5, h),
            Faces::all(face).without(Faces::BOTTOM),
        );
        z += h;
        size *= rng.range(0.7, 0.9);
    }
}
