//! The three furnished rooms: a living room, a bedroom and a kitchen–family room.

use std::f32::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use glam::{Vec2, Vec3};

use super::super::furniture::architecture::{Finish, Room, Wall::*};
use super::super::furniture::{decor, seating, storage, tables};
use super::super::mesh_builder::{Faces, Frame};
use super::super::textures::Pattern::*;
use super::Blueprint;

const WHITE: [f32; 3] = [1.0; 3];

fn at(x: f32, y: f32, yaw: f32) -> Frame {
    Frame::new(Vec3::new(x, y, 0.0), yaw)
}

/// Living room, 7.0 × 5.5 m: sofa and armchair round a coffee table, dining table, TV, bookcases.
pub fn room0() -> Blueprint {
    Blueprint {
        room: Room {
            width: 7.0,
            depth: 5.5,
            height: 2.7,
        },
        lamps: &[(-1.6, 0.0), (1.6, 0.0)],
        panel_lights: false,
        track_centre: Vec2::ZERO,
        track_margin: 1.2,
        finish: |b, s| {
            let paint = b.tiled(Plaster, 11, WHITE, 1.5);
            Finish {
                walls: [paint, paint, paint, b.tiled(Wallpaper, 13, WHITE, 0.8)],
                floor: b.tiled(FloorPlanks, 14, WHITE, 1.6),
                ceiling: b.tiled(Plaster, 15, [1.0, 1.0, 0.98], 2.0),
                skirting: s.paint,
            }
        },
        furnish: |b, s, r| {
            // South: sofa under two paintings, a plant and a floor lamp in the corners.
            seating::sofa(b, s, &r.against(South, 2.7, 0.9), 2.2, s.fabric);
            let south = r.wall_frame(South, 0.0);
            for (x, w, h) in [(2.2, 0.6, 0.45), (3.2, 0.5, 0.65)] {
                let art = b.unique(Painting);
                decor::picture(b, &south, [x, 1.6], [w, h], art, s.dark_wood);
            }
            decor::plant(b, s, &r.against(South, 6.5, 0.5), 1.3);
            decor::floor_lamp(b, s, &r.against(South, 1.1, 0.4));
            // Middle: rug, coffee table, armchair.
            decor::rug(b, &at(0.8, -1.15, 0.0), 2.6, 1.7);
            let table = Frame::new(Vec3::new(0.8, -1.2, 0.012), 0.0);
            let top = tables::coffee_table(b, s, &table, 1.1, 0.6);
            decor::clutter(b, s, &table, 0.9, top);
            seating::armchair(b, s, &at(2.45, -1.1, -FRAC_PI_2), s.accent_fabric);
            // East: door, poster, bookcases.
            r.door(b, s, East, 1.1);
            let poster = b.unique(Poster);
            decor::picture(
                b,
                &r.wall_frame(East, 2.3),
                [0.0, 1.5],
                [0.5, 0.7],
                poster,
                s.metal,
            );
            storage::bookcase(b, s, &r.against(East, 3.4, 0.35), 1.0, 0.35, 2.0, 5);
            let low = r.against(East, 4.55, 0.35);
            storage::bookcase(b, s, &low, 0.9, 0.35, 1.0, 2);
            decor::clutter(b, s, &low, 0.7, 1.02);
            // North: two windows, sideboard with a TV.
            let curtain = b.tiled(Curtain, 16, WHITE, 1.0);
            r.window(b, s, North, 1.3, 1.2, Some(curtain));
            r.window(b, s, North, 6.0, 1.0, Some(curtain));
            let sideboard = r.against(North, 3.9, 0.45);
            let top = tables::sideboard(b, s, &sideboard, 1.6, 0.45, 0.7);
            decor::screen(b, s, &sideboard, top, 1.0);
            for x in [-0.65, 0.65] {
                decor::trinket(b, s, &sideboard.then(Vec3::new(x, 0.0, top), 0.3), 0.25);
            }
            // West: papered wall with a shelf, a painting, a chest of drawers; dining table.
            storage::wall_shelf(b, s, &r.wall_frame(West, 1.2), 1.0, 1.5);
            let art = b.unique(Painting);
            decor::picture(
                b,
                &r.wall_frame(West, 3.4),
                [0.0, 1.6],
                [1.0, 0.7],
                art,
                s.dark_wood,
            );
            let chest = r.against(West, 4.6, 0.45);
            tables::drawers(b, s, &chest, [-0.4, -0.225], [0.4, 0.225], 0.9, 3);
            decor::table_lamp(b, s, &chest, 0.9);
            let dining = at(-1.9, -0.1, 0.0);
            let top = tables::table(b, s, &dining, 1.4, 0.85, 0.75, s.wood);
            decor::clutter(b, s, &dining, 1.0, top);
            for (x, y, yaw) in [
                (-0.35, -0.65, PI),
                (0.35, -0.65, PI),
                (-0.35, 0.65, 0.0),
                (0.35, 0.65, 0.0),
            ] {
                seating::chair(b, s, &dining.then(Vec3::new(x, y, 0.0), yaw), s.fabric);
            }
        },
    }
}

/// Bedroom, 5.8 × 5.0 m: double bed with night stands, wardrobe, desk, bookcase, armchair.
pub fn room1() -> Blueprint {
    Blueprint {
        room: Room {
            width: 5.8,
            depth: 5.0,
            height: 2.6,
        },
        lamps: &[(-0.6, 0.5), (1.2, -1.0)],
        panel_lights: false,
        track_centre: Vec2::new(0.2, -0.5),
        track_margin: 1.15,
        finish: |b, s| {
            let paper = b.tiled(Wallpaper, 21, WHITE, 0.7);
            let plaster = b.tiled(Plaster, 22, [0.95, 0.92, 0.88], 1.5);
            Finish {
                walls: [plaster, plaster, paper, plaster],
                floor: b.tiled(FloorPlanks, 23, WHITE, 1.4),
                ceiling: b.tiled(Plaster, 24, WHITE, 2.0),
                skirting: s.dark_wood,
            }
        },
        furnish: |b, s, r| {
            // North: bed between night stands, a painting above.
            let blanket = b.tiled(Fabric, 25, WHITE, 0.6);
            seating::bed(b, s, &r.against(North, 2.3, 2.1), 1.6, blanket);
            for along in [1.05, 3.55] {
                let stand = r.against(North, along, 0.4);
                tables::drawers(b, s, &stand, [-0.225, -0.2], [0.225, 0.2], 0.55, 2);
                decor::table_lamp(b, s, &stand, 0.55);
            }
            let art = b.unique(Painting);
            decor::picture(
                b,
                &r.wall_frame(North, 2.3),
                [0.0, 1.6],
                [1.1, 0.6],
                art,
                s.dark_wood,
            );
            decor::plant(b, s, &at(-2.5, 2.1, 0.0), 1.1);
            // West: door, wardrobe, poster.
            r.door(b, s, West, 0.9);
            storage::wardrobe(b, s, &r.against(West, 2.6, 0.6), 1.2, 0.6, 2.1);
            let poster = b.unique(Poster);
            decor::picture(
                b,
                &r.wall_frame(West, 4.2),
                [0.0, 1.5],
                [0.45, 0.65],
                poster,
                s.metal,
            );
            // South: desk with a laptop and chair, bookcase, pictures.
            let desk = r.against(South, 3.0, 0.6);
            let top = tables::desk(b, s, &desk, 1.2, 0.6);
            decor::screen(b, s, &desk.then(Vec3::new(-0.15, 0.05, 0.0), 0.0), top, 0.4);
            decor::clutter(b, s, &desk.then(Vec3::new(0.25, -0.1, 0.0), 0.0), 0.4, top);
            seating::chair(b, s, &desk.then(Vec3::new(0.0, -0.6, 0.0), PI), s.leather);
            storage::bookcase(b, s, &r.against(South, 4.4, 0.32), 0.9, 0.32, 1.8, 5);
            let south = r.wall_frame(South, 0.0);
            for (x, z) in [(2.6, 1.7), (3.4, 1.55)] {
                let art = b.unique(Poster);
                decor::picture(b, &south, [x, z], [0.4, 0.5], art, s.dark_wood);
            }
            // East: window, chest of drawers with clutter, armchair in the corner, rug.
            let curtain = b.tiled(Curtain, 26, WHITE, 1.0);
            r.window(b, s, East, 2.5, 1.4, Some(curtain));
            let chest = r.against(East, 0.9, 0.45);
            tables::drawers(b, s, &chest, [-0.5, -0.225], [0.5, 0.225], 0.85, 4);
            decor::clutter(b, s, &chest, 0.9, 0.85);
            seating::armchair(b, s, &at(1.9, -1.7, -3.0 * FRAC_PI_4), s.fabric);
            decor::rug(b, &at(0.2, -0.6, 0.0), 2.0, 1.4);
        },
    }
}

/// Kitchen and family room, 8.2 × 6.2 m: kitchen run, dining table for six, sofa corner.
pub fn room2() -> Blueprint {
    Blueprint {
        room: Room {
            width: 8.2,
            depth: 6.2,
            height: 2.8,
        },
        lamps: &[(-2.2, 0.0), (0.8, 0.0), (2.8, 1.5)],
        panel_lights: false,
        track_centre: Vec2::ZERO,
        track_margin: 1.25,
        finish: |b, s| {
            let plaster = b.tiled(Plaster, 31, [0.96, 0.94, 0.9], 1.5);
            Finish {
                walls: [
                    plaster,
                    b.tiled(Wallpaper, 32, WHITE, 0.8),
                    plaster,
                    b.tiled(Brick, 33, WHITE, 1.0),
                ],
                floor: b.tiled(FloorTiles, 34, WHITE, 1.2),
                ceiling: b.tiled(Plaster, 35, WHITE, 2.0),
                skirting: s.paint,
            }
        },
        furnish: |b, s, r| {
            // North: kitchen run with a tiled splashback and wall cabinets.
            let north = r.wall_frame(North, 0.0);
            let run = (4.4, 8.0);
            let splash = b.tiled(FloorTiles, 36, WHITE, 0.6);
            b.mesh.quad(
                &north,
                Vec3::new(run.0, -0.004, 1.5),
                Vec3::X * (run.1 - run.0),
                -Vec3::Z * 0.6,
                &splash,
            );
            let base = north.then(Vec3::new((run.0 + run.1) / 2.0, -0.33, 0.0), 0.0);
            let half = (run.1 - run.0) / 2.0;
            for k in 0..4 {
                let x0 = -half + k as f32 * (2.0 * half / 4.0);
                tables::drawers(
                    b,
                    s,
                    &base,
                    [x0, -0.3],
                    [x0 + 2.0 * half / 4.0 - 0.01, 0.3],
                    0.88,
                    3,
                );
            }
            b.cuboid(
                &base,
                Vec3::new(-half - 0.02, -0.32, 0.88),
                Vec3::new(half + 0.02, 0.3, 0.92),
                s.stone,
            );
            decor::clutter(b, s, &base, 2.0 * half - 0.4, 0.92);
            let wall_units = north.then(Vec3::new((run.0 + run.1) / 2.0, -0.18, 0.0), 0.0);
            for k in 0..4 {
                let x0 = -half + k as f32 * (2.0 * half / 4.0);
                let door = b.unique(Door);
                let faces = Faces::all(s.wood).with(Faces::FRONT, door);
                b.cuboid(
                    &wall_units,
                    Vec3::new(x0 + 0.01, -0.17, 1.55),
                    Vec3::new(x0 + 2.0 * half / 4.0 - 0.01, 0.17, 2.25),
                    faces,
                );
            }
            // West of the run: a tall bookcase and a plant.
            storage::bookcase(b, s, &r.against(North, 1.0, 0.35), 1.2, 0.35, 2.2, 6);
            decor::plant(b, s, &r.against(North, 2.4, 0.5), 1.5);
            // Dining table for six.
            let dining = at(1.2, -0.1, 0.0);
            let top = tables::table(b, s, &dining, 2.0, 1.0, 0.76, s.stone);
            decor::clutter(b, s, &dining, 1.5, top);
            for x in [-0.6, 0.0, 0.6] {
                seating::chair(b, s, &dining.then(Vec3::new(x, -0.72, 0.0), PI), s.leather);
                seating::chair(b, s, &dining.then(Vec3::new(x, 0.72, 0.0), 0.0), s.leather);
            }
            // West: brick wall, sofa facing east, coffee table, rug, armchair.
            decor::rug(b, &at(-2.5, -0.3, FRAC_PI_2), 2.6, 2.0);
            seating::sofa(b, s, &r.against(West, 2.9, 0.9), 2.4, s.fabric);
            let art = b.unique(Painting);
            decor::picture(
                b,
                &r.wall_frame(West, 2.9),
                [0.0, 1.65],
                [1.2, 0.8],
                art,
                s.dark_wood,
            );
            let table = Frame::new(Vec3::new(-2.4, -0.3, 0.012), FRAC_PI_2);
            let top = tables::coffee_table(b, s, &table, 1.0, 0.55);
            decor::clutter(b, s, &table, 0.8, top);
            seating::armchair(b, s, &at(-2.4, -2.0, PI), s.accent_fabric);
            storage::wall_shelf(b, s, &r.wall_frame(West, 5.2), 0.9, 1.45);
            // South: windows, plant, boxes.
            let curtain = b.tiled(Curtain, 37, WHITE, 1.0);
            r.window(b, s, South, 1.8, 1.3, Some(curtain));
            r.window(b, s, South, 4.6, 1.3, Some(curtain));
            decor::plant(b, s, &r.against(South, 3.2, 0.5), 1.2);
            storage::boxes(b, &r.against(South, 6.5, 0.6), 3);
            decor::floor_lamp(b, s, &r.against(South, 7.6, 0.4));
            // East: door, bookcase, poster, sideboard with a screen.
            r.door(b, s, East, 1.2);
            let poster = b.unique(Poster);
            decor::picture(
                b,
                &r.wall_frame(East, 2.3),
                [0.0, 1.55],
                [0.5, 0.7],
                poster,
                s.metal,
            );
            let sideboard = r.against(East, 3.9, 0.45);
            let top = tables::sideboard(b, s, &sideboard, 1.6, 0.45, 0.75);
            decor::screen(b, s, &sideboard, top, 0.9);
            storage::bookcase(b, s, &r.against(East, 5.4, 0.35), 0.9, 0.35, 1.9, 5);
        },
    }
}
