//! Furniture and fittings built from cuboids, cylinders and ellipsoids. Each builder takes the
//! piece's [`Frame`] (origin at the centre of its footprint on the floor, front towards local −y)
//! and the scene's [`Style`].

pub mod architecture;
pub mod decor;
pub mod seating;
pub mod storage;
pub mod tables;

use glam::Vec3;

use super::mesh_builder::{Frame, Material};
use super::scene_builder::SceneBuilder;
use super::textures::{hsv, Pattern};

/// The materials a scene's furniture is made of.
#[derive(Clone, Copy, Debug)]
pub struct Style {
    pub wood: Material,
    pub dark_wood: Material,
    pub fabric: Material,
    pub accent_fabric: Material,
    pub leather: Material,
    pub metal: Material,
    pub dark_metal: Material,
    pub stone: Material,
    pub paint: Material,
    pub pages: Material,
    pub leaves: Material,
}

impl Style {
    pub fn new(b: &mut SceneBuilder) -> Self {
        let mut rng = b.rng.fork("style");
        let white = [1.0; 3];
        let paint_tint = hsv(rng.f32(), rng.range(0.05, 0.25), rng.range(0.8, 0.95));
        Self {
            wood: b.tiled(Pattern::WoodGrain, rng.seed(), white, 1.0),
            dark_wood: b.tiled(Pattern::WoodGrain, rng.seed(), [0.6, 0.55, 0.5], 1.0),
            fabric: b.tiled(Pattern::Fabric, rng.seed(), white, 0.5),
            accent_fabric: b.tiled(Pattern::Fabric, rng.seed(), white, 0.4),
            leather: b.tiled(Pattern::Leather, rng.seed(), white, 0.5),
            metal: b.tiled(Pattern::BrushedMetal, rng.seed(), white, 0.5),
            dark_metal: b.tiled(Pattern::BrushedMetal, rng.seed(), [0.45, 0.45, 0.48], 0.5),
            stone: b.tiled(Pattern::Marble, rng.seed(), white, 1.0),
            paint: b.tiled(Pattern::Plaster, rng.seed(), paint_tint, 1.0),
            pages: b.tiled(Pattern::Pages, rng.seed(), white, 0.3),
            leaves: b.tiled(Pattern::Leaves, rng.seed(), white, 0.4),
        }
    }
}

/// Four square legs of side `t` under a rectangle (len, depth), inset by `inset`, `height` tall.
pub fn legs(
    b: &mut SceneBuilder,
    f: &Frame,
    [len, depth]: [f32; 2],
    height: f32,
    t: f32,
    inset: f32,
    m: Material,
) {
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            let c = Vec3::new(
                sx * (len / 2.0 - inset - t / 2.0),
                sy * (depth / 2.0 - inset - t / 2.0),
                0.0,
            );
            let h = Vec3::new(t / 2.0, t / 2.0, 0.0);
            b.cuboid(f, c - h, c + h + Vec3::Z * height, m);
        }
    }
}

/// A tinted copy of a material (same texture).
pub fn tinted(m: Material, tint: [f32; 3]) -> Material {
    Material { tint, ..m }
}
