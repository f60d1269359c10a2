//! Things that make a room look lived in: pictures, rugs, plants, lamps, screens, whiteboards and
//! small objects on surfaces.

use glam::Vec3;

use super::super::mesh_builder::{Faces, Frame, Material};
use super::super::scene_builder::SceneBuilder;
use super::super::textures::{hsv, Pattern};
use super::{storage, tinted, Style};

/// A framed picture on a wall frame, centred at (x, z) with size (w, h).
pub fn picture(
    b: &mut SceneBuilder,
    wall: &Frame,
    [x, z]: [f32; 2],
    [w, h]: [f32; 2],
    art: Material,
    frame: Material,
) {
    let (hw, hh, bar) = (w / 2.0, h / 2.0, 0.04);
    let faces = Faces::all(frame).without(Faces::BACK);
    b.cuboid(
        wall,
        Vec3::new(x - hw - bar, -0.03, z - hh - bar),
        Vec3::new(x + hw + bar, 0.0, z - hh),
        faces,
    );
    b.cuboid(
        wall,
        Vec3::new(x - hw - bar, -0.03, z + hh),
        Vec3::new(x + hw + bar, 0.0, z + hh + bar),
        faces,
    );
    b.cuboid(
        wall,
        Vec3::new(x - hw - bar, -0.03, z - hh),
        Vec3::new(x - hw, 0.0, z + hh),
        faces,
    );
    b.cuboid(
        wall,
        Vec3::new(x + hw, -0.03, z - hh),
        Vec3::new(x + hw + bar, 0.0, z + hh),
        faces,
    );
    b.mesh.quad(
        wall,
        Vec3::new(x - hw, -0.015, z + hh),
        Vec3::X * w,
        -Vec3::Z * h,
        &art,
    );
}

/// A rug `w × l` lying on the floor.
pub fn rug(b: &mut SceneBuilder, f: &Frame, w: f32, l: f32) {
    let top = b.unique(Pattern::Rug);
    let edge = tinted(top, [0.6; 3]);
    b.cuboid(
        f,
        Vec3::new(-w / 2.0, -l / 2.0, 0.0),
        Vec3::new(w / 2.0, l / 2.0, 0.012),
        Faces::all(edge)
            .with(Faces::TOP, top)
            .without(Faces::BOTTOM),
    );
}

/// A potted plant about `height` tall.
pub fn plant(b: &mut SceneBuilder, s: &Style, f: &Frame, height: f32) {
    let mut rng = b.sub_rng();
    let pot_r = 0.12 + 0.1 * height / 1.5;
    let pot = tinted(s.stone, hsv(rng.f32(), 0.4, 0.7));
    b.mesh.cylinder(f, Vec3::ZERO, pot_r, height * 0.3, &pot);
    b.mesh.cylinder(
        f,
        Vec3::new(0.0, 0.0, height * 0.3 - 0.02),
        pot_r * 0.9,
        0.03,
        &tinted(s.paint, [0.35, 0.25, 0.18]),
    );
    b.mesh.cylinder(
        f,
        Vec3::new(0.0, 0.0, height * 0.3),
        0.015,
        height * 0.35,
        &s.dark_wood,
    );
    for k in 0..7 {
        let r = height * rng.range(0.14, 0.22);
        let c = Vec3::new(
            rng.range(-0.12, 0.12),
            rng.range(-0.12, 0.12),
            height * (0.5 + 0.07 * k as f32).min(1.0) - r * 0.3,
        );
        b.mesh.ellipsoid(f, c, Vec3::new(r, r, r * 0.8), &s.leaves);
    }
}

/// A floor lamp with a fabric shade, 1.6 m tall.
pub fn floor_lamp(b: &mut SceneBuilder, s: &Style, f: &Frame) {
    b.mesh.cylinder(f, Vec3::ZERO, 0.16, 0.03, &s.dark_metal);
    b.mesh
        .cylinder(f, Vec3::new(0.0, 0.0, 0.03), 0.015, 1.35, &s.metal);
    b.mesh
        .cylinder(f, Vec3::new(0.0, 0.0, 1.3), 0.2, 0.3, &s.accent_fabric);
}

/// A table lamp standing on a surface at height `z`.
pub fn table_lamp(b: &mut SceneBuilder, s: &Style, f: &Frame, z: f32) {
    b.mesh
        .cylinder(f, Vec3::new(0.0, 0.0, z), 0.07, 0.22, &s.stone);
    b.mesh.cylinder(
        f,
        Vec3::new(0.0, 0.0, z + 0.22),
        0.13,
        0.18,
        &s.accent_fabric,
    );
}

/// A flat screen on a stand, centred at the surface height `z`, `w` wide.
pub fn screen(b: &mut SceneBuilder, s: &Style, f: &Frame, z: f32, w: f32) {
    let h = w * 0.58;
    let display = b.unique(Pattern::Screen);
    b.cuboid(
        f,
        Vec3::new(-0.1, -0.08, z),
        Vec3::new(0.1, 0.08, z + 0.015),
        s.dark_metal,
    );
    b.cuboid(
        f,
        Vec3::new(-0.025, 0.02, z),
        Vec3::new(0.025, 0.05, z + 0.12),
        s.dark_metal,
    );
    let bottom = z + 0.1;
    b.cuboid(
        f,
        Vec3::new(-w / 2.0, -0.01, bottom),
        Vec3::new(w / 2.0, 0.02, bottom + h),
        s.dark_metal,
    );
    b.mesh.quad(
        f,
        Vec3::new(-w / 2.0 + 0.012, -0.011, bottom + h - 0.012),
        Vec3::X * (w - 0.024),
        -Vec3::Z * (h - 0.024),
        &display,
    );
}

/// A monitor, keyboard and mouse on a desk top at height `z`; the frame is the desk's.
pub fn workstation(b: &mut SceneBuilder, s: &Style, desk: &Frame, z: f32, depth: f32) {
    let back = desk.then(Vec3::new(0.0, depth / 2.0 - 0.2, 0.0), 0.0);
    screen(b, s, &back, z, 0.56);
    let keys = b.unique(Pattern::Keyboard);
    let kb = desk.then(Vec3::new(0.0, -depth / 2.0 + 0.22, z), 0.0);
    b.cuboid(
        &kb,
        Vec3::new(-0.22, -0.075, 0.0),
        Vec3::new(0.22, 0.075, 0.025),
        Faces::all(s.dark_metal).with(Faces::TOP, keys),
    );
    b.cuboid(
        &kb,
        Vec3::new(0.3, -0.05, 0.0),
        Vec3::new(0.36, 0.05, 0.03),
        s.dark_metal,
    );
}

/// A whiteboard with a pen tray, on a wall frame, centred at `x`.
pub fn whiteboard(b: &mut SceneBuilder, s: &Style, wall: &Frame, x: f32, w: f32) {
    let board = b.unique(Pattern::Whiteboard);
    let (z0, z1) = (0.9, 2.0);
    let rim = Faces::all(s.metal).without(Faces::BACK);
    b.cuboid(
        wall,
        Vec3::new(x - w / 2.0, -0.025, z0),
        Vec3::new(x + w / 2.0, 0.0, z1),
        rim.with(Faces::FRONT, board),
    );
    b.cuboid(
        wall,
        Vec3::new(x - w / 2.0, -0.025, z0 - 0.02),
        Vec3::new(x + w / 2.0, 0.0, z0),
        rim,
    );
    b.cuboid(
        wall,
        Vec3::new(x - 0.4, -0.08, z0 - 0.05),
        Vec3::new(x + 0.4, 0.0, z0 - 0.02),
        rim,
    );
}

/// One small object about `max_h` tall at the frame's origin: a vase with leaves, a box, a
/// stack of books or a mug.
pub fn trinket(b: &mut SceneBuilder, s: &Style, f: &Frame, max_h: f32) {
    let mut rng = b.sub_rng();
    match rng.int(0, 4) {
        0 => {
            let vase = tinted(s.stone, hsv(rng.f32(), 0.5, 0.8));
            b.mesh.cylinder(f, Vec3::ZERO, 0.05, max_h * 0.5, &vase);
            b.mesh.ellipsoid(
                f,
                Vec3::Z * max_h * 0.65,
                Vec3::new(0.08, 0.08, max_h * 0.25),
                &s.leaves,
            );
        }
        1 => {
            let face = b.fitted(
                Pattern::Cardboard,
                rng.int(0, storage::CARDBOARD_DESIGNS) as u64,
                [1.0; 3],
            );
            b.cuboid(
                f,
                Vec3::new(-0.08, -0.06, 0.0),
                Vec3::new(0.08, 0.06, max_h * 0.5),
                Faces::all(face).without(Faces::BOTTOM),
            );
        }
        2 => {
            let mut z = 0.0;
            for _ in 0..rng.int(2, 5) {
                let t = rng.range(0.02, 0.04);
                let cover = b.fitted(
                    Pattern::BookSpine,
                    rng.int(0, storage::SPINE_DESIGNS) as u64,
                    hsv(rng.f32(), 0.6, 0.6),
                );
                let g = f.then(Vec3::new(0.0, 0.0, z), rng.range(-0.3, 0.3));
                b.cuboid(
                    &g,
                    Vec3::new(-0.09, -0.07, 0.0),
                    Vec3::new(0.09, 0.07, t),
                    Faces::all(s.pages)
                        .with(Faces::TOP, cover)
                        .with(Faces::FRONT, cover),
                );
                z += t;
            }
        }
        _ => {
            let mug = tinted(s.stone, hsv(rng.f32(), 0.6, 0.85));
            b.mesh.cylinder(f, Vec3::ZERO, 0.04, 0.1, &mug);
        }
    }
}

/// Two to four trinkets along a surface of length `len` at height `z` (frame of the surface).
pub fn clutter(b: &mut SceneBuilder, s: &Style, f: &Frame, len: f32, z: f32) {
    let mut rng = b.sub_rng();
    let n = rng.int(2, 5);
    for k in 0..n {
        let x = -len / 2.0 + (k as f32 + 0.5) * len / n as f32 + rng.range(-0.05, 0.05);
        let g = f.then(
            Vec3::new(x, rng.range(-0.05, 0.05), z),
            rng.range(-0.5, 0.5),
        );
        trinket(b, s, &g, 0.25);
    }
}
