//! Tables, desks and low cabinets.

use glam::Vec3;

use super::super::mesh_builder::{Faces, Frame, Material};
use super::super::scene_builder::SceneBuilder;
use super::super::textures::Pattern;
use super::{legs, Style};

/// A four-legged table; returns the height of its top surface.
pub fn table(
    b: &mut SceneBuilder,
    s: &Style,
    f: &Frame,
    len: f32,
    depth: f32,
    height: f32,
    top: Material,
) -> f32 {
    let t = 0.04;
    b.cuboid(
        f,
        Vec3::new(-len / 2.0, -depth / 2.0, height - t),
        Vec3::new(len / 2.0, depth / 2.0, height),
        top,
    );
    legs(b, f, [len, depth], height - t, 0.055, 0.05, s.dark_wood);
    let apron = Faces::all(s.dark_wood).without(Faces::TOP);
    let (ax, ay) = (len / 2.0 - 0.08, depth / 2.0 - 0.08);
    b.cuboid(
        f,
        Vec3::new(-ax, -ay, height - t - 0.09),
        Vec3::new(ax, -ay + 0.025, height - t),
        apron,
    );
    b.cuboid(
        f,
        Vec3::new(-ax, ay - 0.025, height - t - 0.09),
        Vec3::new(ax, ay, height - t),
        apron,
    );
    height
}

/// A low table with a lower shelf holding magazines.
pub fn coffee_table(b: &mut SceneBuilder, s: &Style, f: &Frame, len: f32, depth: f32) -> f32 {
    let h = table(b, s, f, len, depth, 0.42, s.wood);
    b.cuboid(
        f,
        Vec3::new(-len / 2.0 + 0.08, -depth / 2.0 + 0.08, 0.1),
        Vec3::new(len / 2.0 - 0.08, depth / 2.0 - 0.08, 0.13),
        s.dark_wood,
    );
    for k in 0..3 {
        let magazine = b.unique(Pattern::Poster);
        let x = -len / 4.0 + k as f32 * 0.12;
        let m = Frame::new(
            f.point(Vec3::new(x, 0.0, 0.13)),
            f.yaw + 0.3 * k as f32 - 0.2,
        );
        b.cuboid(
            &m,
            Vec3::new(-0.11, -0.15, 0.0),
            Vec3::new(0.11, 0.15, 0.008 * (k + 1) as f32),
            Faces::all(s.pages).with(Faces::TOP, magazine),
        );
    }
    h
}

/// A desk with a drawer pedestal on the right; returns the height of its top.
pub fn desk(b: &mut SceneBuilder, s: &Style, f: &Frame, len: f32, depth: f32) -> f32 {
    let (h, t) = (0.75, 0.03);
    b.cuboid(
        f,
        Vec3::new(-len / 2.0, -depth / 2.0, h - t),
        Vec3::new(len / 2.0, depth / 2.0, h),
        s.wood,
    );
    // Left panel leg, modesty panel at the back, pedestal on the right.
    b.cuboid(
        f,
        Vec3::new(-len / 2.0 + 0.02, -depth / 2.0 + 0.03, 0.0),
        Vec3::new(-len / 2.0 + 0.05, depth / 2.0 - 0.03, h - t),
        Faces::all(s.dark_metal).without(Faces::BOTTOM),
    );
    b.cuboid(
        f,
        Vec3::new(-len / 2.0 + 0.05, depth / 2.0 - 0.06, 0.3),
        Vec3::new(len / 2.0 - 0.45, depth / 2.0 - 0.04, h - t),
        s.dark_metal,
    );
    let px = len / 2.0 - 0.44;
    drawers(
        b,
        s,
        f,
        [px, -depth / 2.0 + 0.03],
        [len / 2.0 - 0.02, depth / 2.0 - 0.05],
        h - t,
        3,
    );
    h
}

/// A cabinet body from `min` to `max` (x, y) and floor to `height`, its front split into
/// `count` drawers with handles.
pub fn drawers(
    b: &mut SceneBuilder,
    s: &Style,
    f: &Frame,
    min: [f32; 2],
    max: [f32; 2],
    height: f32,
    count: u32,
) {
    b.cuboid(
        f,
        Vec3::new(min[0], min[1], 0.0),
        Vec3::new(max[0], max[1], height),
        Faces::all(s.wood).without(Faces::BOTTOM),
    );
    let step = height / count as f32;
    let cx = (min[0] + max[0]) / 2.0;
    for k in 0..count {
        let (z0, z1) = (k as f32 * step + 0.015, (k + 1) as f32 * step - 0.015);
        b.cuboid(
            f,
            Vec3::new(min[0] + 0.015, min[1] - 0.012, z0),
            Vec3::new(max[0] - 0.015, min[1], z1),
            Faces::all(s.dark_wood).without(Faces::BACK),
        );
        let zh = (z0 + z1) / 2.0 + step * 0.25;
        b.cuboid(
            f,
            Vec3::new(cx - 0.07, min[1] - 0.035, zh - 0.01),
            Vec3::new(cx + 0.07, min[1] - 0.012, zh + 0.01),
            s.metal,
        );
    }
}

/// A low sideboard with doors and drawers on short legs; returns its top height.
pub fn sideboard(
    b: &mut SceneBuilder,
    s: &Style,
    f: &Frame,
    len: f32,
    depth: f32,
    height: f32,
) -> f32 {
    let leg = 0.12;
    legs(b, f, [len, depth], leg, 0.04, 0.04, s.dark_wood);
    let body = Frame::new(f.point(Vec3::Z * leg), f.yaw);
    let (hl, hd) = (len / 2.0, depth / 2.0);
    b.cuboid(
        &body,
        Vec3::new(-hl, -hd, 0.0),
        Vec3::new(hl, hd, height - leg),
        s.wood,
    );
    let n = (len / 0.45).round().max(2.0) as u32;
    let w = len / n as f32;
    for k in 0..n {
        let x0 = -hl + k as f32 * w;
        let front = Faces::all(s.dark_wood).without(Faces::BACK);
        b.cuboid(
            &body,
            Vec3::new(x0 + 0.015, -hd - 0.012, 0.02),
            Vec3::new(x0 + w - 0.015, -hd, height - leg - 0.02),
            front,
        );
        let hx = if k % 2 == 0 { x0 + w - 0.06 } else { x0 + 0.05 };
        b.cuboid(
            &body,
            Vec3::new(hx, -hd - 0.035, (height - leg) * 0.55),
            Vec3::new(hx + 0.015, -hd - 0.012, (height - leg) * 0.8),
            s.metal,
        );
    }
    height
}
