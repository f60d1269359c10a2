//! The five offices: a two-desk office, a meeting room, an open-plan office, a lounge office and
//! a manager's office.

use std::f32::consts::{FRAC_PI_2, PI};

use glam::{Vec2, Vec3};

use super::super::furniture::architecture::{Finish, Room, Wall, Wall::*};
use super::super::furniture::{decor, seating, storage, tables, Style};
use super::super::mesh_builder::Frame;
use super::super::scene_builder::SceneBuilder;
use super::super::textures::Pattern::*;
use super::Blueprint;

const WHITE: [f32; 3] = [1.0; 3];

fn at(x: f32, y: f32, yaw: f32) -> Frame {
    Frame::new(Vec3::new(x, y, 0.0), yaw)
}

fn office_finish(b: &mut SceneBuilder, s: &Style, seed: u64, accent: usize) -> Finish {
    let plaster = b.tiled(Plaster, seed, [0.94, 0.94, 0.92], 1.5);
    let mut walls = [plaster; 4];
    walls[accent] = b.tiled(Wallpaper, seed + 1, WHITE, 0.9);
    Finish {
        walls,
        floor: b.tiled(OfficeCarpet, seed + 2, WHITE, 1.0),
        ceiling: b.tiled(CeilingTiles, seed + 3, WHITE, 1.2),
        skirting: s.dark_metal,
    }
}

/// A desk against a wall with a workstation and an office chair pulled up to it.
fn workplace(b: &mut SceneBuilder, s: &Style, r: &Room, wall: Wall, along: f32, len: f32) {
    let desk = r.against(wall, along, 0.7);
    let top = tables::desk(b, s, &desk, len, 0.7);
    decor::workstation(b, s, &desk, top, 0.7);
    decor::clutter(
        b,
        s,
        &desk.then(Vec3::new(-len / 2.0 + 0.25, 0.05, 0.0), 0.0),
        0.3,
        top,
    );
    seating::office_chair(b, s, &desk.then(Vec3::new(0.05, -0.62, 0.0), PI), s.fabric);
}

/// A filing cabinet (four drawers) against a wall.
fn filing_cabinet(b: &mut SceneBuilder, s: &Style, f: &Frame) {
    tables::drawers(b, s, f, [-0.23, -0.3], [0.23, 0.3], 1.3, 4);
}

/// Small office, 5.4 × 5.0 m: two desks, a corner desk, bookcase, whiteboard, filing cabinet.
pub fn office0() -> Blueprint {
    Blueprint {
        room: Room {
            width: 5.4,
            depth: 5.0,
            height: 2.7,
        },
        lamps: &[(-1.2, 0.0), (1.2, 0.0)],
        panel_lights: true,
        track_centre: Vec2::ZERO,
        track_margin: 1.35,
        finish: |b, s| office_finish(b, s, 41, 1),
        furnish: |b, s, r| {
            workplace(b, s, r, North, 1.6, 1.4);
            workplace(b, s, r, North, 3.4, 1.4);
            workplace(b, s, r, East, 2.9, 1.4);
            let wb = r.wall_frame(South, 0.0);
            decor::whiteboard(b, s, &wb, 2.2, 1.8);
            storage::bookcase(b, s, &r.against(South, 4.2, 0.35), 1.0, 0.35, 2.0, 5);
            filing_cabinet(b, s, &r.against(South, 0.6, 0.6));
            decor::clutter(b, s, &r.against(South, 0.6, 0.6), 0.35, 1.3);
            r.window(b, s, West, 1.5, 1.4, None);
            r.window(b, s, West, 3.6, 1.0, None);
            r.door(b, s, East, 0.8);
            let poster = b.unique(Poster);
            decor::picture(
                b,
                &r.wall_frame(East, 4.3),
                [0.0, 1.5],
                [0.5, 0.7],
                poster,
                s.metal,
            );
            decor::plant(b, s, &at(-2.3, 2.1, 0.0), 1.4);
            storage::boxes(b, &r.against(South, 5.0, 0.6), 2);
        },
    }
}

/// Meeting room, 7.0 × 5.2 m: conference table for eight, wall screen, whiteboard.
pub fn office1() -> Blueprint {
    Blueprint {
        room: Room {
            width: 7.0,
            depth: 5.2,
            height: 2.7,
        },
        lamps: &[(-1.8, 0.0), (0.0, 0.0), (1.8, 0.0)],
        panel_lights: true,
        track_centre: Vec2::ZERO,
        track_margin: 1.3,
        finish: |b, s| office_finish(b, s, 51, 3),
        furnish: |b, s, r| {
            let table = at(0.0, -0.1, 0.0);
            let top = tables::table(b, s, &table, 2.8, 1.1, 0.75, s.wood);
            decor::clutter(b, s, &table, 2.2, top);
            for x in [-0.9, 0.0, 0.9] {
                seating::office_chair(b, s, &table.then(Vec3::new(x, -0.85, 0.0), PI), s.leather);
                seating::office_chair(b, s, &table.then(Vec3::new(x, 0.85, 0.0), 0.0), s.leather);
            }
            for x in [-1.75, 1.75] {
                seating::office_chair(
                    b,
                    s,
                    &table.then(Vec3::new(x, 0.0, 0.0), -x.signum() * FRAC_PI_2),
                    s.leather,
                );
            }
            // West: wall-mounted screen over a sideboard.
            let sideboard = r.against(West, 2.6, 0.45);
            let top = tables::sideboard(b, s, &sideboard, 1.8, 0.45, 0.7);
            decor::clutter(b, s, &sideboard, 1.5, top);
            decor::screen(
                b,
                s,
                &r.wall_frame(West, 2.6)
                    .then(Vec3::new(0.0, -0.03, 0.0), 0.0),
                1.05,
                1.4,
            );
            // East: whiteboard, plant; North: windows; South: door, posters, bookcase.
            decor::whiteboard(b, s, &r.wall_frame(East, 0.0), 2.6, 2.2);
            decor::plant(b, s, &r.against(East, 4.6, 0.5), 1.5);
            r.window(b, s, North, 2.0, 1.6, None);
            r.window(b, s, North, 5.0, 1.6, None);
            r.door(b, s, South, 1.0);
            let south = r.wall_frame(South, 0.0);
            for x in [2.4, 3.3, 4.2] {
                let poster = b.unique(Poster);
                decor::picture(b, &south, [x, 1.55], [0.55, 0.75], poster, s.metal);
            }
            storage::bookcase(b, s, &r.against(South, 5.8, 0.35), 1.2, 0.35, 1.1, 3);
            decor::clutter(b, s, &r.against(South, 5.8, 0.35), 1.0, 1.12);
        },
    }
}

/// Open-plan office, 9.0 × 6.6 m: rows of desks, filing cabinets, a small meeting corner.
pub fn office2() -> Blueprint {
    Blueprint {
        room: Room {
            width: 9.0,
            depth: 6.6,
            height: 2.9,
        },
        lamps: &[
            (-2.5, -1.2),
            (0.0, -1.2),
            (2.5, -1.2),
            (-2.5, 1.2),
            (0.0, 1.2),
            (2.5, 1.2),
        ],
        panel_lights: true,
        track_centre: Vec2::ZERO,
        track_margin: 1.4,
        finish: |b, s| office_finish(b, s, 61, 2),
        furnish: |b, s, r| {
            for along in [1.6, 3.2, 4.8, 6.4] {
                workplace(b, s, r, North, along, 1.5);
            }
            workplace(b, s, r, East, 2.2, 1.5);
            workplace(b, s, r, East, 4.2, 1.5);
            let north = r.wall_frame(North, 0.0);
            for x in [2.4, 5.6] {
                let poster = b.unique(Poster);
                decor::picture(b, &north, [x, 1.75], [0.6, 0.45], poster, s.metal);
            }
            decor::plant(b, s, &r.against(North, 8.3, 0.5), 1.6);
            // West: filing cabinets, bookcases, whiteboard.
            for along in [0.6, 1.1] {
                filing_cabinet(b, s, &r.against(West, along, 0.6));
            }
            storage::bookcase(b, s, &r.against(West, 2.2, 0.35), 1.0, 0.35, 2.1, 5);
            decor::whiteboard(b, s, &r.wall_frame(West, 0.0), 4.2, 2.0);
            storage::bookcase(b, s, &r.against(West, 6.0, 0.35), 0.9, 0.35, 2.1, 5);
            // South: windows, meeting corner, boxes, plant.
            r.window(b, s, South, 1.6, 1.5, None);
            r.window(b, s, South, 4.5, 1.5, None);
            r.window(b, s, South, 7.4, 1.5, None);
            let meeting = at(-3.0, -2.1, 0.0);
            let top = tables::table(b, s, &meeting, 1.2, 0.8, 0.74, s.stone);
            decor::clutter(b, s, &meeting, 0.9, top);
            for (x, y, yaw) in [
                (-0.35, 0.62, 0.0),
                (0.35, 0.62, 0.0),
                (0.85, 0.0, -FRAC_PI_2),
            ] {
                seating::chair(b, s, &meeting.then(Vec3::new(x, y, 0.0), yaw), s.fabric);
            }
            storage::boxes(b, &r.against(South, 3.0, 0.6), 3);
            decor::plant(b, s, &r.against(East, 6.2, 0.5), 1.2);
            r.door(b, s, East, 0.8);
        },
    }
}

/// Lounge office, 8.0 × 7.6 m: sofas round a rug, desks along the west wall, bookcases, kitchenette.
pub fn office3() -> Blueprint {
    Blueprint {
        room: Room {
            width: 8.0,
            depth: 7.6,
            height: 3.0,
        },
        lamps: &[(-2.0, -2.0), (2.0, -2.0), (-2.0, 2.0), (2.0, 2.0)],
        panel_lights: true,
        track_centre: Vec2::ZERO,
        track_margin: 1.35,
        finish: |b, s| {
            let mut f = office_finish(b, s, 71, 0);
            f.walls[2] = b.tiled(Brick, 75, WHITE, 1.0);
            f.floor = b.tiled(FloorPlanks, 76, WHITE, 1.6);
            f
        },
        furnish: |b, s, r| {
            // Lounge: two sofas facing each other over a rug and coffee table, an armchair.
            decor::rug(b, &at(0.6, -0.9, 0.0), 3.0, 2.2);
            seating::sofa(b, s, &at(0.6, -2.4, PI), 2.4, s.leather);
            seating::sofa(b, s, &at(0.6, 0.6, 0.0), 2.2, s.fabric);
            let table = Frame::new(Vec3::new(0.6, -0.9, 0.012), 0.0);
            let top = tables::coffee_table(b, s, &table, 1.2, 0.6);
            decor::clutter(b, s, &table, 1.0, top);
            seating::armchair(b, s, &at(2.5, -0.9, -FRAC_PI_2), s.accent_fabric);
            // North: brick wall with bookcases and a painting.
            for along in [1.0, 2.2, 5.6, 6.8] {
                storage::bookcase(b, s, &r.against(North, along, 0.35), 1.1, 0.35, 2.2, 6);
            }
            let art = b.unique(Painting);
            decor::picture(
                b,
                &r.wall_frame(North, 3.9),
                [0.0, 1.7],
                [1.4, 0.9],
                art,
                s.dark_wood,
            );
            decor::plant(b, s, &r.against(North, 3.9, 0.5), 1.0);
            // West: desks with workstations, whiteboard.
            workplace(b, s, r, West, 1.4, 1.4);
            workplace(b, s, r, West, 3.1, 1.4);
            decor::whiteboard(b, s, &r.wall_frame(West, 0.0), 5.5, 2.4);
            // East: windows; South: kitchenette sideboard with a screen, door, boxes.
            r.window(b, s, East, 1.8, 1.6, None);
            r.window(b, s, East, 4.6, 1.6, None);
            decor::plant(b, s, &r.against(East, 6.8, 0.5), 1.5);
            let counter = r.against(South, 2.2, 0.5);
            let top = tables::sideboard(b, s, &counter, 2.4, 0.5, 0.9);
            decor::clutter(b, s, &counter, 2.0, top);
            r.door(b, s, South, 4.4);
            storage::boxes(b, &r.against(South, 6.3, 0.6), 2);
            let south = r.wall_frame(South, 0.0);
            for x in [1.6, 2.8] {
                let poster = b.unique(Poster);
                decor::picture(b, &south, [x, 1.7], [0.6, 0.8], poster, s.metal);
            }
        },
    }
}

/// Manager's office, 6.6 × 6.0 m: a desk facing the room before bookcases, visitor chairs, a
/// round-table corner.
pub fn office4() -> Blueprint {
    Blueprint {
        room: Room {
            width: 6.6,
            depth: 6.0,
            height: 2.8,
        },
        lamps: &[(-1.5, -1.4), (1.5, -1.4), (-1.5, 1.4), (1.5, 1.4)],
        panel_lights: true,
        track_centre: Vec2::new(-0.5, 0.0),
        track_margin: 1.3,
        finish: |b, s| {
            let mut f = office_finish(b, s, 81, 1);
            f.walls[3] = b.tiled(Wallpaper, 85, WHITE, 0.8);
            f
        },
        furnish: |b, s, r| {
            // East: bookcases behind the desk, which faces west.
            for along in [1.5, 2.6, 3.7] {
                storage::bookcase(b, s, &r.against(East, along, 0.35), 1.05, 0.35, 2.1, 5);
            }
            let desk = at(1.9, -0.2, -FRAC_PI_2);
            let top = tables::desk(b, s, &desk, 1.6, 0.8);
            decor::screen(b, s, &desk.then(Vec3::new(0.3, 0.15, 0.0), 0.0), top, 0.5);
            decor::clutter(b, s, &desk.then(Vec3::new(-0.4, -0.1, 0.0), 0.0), 0.6, top);
            seating::office_chair(b, s, &desk.then(Vec3::new(0.0, 0.65, 0.0), 0.0), s.leather);
            for x in [-0.4, 0.4] {
                seating::chair(b, s, &desk.then(Vec3::new(x, -0.95, 0.0), PI), s.fabric);
            }
            // North: round-table corner, posters; West: windows; South: door, sofa.
            let round = at(-1.8, 1.7, 0.0);
            let top = tables::table(b, s, &round, 1.0, 1.0, 0.74, s.stone);
            decor::clutter(b, s, &round, 0.7, top);
            for (x, y, yaw) in [(0.0, 0.75, 0.0), (0.75, 0.0, -FRAC_PI_2), (0.0, -0.75, PI)] {
                seating::chair(b, s, &round.then(Vec3::new(x, y, 0.0), yaw), s.fabric);
            }
            let north = r.wall_frame(North, 0.0);
            for x in [1.0, 2.0] {
                let poster = b.unique(Poster);
                decor::picture(b, &north, [x, 1.6], [0.5, 0.7], poster, s.metal);
            }
            decor::plant(b, s, &r.against(North, 5.9, 0.5), 1.5);
            r.window(b, s, West, 1.6, 1.4, Some(s.accent_fabric));
            r.window(b, s, West, 4.2, 1.4, Some(s.accent_fabric));
            r.door(b, s, South, 1.0);
            seating::sofa(b, s, &r.against(South, 3.6, 0.9), 2.0, s.fabric);
            let art = b.unique(Painting);
            decor::picture(
                b,
                &r.wall_frame(South, 3.6),
                [0.0, 1.65],
                [1.0, 0.65],
                art,
                s.dark_wood,
            );
            storage::boxes(b, &r.against(South, 5.6, 0.6), 2);
        },
    }
}
