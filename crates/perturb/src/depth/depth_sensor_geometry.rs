//! The `geometry` entry of `depth_sensor.wgsl` on the CPU: from the rendered depth and the
//! camera, the angle between each pixel's surface normal and its viewing ray, and which pixel's
//! measurement each pixel shows once the depth edges moved laterally (see the module doc of
//! `depth_sensor`).

use std::f32::consts::FRAC_PI_2;

use rslam_core::DepthImage;

use super::SensorParams;
use crate::rng::{self, RngKey};

type Pixel = [i32; 2];

pub(super) struct Geometry<'a> {
    depth: &'a DepthImage,
    p: &'a SensorParams,
    rng: RngKey,
}

impl<'a> Geometry<'a> {
    pub(super) fn new(depth: &'a DepthImage, p: &'a SensorParams) -> Self {
        Self {
            depth,
            p,
            rng: RngKey(p.lateral_key),
        }
    }

    /// Per pixel, the index of the pixel whose measurement it shows once the edges moved (its
    /// own where none swept over it), and θ (radians) of its own surface.
    pub(super) fn survey(&self) -> (Vec<usize>, Vec<f32>) {
        let (w, h) = (self.depth.width as i32, self.depth.height as i32);
        let mut sources = Vec::with_capacity((w * h) as usize);
        let mut angles = Vec::with_capacity((w * h) as usize);
        for y in 0..h {
            for x in 0..w {
                let mut from = self.source([x, y], 0);
                if from == [x, y] {
                    from = self.source([x, y], 1);
                }
                sources.push((from[1] * w + from[0]) as usize);
                angles.push(self.angle([x, y]));
            }
        }
        (sources, angles)
    }

    fn inside(&self, [x, y]: Pixel) -> bool {
        x >= 0 && y >= 0 && x < self.depth.width as i32 && y < self.depth.height as i32
    }

    /// The depth at a pixel, 0 outside the frame.
    fn load(&self, q: Pixel) -> f32 {
        if self.inside(q) {
            self.depth.data[(q[1] as u32 * self.depth.width + q[0] as u32) as usize]
        } else {
            0.0
        }
    }

    /// Whether neighbours of depths a and b along an axis of focal length f are on one surface.
    fn continuous(&self, a: f32, b: f32, f: f32) -> bool {
        a > 0.0 && b > 0.0 && (a - b).abs() <= self.p.limits[1] / f * a.min(b)
    }

    /// Whether an edge lies between neighbours: a jump, or a valid pixel beside an invalid one.
    fn is_edge(&self, a: f32, b: f32, f: f32) -> bool {
        (a > 0.0 || b > 0.0) && !self.continuous(a, b, f)
    }

    /// The difference of the back-projected points of pixels q1 and q0 at depths z1 and z0,
    /// written so nothing cancels: X1 − X0 = u1·(z1 − z0) + (x1 − x0)/fx·z0 with u = (x − cx)/fx
    /// (and alike for Y), so it is the same to the last bits on the GPU.
    fn difference(&self, q1: Pixel, z1: f32, q0: Pixel, z0: f32) -> [f32; 3] {
        let [fx, fy, cx, cy] = self.p.camera;
        let dz = z1 - z0;
        [
            (q1[0] as f32 - cx) / fx * dz + (q1[0] - q0[0]) as f32 / fx * z0,
            (q1[1] as f32 - cy) / fy * dz + (q1[1] - q0[1]) as f32 / fy * z0,
            dz,
        ]
    }

    /// The surface's difference across q along `step`: central, one-sided where one neighbour is
    /// across an edge, zero where both are.
    fn tangent(&self, q: Pixel, z: f32, step: Pixel, f: f32) -> [f32; 3] {
        let before = [q[0] - step[0], q[1] - step[1]];
        let after = [q[0] + step[0], q[1] + step[1]];
        let (a, b) = (self.load(before), self.load(after));
        let (q0, z0) = if self.continuous(a, z, f) {
            (before, a)
        } else {
            (q, z)
        };
        let (q1, z1) = if self.continuous(b, z, f) {
            (after, b)
        } else {
            (q, z)
        };
        self.difference(q1, z1, q0, z0)
    }

    /// θ between the normal and the viewing ray at q, clamped; 0 where q is invalid or its normal
    /// is unknown (no neighbour on its surface along x or along y).
    fn angle(&self, q: Pixel) -> f32 {
        let z = self.load(q);
        if z <= 0.0 {
            return 0.0;
        }
        let (u, v) = (
            self.tangent(q, z, [1, 0], self.p.camera[0]),
            self.tangent(q, z, [0, 1], self.p.camera[1]),
        );
        let n = [
            u[1] * v[2] - u[2] * v[1],
            u[2] * v[0] - u[0] * v[2],
            u[0] * v[1] - u[1] * v[0],
        ];
        let nn = dot(n, n);
        if nn == 0.0 {
            return 0.0;
        }
        let [fx, fy, cx, cy] = self.p.camera;
        let ray = [(q[0] as f32 - cx) / fx, (q[1] as f32 - cy) / fy, 1.0];
        let cos = dot(n, ray).abs() / (nn * dot(ray, ray)).sqrt();
        acos(cos.min(1.0)).min(self.p.limits[0])
    }

    /// The pixel whose depth q takes after the nearest edge along `axis` (0: x, 1: y) within the
    /// reach moved: the growing side's pixel at the edge where the edge swept over q, else q.
    fn source(&self, q: Pixel, axis: u32) -> Pixel {
        let e = if axis == 0 { [1, 0] } else { [0, 1] };
        let f = self.p.camera[axis as usize];
        for d in 0..self.p.lateral[2] as i32 {
            for before in [true, false] {
                // The edge lies between lo and hi = lo + e, d + ½ pixels from q.
                let k = if before { -(d + 1) } else { d };
                let lo = [q[0] + k * e[0], q[1] + k * e[1]];
                let hi = [lo[0] + e[0], lo[1] + e[1]];
                if !self.inside(lo) || !self.inside(hi) {
                    continue;
                }
                let (a, b) = (self.load(lo), self.load(hi));
                if !self.is_edge(a, b, f) {
                    continue;
                }
                let near = if b > 0.0 && (a <= 0.0 || b < a) {
                    hi
                } else {
                    lo
                };
                let s = self.shift(lo, axis, self.sigma_lateral(near, f));
                return match before {
                    true if s > d => lo,
                    false if -s > d => hi,
                    _ => q,
                };
            }
        }
        q
    }

    /// σ_L at the surface of `near`, in frame pixels along an axis of focal length f.
    fn sigma_lateral(&self, near: Pixel, f: f32) -> f32 {
        let theta = self.angle(near);
        let [l0, l1, ..] = self.p.lateral;
        (l0 + l1 * theta / (FRAC_PI_2 - theta)) * f / self.p.limits[2]
    }

    /// The integer shift of the edge after `lo` along `axis`, of standard deviation σ px.
    fn shift(&self, lo: Pixel, axis: u32, sigma: f32) -> i32 {
        let [_, _, reach, rounded_from] = self.p.lateral;
        let u = self.rng.draw([lo[0] as u32, lo[1] as u32, axis, 0]);
        let s = if sigma >= rounded_from {
            let n = rng::normal_pair(u[0], u[1])[0];
            ((sigma * sigma - 1.0 / 12.0).sqrt() * n + 0.5).floor()
        } else {
            let (v, p) = (rng::uniform(u[2]), sigma * sigma / 2.0);
            if v < p {
                -1.0
            } else if v >= 1.0 - p {
                1.0
            } else {
                0.0
            }
        };
        s.clamp(-reach, reach) as i32
    }
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// acos on [0, 1] to 2·10⁻⁸ rad, from +, ×, √ alone (WGSL `acos_poly`), so the GPU's and Rust's
/// θ agree to the last bits (a driver's acos may be off by far more): Abramowitz & Stegun 4.4.46.
fn acos(x: f32) -> f32 {
    // a₀ = 1.5707963050 is the fit's, one f32 step below π/2.
    #[allow(clippy::approx_constant)]
    const A: [f32; 8] = [
        1.570_796_3,
        -0.214_598_8,
        0.088_978_99,
        -0.050_174_305,
        0.030_891_88,
        -0.017_088_126,
        0.006_670_09,
        -0.001_262_491_1,
    ];
    let poly = A.iter().rev().fold(0.0, |p, &a| p * x + a);
    (1.0 - x).sqrt() * poly
}
