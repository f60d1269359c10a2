//! The room itself: floor, walls, ceiling, skirting, doors, windows and ceiling lights.

use std::f32::consts::{FRAC_PI_2, PI};

use glam::Vec3;

use super::super::mesh_builder::{Faces, Frame, Material};
use super::super::scene_builder::SceneBuilder;
use super::super::textures::Pattern;
use super::Style;
use crate::scene::Door;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wall {
    /// y = −depth/2, facing +y.
    South,
    /// x = +width/2, facing −x.
    East,
    /// y = +depth/2, facing −y.
    North,
    /// x = −width/2, facing +x.
    West,
}

pub const WALLS: [Wall; 4] = [Wall::South, Wall::East, Wall::North, Wall::West];

/// A box-shaped room centred on the origin, floor at z = 0.
#[derive(Clone, Copy, Debug)]
pub struct Room {
    /// Along x.
    pub width: f32,
    /// Along y.
    pub depth: f32,
    pub height: f32,
}

/// Surfaces of the room shell.
pub struct Finish {
    pub walls: [Material; 4],
    pub floor: Material,
    pub ceiling: Material,
    pub skirting: Material,
}

impl Room {
    pub fn wall_length(&self, wall: Wall) -> f32 {
        match wall {
            Wall::South | Wall::North => self.width,
            Wall::East | Wall::West => self.depth,
        }
    }

    /// A frame on the inside face of `wall`, `along` metres from its left end seen from inside,
    /// at floor level: local x runs along the wall to the right, local −y points into the room.
    pub fn wall_frame(&self, wall: Wall, along: f32) -> Frame {
        let (w, d) = (self.width / 2.0, self.depth / 2.0);
        let (left_end, yaw) = match wall {
            Wall::South => (Vec3::new(w, -d, 0.0), PI),
            Wall::East => (Vec3::new(w, d, 0.0), -FRAC_PI_2),
            Wall::North => (Vec3::new(-w, d, 0.0), 0.0),
            Wall::West => (Vec3::new(-w, -d, 0.0), FRAC_PI_2),
        };
        Frame::new(left_end, yaw).then(Vec3::new(along, 0.0, 0.0), 0.0)
    }

    /// The footprint-centre frame of a piece `depth` deep standing against `wall`, facing the room.
    pub fn against(&self, wall: Wall, along: f32, depth: f32) -> Frame {
        self.wall_frame(wall, along)
            .then(Vec3::new(0.0, -depth / 2.0 - 0.03, 0.0), 0.0)
    }

    /// Floor, ceiling, four walls and skirting boards.
    pub fn shell(&self, b: &mut SceneBuilder, finish: &Finish) {
        let world = Frame::new(Vec3::ZERO, 0.0);
        let (w, d, h) = (self.width, self.depth, self.height);
        b.mesh.quad(
            &world,
            Vec3::new(-w / 2.0, d / 2.0, 0.0),
            Vec3::X * w,
            -Vec3::Y * d,
            &finish.floor,
        );
        b.mesh.quad(
            &world,
            Vec3::new(-w / 2.0, -d / 2.0, h),
            Vec3::X * w,
            Vec3::Y * d,
            &finish.ceiling,
        );
        for (wall, m) in WALLS.into_iter().zip(finish.walls) {
            let len = self.wall_length(wall);
            let f = self.wall_frame(wall, 0.0);
            b.mesh
                .quad(&f, Vec3::Z * h, Vec3::X * len, -Vec3::Z * h, &m);
            let skirting = Faces::all(finish.skirting)
                .without(Faces::BOTTOM)
                .without(Faces::BACK);
            b.cuboid(
                &f,
                Vec3::new(0.0, -0.015, 0.0),
                Vec3::new(len, 0.0, 0.09),
                skirting,
            );
        }
    }

    /// A closed panelled door centred `along` the wall, with trim and a lever handle.
    pub fn door(&self, b: &mut SceneBuilder, s: &Style, wall: Wall, along: f32) {
        let f = self.wall_frame(wall, along);
        let (hw, h) = (0.45, 2.05);
        let leaf = b.unique(Pattern::Door);
        let leaf_start = b.mesh.index_count();
        b.cuboid(
            &f,
            Vec3::new(-hw, -0.03, 0.0),
            Vec3::new(hw, 0.0, h),
            Faces::all(s.paint)
                .with(Faces::FRONT, leaf)
                .without(Faces::BACK),
        );
        let leaf_end = b.mesh.index_count();
        let trim = Faces::all(s.paint).without(Faces::BACK);
        b.cuboid(
            &f,
            Vec3::new(-hw - 0.08, -0.02, 0.0),
            Vec3::new(-hw, 0.0, h + 0.08),
            trim,
        );
        b.cuboid(
            &f,
            Vec3::new(hw, -0.02, 0.0),
            Vec3::new(hw + 0.08, 0.0, h + 0.08),
            trim,
        );
        b.cuboid(
            &f,
            Vec3::new(-hw, -0.02, h),
            Vec3::new(hw, 0.0, h + 0.08),
            trim,
        );
        let handle_start = b.mesh.index_count();
        b.cuboid(
            &f,
            Vec3::new(hw - 0.2, -0.09, 1.0),
            Vec3::new(hw - 0.06, -0.03, 1.03),
            s.metal,
        );
        let into_room = f.vector(Vec3::NEG_Y).truncate();
        b.doors.push(Door {
            hinge: f.point(Vec3::new(-hw, -0.03, 0.0)).into(),
            along: f.vector(Vec3::X).truncate().into(),
            into_room: into_room.into(),
            width: 2.0 * hw,
            height: h,
            thickness: 0.03,
            indices: [(leaf_start, leaf_end), (handle_start, b.mesh.index_count())],
        });
    }

    /// A window (the view outside is a picture behind the frame) with a sill and two curtains.
    pub fn window(
        &self,
        b: &mut SceneBuilder,
        s: &Style,
        wall: Wall,
        along: f32,
        width: f32,
        curtains: Option<Material>,
    ) {
        let f = self.wall_frame(wall, along);
        let (hw, z0, z1) = (width / 2.0, 0.9, 2.1);
        let view = b.unique(Pattern::WindowView).glowing();
        let (corner, right, down) = (
            Vec3::new(-hw, -0.005, z1),
            Vec3::X * width,
            -Vec3::Z * (z1 - z0),
        );
        b.mesh.quad(&f, corner, right, down, &view);
        b.mesh.window_light(&f, corner, right, down);
        let frame = Faces::all(s.paint).without(Faces::BACK);
        let bar = 0.06;
        b.cuboid(
            &f,
            Vec3::new(-hw - bar, -0.05, z0),
            Vec3::new(-hw, 0.0, z1),
            frame,
        );
        b.cuboid(
            &f,
            Vec3::new(hw, -0.05, z0),
            Vec3::new(hw + bar, 0.0, z1),
            frame,
        );
        b.cuboid(
            &f,
            Vec3::new(-hw, -0.05, z1 - bar),
            Vec3::new(hw, 0.0, z1),
            frame,
        );
        b.cuboid(
            &f,
            Vec3::new(-bar / 2.0, -0.04, z0),
            Vec3::new(bar / 2.0, -0.005, z1),
            frame,
        );
        b.cuboid(
            &f,
            Vec3::new(-hw, -0.04, (z0 + z1) / 2.0 - 0.02),
            Vec3::new(hw, -0.005, (z0 + z1) / 2.0 + 0.02),
            frame,
        );
        b.cuboid(
            &f,
            Vec3::new(-hw - 0.1, -0.16, z0 - 0.05),
            Vec3::new(hw + 0.1, 0.0, z0),
            s.stone,
        );
        if let Some(curtain) = curtains {
            for side in [-1.0, 1.0] {
                let x = side * (hw + 0.2);
                b.cuboid(
                    &f,
                    Vec3::new(x - 0.2, -0.14, 0.05),
                    Vec3::new(x + 0.2, -0.06, z1 + 0.25),
                    Faces::all(curtain).without(Faces::BACK),
                );
            }
            b.cuboid(
                &f,
                Vec3::new(-hw - 0.5, -0.12, z1 + 0.25),
                Vec3::new(hw + 0.5, -0.1, z1 + 0.28),
                s.dark_metal,
            );
        }
    }

    /// A flush ceiling light at (x, y): a square panel or a round dome.
    pub fn ceiling_light(&self, b: &mut SceneBuilder, m: &Material, x: f32, y: f32, square: bool) {
        let f = Frame::new(Vec3::new(x, y, self.height), 0.0);
        if square {
            b.cuboid(
                &f,
                Vec3::new(-0.3, -0.3, -0.03),
                Vec3::new(0.3, 0.3, 0.0),
                Faces::all(*m).without(Faces::TOP),
            );
        } else {
            b.mesh
                .ellipsoid(&f, Vec3::ZERO, Vec3::new(0.25, 0.25, 0.09), m);
        }
    }
}
