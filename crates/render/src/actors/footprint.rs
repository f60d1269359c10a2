//! What a walker covers of the floor: a capsule along its heading (a segment from heel to toe
//! of its longest step, widened by its shoulders and swinging arms), which holds every vertex
//! of the body in every pose of its gait. Walkers keep capsules, not circles, apart: a circle
//! round a full stride would be a metre across, and no one could pass between two desks.

use glam::Vec2;

use super::walker::{PosedMesh, WalkerBody};

/// Gait phases sampled to find the footprint.
const PHASES: usize = 64;
/// Metres added all round to what the samples reached.
const MARGIN: f32 = 0.01;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Footprint {
    /// Half the segment's length, metres.
    pub half_length: f32,
    /// Metres from the segment to the capsule's edge.
    pub radius: f32,
}

impl Footprint {
    /// The capsule holding `body` at every phase of its gait with steps up to `stride`.
    pub fn of(body: &WalkerBody, stride: f32) -> Self {
        let mut mesh = PosedMesh::default();
        for i in 0..PHASES {
            for step in [0.0, stride / 2.0, stride] {
                body.pose(i as f32 / PHASES as f32, step, &mut mesh);
            }
        }
        let radius = mesh.positions.iter().map(|p| p.y.abs()).fold(0.0, f32::max) + MARGIN;
        let half_length = (mesh.positions.iter())
            .map(|p| p.x.abs() - (radius * radius - p.y * p.y).max(0.0).sqrt())
            .fold(0.0, f32::max)
            + MARGIN;
        Self {
            half_length,
            radius,
        }
    }

    /// The segment's ends for a body at `at` facing `heading`.
    pub fn segment(&self, at: Vec2, heading: f32) -> [Vec2; 2] {
        self.segment_facing(at, Vec2::from_angle(heading))
    }

    /// The segment's ends for a body at `at` facing the unit vector `facing`.
    pub fn segment_facing(&self, at: Vec2, facing: Vec2) -> [Vec2; 2] {
        let along = facing * self.half_length;
        [at - along, at + along]
    }

    /// Whether the capsule at `at` facing `heading` holds the point `p` (body frame x forward).
    pub fn holds(&self, at: Vec2, heading: f32, p: Vec2) -> bool {
        let [a, b] = self.segment(at, heading);
        point_segment_distance(p, a, b) <= self.radius
    }
}

/// Distance from `p` to the segment `a`–`b`.
pub fn point_segment_distance(p: Vec2, a: Vec2, b: Vec2) -> f32 {
    let d = b - a;
    let t = if d.length_squared() > 0.0 {
        ((p - a).dot(d) / d.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + d * t)
}

/// Distance between the segments `a`–`b` and `c`–`d` (0 where they cross).
pub fn segment_distance([a, b]: [Vec2; 2], [c, d]: [Vec2; 2]) -> f32 {
    let side = |p: Vec2, q: Vec2, r: Vec2| (q - p).perp_dot(r - p);
    let (d1, d2) = (side(a, b, c), side(a, b, d));
    let (d3, d4) = (side(c, d, a), side(c, d, b));
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        return 0.0;
    }
    [
        point_segment_distance(a, c, d),
        point_segment_distance(b, c, d),
        point_segment_distance(c, a, b),
        point_segment_distance(d, a, b),
    ]
    .into_iter()
    .fold(f32::INFINITY, f32::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin::rng::Rng;

    #[test]
    fn segment_distances_are_exact() {
        let s = [Vec2::new(0.0, 0.0), Vec2::new(2.0, 0.0)];
        assert_eq!(point_segment_distance(Vec2::new(1.0, 0.5), s[0], s[1]), 0.5);
        assert_eq!(point_segment_distance(Vec2::new(3.0, 0.0), s[0], s[1]), 1.0);
        assert_eq!(
            segment_distance(s, [Vec2::new(1.0, -1.0), Vec2::new(1.0, 1.0)]),
            0.0
        );
        assert_eq!(
            segment_distance(s, [Vec2::new(1.0, 0.3), Vec2::new(1.0, 1.0)]),
            0.3
        );
        let beyond = segment_distance(s, [Vec2::new(3.0, 1.0), Vec2::new(4.0, 1.0)]);
        assert!((beyond - 2f32.sqrt()).abs() < 1e-6);
    }

    #[test]
    fn the_footprint_holds_the_body_in_every_pose_and_is_longer_than_wide_in_stride() {
        let body = WalkerBody::new(&mut Rng::new(5));
        let still = Footprint::of(&body, 0.0);
        let walking = Footprint::of(&body, 0.7);
        assert!(
            walking.half_length > still.half_length + 0.2,
            "{still:?} {walking:?}"
        );
        assert!(walking.radius < 0.4 && walking.half_length + walking.radius < 0.75);
        let mut mesh = PosedMesh::default();
        for i in 0..100 {
            body.pose(i as f32 / 100.0 + 0.003, 0.7, &mut mesh);
        }
        let heading = 0.8;
        let at = Vec2::new(1.0, -2.0);
        let turn = Vec2::from_angle(heading);
        assert!(mesh.positions.iter().all(|p| walking.holds(
            at,
            heading,
            at + turn.rotate(p.truncate())
        )));
    }
}
