//! A walker's route and its timing: a closed, curved path over the floor (a periodic uniform
//! Catmull–Rom spline through waypoints), and how far along it the walker is at each instant
//! (it walks at its speed, and waits or steps back to give way).

use glam::Vec2;

/// Spline samples per waypoint.
const SAMPLES_PER_SPAN: usize = 24;
/// Seconds over which the walker's pace is averaged: it slows into a stop over about a step.
const PACE_WINDOW_S: f64 = 0.5;

/// A curved path through waypoints: closed (a walker's lap) or open (a pushed chair's way).
#[derive(Clone, Debug, PartialEq)]
pub struct Route {
    /// Dense samples; closed, the last point is the first.
    points: Vec<Vec2>,
    /// Arc length at each point, metres; `lengths[0] = 0`.
    lengths: Vec<f32>,
    /// Each piece's direction of travel: radians from +x towards +y, and the unit vector (worked
    /// out once: walks are planned by asking millions of poses).
    facings: Vec<(f32, Vec2)>,
    closed: bool,
}

impl Route {
    /// The closed path through `waypoints` (at least 3).
    pub fn new(waypoints: &[Vec2]) -> Self {
        let n = waypoints.len();
        let at = |i: usize| waypoints[i % n];
        let spans = (0..n).map(|i| [at(i + n - 1), at(i), at(i + 1), at(i + 2)]);
        Self::through(spans, SAMPLES_PER_SPAN, None)
    }

    /// The open path from the first of `waypoints` to the last (at least 2; the ends repeated
    /// as their own neighbours), `samples_per_span` samples between two waypoints.
    pub fn open(waypoints: &[Vec2], samples_per_span: usize) -> Self {
        let last = waypoints.len() as isize - 1;
        let at = |i: isize| waypoints[i.clamp(0, last) as usize];
        let spans = (0..last).map(|i| [at(i - 1), at(i), at(i + 1), at(i + 2)]);
        Self::through(spans, samples_per_span, waypoints.last().copied())
    }

    /// The Catmull–Rom spline over `spans` (each the four control points of one), ending at
    /// `end` (open) or at its start (closed).
    fn through(
        spans: impl Iterator<Item = [Vec2; 4]>,
        samples_per_span: usize,
        end: Option<Vec2>,
    ) -> Self {
        let mut points = Vec::new();
        for [p0, p1, p2, p3] in spans {
            for s in 0..samples_per_span {
                let t = s as f32 / samples_per_span as f32;
                points.push(catmull_rom(p0, p1, p2, p3, t));
            }
        }
        points.push(end.unwrap_or(points[0]));
        let mut lengths = Vec::with_capacity(points.len());
        let mut total = 0.0;
        for (i, p) in points.iter().enumerate() {
            if i > 0 {
                total += p.distance(points[i - 1]);
            }
            lengths.push(total);
        }
        let facings = (points.windows(2))
            .map(|piece| {
                let d = piece[1] - piece[0];
                let heading = d.y.atan2(d.x);
                (heading, Vec2::from_angle(heading))
            })
            .collect();
        Self {
            points,
            lengths,
            facings,
            closed: end.is_none(),
        }
    }

    /// Length of one lap (or of the way, open), metres.
    pub fn length(&self) -> f32 {
        *self.lengths.last().expect("a route has points")
    }

    /// The dense samples.
    pub fn points(&self) -> &[Vec2] {
        &self.points
    }

    /// Position and direction of travel (radians from +x towards +y) `s` metres along (round
    /// and round a closed route; an open one ends at its ends).
    pub fn at(&self, s: f32) -> (Vec2, f32) {
        let (position, i) = self.locate(s);
        (position, self.facings[i - 1].0)
    }

    /// Position and direction of travel as a unit vector (`Vec2::from_angle` of [`Self::at`]'s)
    /// `s` metres along.
    pub fn facing_at(&self, s: f32) -> (Vec2, Vec2) {
        let (position, i) = self.locate(s);
        (position, self.facings[i - 1].1)
    }

    /// Position `s` metres along, and the index of the sample that ends its piece.
    fn locate(&self, s: f32) -> (Vec2, usize) {
        let s = if self.closed {
            s.rem_euclid(self.length())
        } else {
            s.clamp(0.0, self.length())
        };
        let i = (self.lengths.partition_point(|&l| l <= s)).clamp(1, self.points.len() - 1);
        let (a, b) = (self.points[i - 1], self.points[i]);
        let span = self.lengths[i] - self.lengths[i - 1];
        let f = if span > 0.0 {
            (s - self.lengths[i - 1]) / span
        } else {
            0.0
        };
        (a + (b - a) * f, i)
    }

    /// The straight pieces between the dense samples: start, end and the unit vector of the
    /// direction of travel along each.
    pub fn pieces(&self) -> impl Iterator<Item = (Vec2, Vec2, Vec2)> + '_ {
        (self.points.windows(2).zip(&self.facings))
            .map(|(ends, &(_, facing))| (ends[0], ends[1], facing))
    }

    /// Metres along to the sample nearest `point`.
    pub fn arc_length_to(&self, point: Vec2) -> f32 {
        let nearest = (0..self.points.len())
            .min_by(|&a, &b| {
                (self.points[a].distance(point)).total_cmp(&self.points[b].distance(point))
            })
            .unwrap_or(0);
        self.lengths[nearest]
    }
}

/// A route with the walker's place on it every `step_s` seconds from time 0.
#[derive(Clone, Debug, PartialEq)]
pub struct WalkPath {
    route: Route,
    speed: f32,
    step_s: f64,
    /// Metres along the route at each step.
    along: Vec<f32>,
    /// Metres walked (forwards or back) by each step.
    walked: Vec<f32>,
}

/// Where a walker is at an instant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stride {
    pub position: Vec2,
    /// Direction the walker faces, radians from +x towards +y (along the route).
    pub heading: f32,
    /// Metres walked since time 0.
    pub walked: f32,
    /// Pace over the last half second, as a share of the walking speed (0: standing).
    pub pace: f32,
}

impl WalkPath {
    /// `route` walked at `speed` m/s, at `along[i]` metres along it at `i · step_s` seconds.
    pub fn new(route: Route, speed: f32, step_s: f64, along: Vec<f32>) -> Self {
        let mut walked = Vec::with_capacity(along.len());
        let mut total = 0.0;
        for (i, s) in along.iter().enumerate() {
            if i > 0 {
                total += (s - along[i - 1]).abs();
            }
            walked.push(total);
        }
        Self {
            route,
            speed,
            step_s,
            along,
            walked,
        }
    }

    pub fn route(&self) -> &Route {
        &self.route
    }

    pub fn speed(&self) -> f32 {
        self.speed
    }

    /// Metres along the route at each step.
    pub fn along(&self) -> &[f32] {
        &self.along
    }

    /// Where the walker is `t` seconds from the start (it stays where it is after the last
    /// step).
    pub fn at(&self, t: f64) -> Stride {
        let (s, walked) = (self.sample(&self.along, t), self.sample(&self.walked, t));
        let (position, heading) = self.route.at(s);
        let before = self.sample(&self.walked, t - PACE_WINDOW_S);
        let pace = (walked - before) / (self.speed * PACE_WINDOW_S as f32);
        Stride {
            position,
            heading,
            walked,
            pace: pace.clamp(0.0, 1.0),
        }
    }

    /// Where the walker is `t` seconds from the start and the unit vector it faces: [`Self::at`]'s
    /// position, and `Vec2::from_angle` of its heading.
    pub fn facing_at(&self, t: f64) -> (Vec2, Vec2) {
        self.route.facing_at(self.sample(&self.along, t))
    }

    fn sample(&self, values: &[f32], t: f64) -> f32 {
        let x = (t / self.step_s).max(0.0);
        let i = x.floor() as usize;
        if i + 1 >= values.len() {
            return *values.last().expect("a walk has a step");
        }
        let f = (x - i as f64) as f32;
        values[i] + (values[i + 1] - values[i]) * f
    }
}

fn catmull_rom(p0: Vec2, p1: Vec2, p2: Vec2, p3: Vec2, t: f32) -> Vec2 {
    let (t2, t3) = (t * t, t * t * t);
    0.5 * (2.0 * p1
        + (p2 - p0) * t
        + (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3) * t2
        + (3.0 * p1 - p0 - 3.0 * p2 + p3) * t3)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn diamond() -> Route {
        Route::new(&[
            Vec2::new(1.0, 0.0),
            Vec2::new(0.0, 1.0),
            Vec2::new(-1.0, 0.0),
            Vec2::new(0.0, -1.0),
        ])
    }

    #[test]
    fn a_route_passes_its_waypoints_and_faces_where_it_goes() {
        let route = diamond();
        // A Catmull–Rom loop through the corners of a diamond bulges out of the diamond
        // (perimeter 4√2) but stays inside the unit circle.
        let length = route.length();
        assert!(
            length > 4.0 * 2f32.sqrt() && length < std::f32::consts::TAU,
            "{length}"
        );
        assert!(route
            .points()
            .iter()
            .any(|p| p.distance(Vec2::new(0.0, 1.0)) < 1e-5));
        for k in 0..200 {
            let s = k as f32 * 0.03;
            let ((a, heading), (b, _)) = (route.at(s), route.at(s + 0.01));
            assert!(
                (b - a).normalize().dot(Vec2::from_angle(heading)) > 0.99,
                "{s}"
            );
            assert_eq!(route.facing_at(s), (a, Vec2::from_angle(heading)));
        }
        let quarter = route.arc_length_to(Vec2::new(0.0, 1.0));
        assert!(route.at(quarter).0.distance(Vec2::new(0.0, 1.0)) < 1e-4);
    }

    #[test]
    fn a_walk_interpolates_its_steps_counts_steps_back_and_slows_to_a_stop() {
        // 1 m/s for 2 s, a 2 s wait, then 1 s back.
        let along: Vec<f32> = (0..=500)
            .map(|i| {
                let t = i as f32 * 0.01;
                if t <= 2.0 {
                    t
                } else if t <= 4.0 {
                    2.0
                } else {
                    2.0 - (t - 4.0)
                }
            })
            .collect();
        let walk = WalkPath::new(diamond(), 1.0, 0.01, along);
        let a = walk.at(1.005);
        assert!(a.position.distance(walk.route().at(1.005).0) < 1e-5);
        assert!((a.pace - 1.0).abs() < 1e-3 && (a.walked - 1.005).abs() < 1e-4);
        let waiting = walk.at(3.0);
        assert_eq!(waiting.pace, 0.0);
        assert_eq!(waiting.position, walk.at(2.5).position);
        let back = walk.at(5.0);
        assert!((back.walked - 3.0).abs() < 1e-4, "{}", back.walked);
        assert_eq!(
            walk.at(99.0).position,
            walk.at(5.0).position,
            "stays after the end"
        );
    }
}
