//! Chairs, sofas and beds.

use std::f32::consts::TAU;

use glam::Vec3;

use super::super::mesh_builder::{Faces, Frame, Material};
use super::super::scene_builder::SceneBuilder;
use super::{legs, Style};

/// A dining chair facing local −y (its back at +y).
pub fn chair(b: &mut SceneBuilder, s: &Style, f: &Frame, seat: Material) {
    let (w, seat_h) = (0.44, 0.46);
    legs(b, f, [w, w], seat_h - 0.04, 0.035, 0.0, s.dark_wood);
    b.cuboid(
        f,
        Vec3::new(-w / 2.0, -w / 2.0, seat_h - 0.04),
        Vec3::new(w / 2.0, w / 2.0, seat_h),
        s.dark_wood,
    );
    b.cuboid(
        f,
        Vec3::new(-w / 2.0 + 0.02, -w / 2.0 + 0.02, seat_h),
        Vec3::new(w / 2.0 - 0.02, w / 2.0 - 0.02, seat_h + 0.04),
        seat,
    );
    for x in [-w / 2.0, w / 2.0 - 0.035] {
        b.cuboid(
            f,
            Vec3::new(x, w / 2.0 - 0.035, seat_h),
            Vec3::new(x + 0.035, w / 2.0, 0.92),
            s.dark_wood,
        );
    }
    for z in [0.62, 0.76, 0.86] {
        b.cuboid(
            f,
            Vec3::new(-w / 2.0 + 0.035, w / 2.0 - 0.03, z),
            Vec3::new(w / 2.0 - 0.035, w / 2.0 - 0.01, z + 0.06),
            s.wood,
        );
    }
}

/// A swivel office chair facing local −y.
pub fn office_chair(b: &mut SceneBuilder, s: &Style, f: &Frame, upholstery: Material) {
    for k in 0..5 {
        let arm = f.then(Vec3::ZERO, k as f32 / 5.0 * TAU);
        b.cuboid(
            &arm,
            Vec3::new(-0.02, 0.0, 0.05),
            Vec3::new(0.02, 0.32, 0.09),
            s.dark_metal,
        );
        b.mesh
            .cylinder(&arm, Vec3::new(0.0, 0.3, 0.0), 0.025, 0.05, &s.dark_metal);
    }
    b.mesh
        .cylinder(f, Vec3::new(0.0, 0.0, 0.09), 0.03, 0.33, &s.metal);
    b.cuboid(
        f,
        Vec3::new(-0.25, -0.24, 0.42),
        Vec3::new(0.25, 0.24, 0.5),
        upholstery,
    );
    b.cuboid(
        f,
        Vec3::new(-0.03, 0.2, 0.45),
        Vec3::new(0.03, 0.26, 0.6),
        s.dark_metal,
    );
    b.cuboid(
        f,
        Vec3::new(-0.23, 0.22, 0.58),
        Vec3::new(0.23, 0.3, 1.02),
        upholstery,
    );
    for x in [-0.27, 0.23] {
        b.cuboid(
            f,
            Vec3::new(x, -0.05, 0.5),
            Vec3::new(x + 0.04, 0.08, 0.66),
            s.dark_metal,
        );
        b.cuboid(
            f,
            Vec3::new(x - 0.01, -0.1, 0.66),
            Vec3::new(x + 0.05, 0.15, 0.69),
            s.dark_metal,
        );
    }
}

/// A sofa `len` long: base, seat and back cushions, arms and throw pillows.
pub fn sofa(b: &mut SceneBuilder, s: &Style, f: &Frame, len: f32, upholstery: Material) {
    let (d, hl) = (0.9, len / 2.0);
    legs(b, f, [len, d], 0.08, 0.05, 0.05, s.dark_wood);
    b.cuboid(
        f,
        Vec3::new(-hl, -d / 2.0, 0.08),
        Vec3::new(hl, d / 2.0, 0.3),
        upholstery,
    );
    let arm = 0.18;
    for x in [-hl, hl - arm] {
        b.cuboid(
            f,
            Vec3::new(x, -d / 2.0, 0.3),
            Vec3::new(x + arm, d / 2.0, 0.62),
            upholstery,
        );
    }
    b.cuboid(
        f,
        Vec3::new(-hl + arm, d / 2.0 - 0.2, 0.3),
        Vec3::new(hl - arm, d / 2.0, 0.85),
        upholstery,
    );
    let n = ((len - 2.0 * arm) / 0.7).round().max(1.0) as u32;
    let w = (len - 2.0 * arm) / n as f32;
    for k in 0..n {
        let x0 = -hl + arm + k as f32 * w;
        b.cuboid(
            f,
            Vec3::new(x0 + 0.01, -d / 2.0 + 0.02, 0.3),
            Vec3::new(x0 + w - 0.01, d / 2.0 - 0.2, 0.44),
            upholstery,
        );
        b.cuboid(
            f,
            Vec3::new(x0 + 0.02, d / 2.0 - 0.35, 0.44),
            Vec3::new(x0 + w - 0.02, d / 2.0 - 0.2, 0.8),
            upholstery,
        );
    }
    for x in [-hl + arm + 0.25, hl - arm - 0.25] {
        let p = f.then(Vec3::new(x, d / 2.0 - 0.42, 0.6), 0.0);
        b.cuboid(
            &p,
            Vec3::new(-0.2, -0.06, -0.16),
            Vec3::new(0.2, 0.06, 0.2),
            s.accent_fabric,
        );
    }
}

/// A one-seat sofa.
pub fn armchair(b: &mut SceneBuilder, s: &Style, f: &Frame, upholstery: Material) {
    sofa(b, s, f, 1.0, upholstery);
}

/// A bed `width` wide and 2.05 m long, headboard at local +y.
pub fn bed(b: &mut SceneBuilder, s: &Style, f: &Frame, width: f32, blanket: Material) {
    let (hw, hl) = (width / 2.0, 1.025);
    b.cuboid(
        f,
        Vec3::new(-hw, -hl, 0.0),
        Vec3::new(hw, hl, 0.3),
        Faces::all(s.wood).without(Faces::BOTTOM),
    );
    b.cuboid(
        f,
        Vec3::new(-hw - 0.03, hl, 0.0),
        Vec3::new(hw + 0.03, hl + 0.06, 1.05),
        s.dark_wood,
    );
    b.cuboid(
        f,
        Vec3::new(-hw + 0.03, -hl + 0.03, 0.3),
        Vec3::new(hw - 0.03, hl - 0.03, 0.5),
        s.paint,
    );
    b.cuboid(
        f,
        Vec3::new(-hw + 0.01, -hl + 0.01, 0.35),
        Vec3::new(hw - 0.01, hl * 0.35, 0.55),
        blanket,
    );
    let n = if width > 1.2 { 2 } else { 1 };
    let pw = (width - 0.2) / n as f32;
    for k in 0..n {
        let x0 = -hw + 0.1 + k as f32 * pw;
        b.cuboid(
            f,
            Vec3::new(x0 + 0.03, hl - 0.5, 0.5),
            Vec3::new(x0 + pw - 0.03, hl - 0.1, 0.63),
            s.accent_fabric,
        );
    }
}
