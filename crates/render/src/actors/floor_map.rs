//! Where on a scene's floor a body fits: the horizontal clearance of every 5 cm cell, from the
//! distance to the nearest surface that is not floor along a vertical axis through the cell.

use std::collections::BinaryHeap;

use glam::{Vec2, Vec3, Vec3A};
use obvhs::triangle::Triangle;
use rslam_core::SurfaceBvh;

use crate::{FreeFloor, Mesh};

/// Side of a cell, metres.
pub const CELL: f32 = 0.05;
/// Heights sampled on a cell's axis are this far apart, metres.
const AXIS_STEP: f32 = 0.1;
/// Metres above the tallest head from which surfaces are out of reach.
const HEADROOM: f32 = 0.1;
/// Surfaces lower than this and nearly flat are walked on (floor, rugs, thresholds), metres.
const WALKABLE_HEIGHT: f32 = 0.03;

/// The clearance of every cell of the room's floor.
pub struct FloorMap {
    room_half: Vec2,
    columns: usize,
    rows: usize,
    /// Metres from the cell centre's axis (0 to `height`) to the nearest obstacle, less what a
    /// point of the cell and a point between two sampled heights can be nearer: a body whose
    /// radius is at most this stands clear anywhere in the cell.
    clearance: Vec<f32>,
}

impl FloorMap {
    /// The clearance of `floor`'s cells for bodies up to `height` metres tall among `mesh`'s
    /// obstacles.
    pub fn new(mesh: &Mesh, floor: &FreeFloor, height: f32) -> Self {
        let obstacles = SurfaceBvh::new(obstacles(mesh, height));
        let room_half = Vec2::from(floor.room_half);
        let columns = (2.0 * room_half.x / CELL).ceil() as usize;
        let rows = (2.0 * room_half.y / CELL).ceil() as usize;
        let slack = CELL * std::f32::consts::FRAC_1_SQRT_2 + AXIS_STEP / 2.0;
        let heights: Vec<f32> = (0..)
            .map(|i| 0.05 + i as f32 * AXIS_STEP)
            .take_while(|&z| z < height + AXIS_STEP)
            .collect();
        use rayon::prelude::*;
        let clearance = (0..columns * rows)
            .into_par_iter()
            .map(|i| {
                let centre = cell_centre(room_half, i % columns, i / columns);
                let nearest = heights
                    .iter()
                    .filter_map(|&z| obstacles.nearest(centre.extend(z)))
                    .map(|p| p.distance)
                    .fold(f32::INFINITY, f32::min);
                nearest - slack
            })
            .collect();
        Self {
            room_half,
            columns,
            rows,
            clearance,
        }
    }

    /// Metres a body's axis at `p` keeps from every obstacle, at least; 0 outside the room.
    pub fn clearance(&self, p: Vec2) -> f32 {
        self.index_of(p).map_or(0.0, |i| self.clearance[i].max(0.0))
    }

    /// The centres of the cells with at least `radius` of clearance.
    pub fn free_cells(&self, radius: f32) -> Vec<Vec2> {
        (0..self.columns * self.rows)
            .filter(|&i| self.clearance[i] >= radius)
            .map(|i| cell_centre(self.room_half, i % self.columns, i / self.columns))
            .collect()
    }
}

impl FloorMap {
    /// The shortest way (8-connected A*) from `from` to `to` over cells with at least `radius`
    /// of clearance, as cell centres from `from`'s cell to `to`'s; `None` when there is none.
    pub fn way(&self, from: Vec2, to: Vec2, radius: f32) -> Option<Vec<Vec2>> {
        let (start, goal) = (self.index_of(from)?, self.index_of(to)?);
        let open = |i: usize| self.clearance[i] >= radius;
        if !open(start) || !open(goal) {
            return None;
        }
        let centre = |i: usize| cell_centre(self.room_half, i % self.columns, i / self.columns);
        let estimate = |i: usize| centre(i).distance(centre(goal));
        let mut cost = vec![f32::INFINITY; self.clearance.len()];
        let mut came_from = vec![usize::MAX; self.clearance.len()];
        let mut queue = BinaryHeap::new();
        cost[start] = 0.0;
        queue.push(Entry(estimate(start), start));
        while let Some(Entry(_, i)) = queue.pop() {
            if i == goal {
                let mut way = vec![centre(goal)];
                let mut at = goal;
                while at != start {
                    at = came_from[at];
                    way.push(centre(at));
                }
                way.reverse();
                return Some(way);
            }
            for (j, step) in self.neighbours(i) {
                if open(j) && cost[i] + step < cost[j] {
                    cost[j] = cost[i] + step;
                    came_from[j] = i;
                    queue.push(Entry(cost[j] + estimate(j), j));
                }
            }
        }
        None
    }

    /// The centres of the cells with at least `radius` of clearance that a body can walk to
    /// from `from` (8-connected), `from`'s own cell first; empty when `from`'s lacks it.
    pub fn reachable(&self, from: Vec2, radius: f32) -> Vec<Vec2> {
        let Some(start) = self.index_of(from).filter(|&i| self.clearance[i] >= radius) else {
            return Vec::new();
        };
        let mut seen = vec![false; self.clearance.len()];
        let mut cells = vec![start];
        seen[start] = true;
        let mut next = 0;
        while next < cells.len() {
            let i = cells[next];
            next += 1;
            for (j, _) in self.neighbours(i) {
                if !seen[j] && self.clearance[j] >= radius {
                    seen[j] = true;
                    cells.push(j);
                }
            }
        }
        (cells.into_iter())
            .map(|i| cell_centre(self.room_half, i % self.columns, i / self.columns))
            .collect()
    }

    /// The largest region of cells with at least `radius` of clearance that a body can walk
    /// across (8-connected): where a room's people walk.
    pub fn largest_region(&self, radius: f32) -> Vec<Vec2> {
        let mut placed = vec![false; self.clearance.len()];
        let mut largest = Vec::new();
        for p in self.free_cells(radius) {
            let i = self.index_of(p).expect("a free cell is in the room");
            if placed[i] {
                continue;
            }
            let region = self.reachable(p, radius);
            for q in &region {
                placed[self.index_of(*q).expect("in the room")] = true;
            }
            if region.len() > largest.len() {
                largest = region;
            }
        }
        largest
    }

    /// The cells next to cell `i` (8-connected) in the room, each with the step to it, metres.
    fn neighbours(&self, i: usize) -> impl Iterator<Item = (usize, f32)> + '_ {
        let (column, row) = ((i % self.columns) as i64, (i / self.columns) as i64);
        NEIGHBOURS.iter().filter_map(move |&(dc, dr)| {
            let (c, r) = (column + dc, row + dr);
            let inside =
                (0..self.columns as i64).contains(&c) && (0..self.rows as i64).contains(&r);
            let step = if dc != 0 && dr != 0 {
                CELL * std::f32::consts::SQRT_2
            } else {
                CELL
            };
            inside.then(|| (r as usize * self.columns + c as usize, step))
        })
    }

    fn index_of(&self, p: Vec2) -> Option<usize> {
        let c = (p + self.room_half) / CELL;
        let (column, row) = (c.x.floor() as i64, c.y.floor() as i64);
        let inside =
            (0..self.columns as i64).contains(&column) && (0..self.rows as i64).contains(&row);
        inside.then(|| row as usize * self.columns + column as usize)
    }
}

const NEIGHBOURS: [(i64, i64); 8] = [
    (1, 0),
    (-1, 0),
    (0, 1),
    (0, -1),
    (1, 1),
    (1, -1),
    (-1, 1),
    (-1, -1),
];

/// A cell in the A* queue, least estimated cost first.
struct Entry(f32, usize);

impl PartialEq for Entry {
    fn eq(&self, other: &Self) -> bool {
        self.0 == other.0 && self.1 == other.1
    }
}
impl Eq for Entry {}
impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Entry {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

fn cell_centre(room_half: Vec2, column: usize, row: usize) -> Vec2 {
    -room_half + (Vec2::new(column as f32, row as f32) + 0.5) * CELL
}

/// The triangles a body up to `height` tall cannot pass through: all but the flat, low ones it
/// walks on and those wholly above its head (the ceiling, lamps).
fn obstacles(mesh: &Mesh, height: f32) -> Vec<Triangle> {
    let p = |i: u32| Vec3::from(mesh.vertices[i as usize].position);
    mesh.indices
        .chunks_exact(3)
        .map(|t| [p(t[0]), p(t[1]), p(t[2])])
        .filter(|[a, b, c]| {
            let low = a.z.max(b.z).max(c.z) < WALKABLE_HEIGHT;
            let flat = (b - a).cross(c - a).normalize_or_zero().z.abs() > 0.9;
            let overhead = a.z.min(b.z).min(c.z) > height + HEADROOM;
            !(overhead || low && flat)
        })
        .map(|[a, b, c]| Triangle {
            v0: Vec3A::from(a),
            v1: Vec3A::from(b),
            v2: Vec3A::from(c),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vertex;

    fn quad(mesh: &mut Mesh, corners: [[f32; 3]; 4]) {
        let base = mesh.vertices.len() as u32;
        for position in corners {
            mesh.vertices.push(Vertex {
                position,
                uv: [0.0; 2],
                color: [255; 4],
                layer: 0,
            });
        }
        mesh.indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
    }

    #[test]
    fn the_floor_is_walked_on_and_a_pillar_and_the_walls_keep_bodies_away() {
        let mut mesh = Mesh::default();
        quad(
            &mut mesh,
            [
                [-2.0, -2.0, 0.0],
                [2.0, -2.0, 0.0],
                [2.0, 2.0, 0.0],
                [-2.0, 2.0, 0.0],
            ],
        );
        // A wall at x = 2 and a thin pillar face at x = 0.5 from y = -0.1 to 0.1.
        quad(
            &mut mesh,
            [
                [2.0, -2.0, 0.0],
                [2.0, 2.0, 0.0],
                [2.0, 2.0, 2.5],
                [2.0, -2.0, 2.5],
            ],
        );
        quad(
            &mut mesh,
            [
                [0.5, -0.1, 0.0],
                [0.5, 0.1, 0.0],
                [0.5, 0.1, 2.5],
                [0.5, -0.1, 2.5],
            ],
        );
        let floor = FreeFloor {
            room_half: [2.0, 2.0],
            free_centre: [0.0; 2],
            free_half: [1.5; 2],
            ceiling: 2.5,
            door: None,
        };
        let map = FloorMap::new(&mesh, &floor, 1.9);
        let slack = CELL * std::f32::consts::FRAC_1_SQRT_2 + AXIS_STEP / 2.0;
        // Cell centres lie on the 5 cm grid offset by half a cell.
        let at = |x: f32, y: f32| map.clearance(Vec2::new(x, y));
        // The cell at (-0.975, 1.025) is nearest to the pillar's edge at (0.5, 0.1).
        let pillar_edge = Vec2::new(1.475, 0.925).length();
        assert!(
            (at(-1.0, 1.0) - (pillar_edge - slack)).abs() < 1e-3,
            "{}",
            at(-1.0, 1.0)
        );
        assert!((at(1.475, 1.025) - (0.525 - slack)).abs() < 1e-3);
        assert!((at(0.275, 0.025) - (0.225 - slack)).abs() < 1e-3);
        assert_eq!(at(2.5, 0.0), 0.0, "outside the room");
        let free = map.free_cells(0.3);
        assert!(free
            .iter()
            .all(|p| p.x < 2.0 - 0.3 && (p - Vec2::new(0.5, 0.0)).length() > 0.3));
        assert!(free.len() > 1000);
        // Round the pillar, never through it, about as short as the way round.
        let (from, to) = (Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0));
        let way = map.way(from, to, 0.3).expect("a way round the pillar");
        assert!(way.iter().all(|&p| map.clearance(p) >= 0.3));
        let length: f32 = way.windows(2).map(|w| w[0].distance(w[1])).sum();
        assert!(length > 1.0 && length < 2.2, "{length}");
        assert!(
            map.way(from, Vec2::new(1.9, 0.0), 0.3).is_none(),
            "no room by the wall"
        );
        let reachable = map.reachable(from, 0.3);
        assert_eq!(reachable.len(), free.len(), "one open floor");
        assert!(map.reachable(Vec2::new(1.9, 0.0), 0.3).is_empty());
        assert_eq!(map.largest_region(0.3).len(), free.len());
    }
}
