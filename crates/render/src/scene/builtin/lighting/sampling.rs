//! Low-discrepancy sample points for the bake: the k-th of n points of a Hammersley set, shifted
//! by a per-vertex rotation (Cranley–Patterson) so neighbouring vertices do not share one
//! pattern of errors.

use std::f32::consts::TAU;

use glam::{Vec2, Vec3};

/// The k-th of n points in the unit square, shifted by `rotation` modulo 1.
pub fn square(k: u32, n: u32, rotation: Vec2) -> Vec2 {
    let p = Vec2::new((k as f32 + 0.5) / n as f32, radical_inverse(k));
    (p + rotation).fract()
}

/// Van der Corput radical inverse in base 2.
fn radical_inverse(k: u32) -> f32 {
    k.reverse_bits() as f32 * (1.0 / 4_294_967_296.0)
}

/// A point of the unit disc, uniform in area.
pub fn disc(u: Vec2) -> Vec2 {
    let r = u.x.sqrt();
    let a = TAU * u.y;
    Vec2::new(r * a.cos(), r * a.sin())
}

/// A unit direction about the unit normal `n`, cosine-weighted (pdf cos θ / π).
pub fn cosine_hemisphere(n: Vec3, u: Vec2) -> Vec3 {
    let d = disc(u);
    let (t, b) = n.any_orthonormal_pair();
    let up = (1.0 - d.length_squared()).max(0.0).sqrt();
    (t * d.x + b * d.y + n * up).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cosine_hemisphere_has_the_mean_cosine_of_its_density() {
        // E[cos θ] under pdf cos θ / π is 2/3.
        let n = Vec3::new(0.3, -0.5, 0.8).normalize();
        let count = 4096;
        let mean = (0..count)
            .map(|k| cosine_hemisphere(n, square(k, count, Vec2::new(0.37, 0.61))).dot(n))
            .sum::<f32>()
            / count as f32;
        assert!((mean - 2.0 / 3.0).abs() < 2e-3, "{mean}");
    }

    #[test]
    fn disc_points_fill_the_disc_evenly() {
        let count = 4096;
        let inner = (0..count)
            .filter(|&k| disc(square(k, count, Vec2::ZERO)).length() < 0.5f32.sqrt())
            .count();
        assert!((inner as f32 / count as f32 - 0.5).abs() < 0.01, "{inner}");
    }
}
