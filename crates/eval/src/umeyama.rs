//! Umeyama's least-squares similarity between two point sets (Umeyama, "Least-squares estimation
//! of transformation parameters between two point patterns", IEEE PAMI 1991), following evo's
//! `geometry.umeyama_alignment` step by step.

use glam::{DMat3, DVec3};
use nalgebra::DMatrix;

use crate::{EvalError, Similarity};

/// Singular values at or below this fraction of the largest count as zero (besides evo's
/// absolute `eps`): exact lines built in floating point leave rounding-level singular values that
/// an absolute threshold misses once coordinates are metres rather than millimetres.
const RELATIVE_RANK_TOLERANCE: f64 = 1e-12;

/// The similarity `y ≈ s·R·x + t` minimising the squared distances over corresponding points.
/// Without `with_scale`, `s = 1`. Fewer than two non-zero singular values of the
/// cross-covariance (a static set, a straight line) is an error, as in evo.
pub fn umeyama(x: &[DVec3], y: &[DVec3], with_scale: bool) -> Result<Similarity, EvalError> {
    assert_eq!(x.len(), y.len(), "umeyama needs corresponding points");
    let n = x.len();
    if n == 0 {
        return Err(EvalError::Degenerate {
            positions: 0,
            reason: "no points",
        });
    }
    let inv_n = 1.0 / n as f64;
    let mean_x = x.iter().copied().sum::<DVec3>() * inv_n; // eq. 34
    let mean_y = y.iter().copied().sum::<DVec3>() * inv_n; // eq. 35
    let sigma_x = inv_n
        * x.iter()
            .map(|p| (*p - mean_x).length_squared())
            .sum::<f64>(); // eq. 36

    // Cross-covariance, eq. 38: Σ (y_i − μ_y)(x_i − μ_x)ᵀ / n.
    let mut covariance = [[0.0_f64; 3]; 3];
    for (px, py) in x.iter().zip(y) {
        let dx = (*px - mean_x).to_array();
        let dy = (*py - mean_y).to_array();
        for (row, dy_r) in covariance.iter_mut().zip(dy) {
            for (cell, dx_c) in row.iter_mut().zip(dx) {
                *cell += dy_r * dx_c;
            }
        }
    }
    let covariance = DMatrix::from_fn(3, 3, |r, c| covariance[r][c] * inv_n);

    // A dynamic matrix takes nalgebra's general (Golub–Kahan) SVD, sorted descending, rather than
    // its eigen-decomposition shortcut for 3×3 that loses the small singular values.
    let svd = covariance.svd(true, true);
    let (Some(u), Some(v_t)) = (svd.u, svd.v_t) else {
        unreachable!("SVD asked for U and Vᵀ");
    };
    let d = svd.singular_values;
    let zero_below = f64::EPSILON.max(d[0] * RELATIVE_RANK_TOLERANCE);
    if d.iter().filter(|s| **s > zero_below).count() < 2 {
        return Err(EvalError::Degenerate {
            positions: n,
            reason: if d[0] <= f64::EPSILON {
                "they do not move"
            } else {
                "they lie on a straight line"
            },
        });
    }
    // eq. 43: flip the last axis when U·Vᵀ would be a reflection (Kabsch).
    let reflection = u.determinant() * v_t.determinant() < 0.0;
    let s_last = if reflection { -1.0 } else { 1.0 };
    let to_glam =
        |m: &DMatrix<f64>| DMat3::from_cols_array(&std::array::from_fn(|i| m[(i % 3, i / 3)]));
    let u = to_glam(&u);
    let v_t = to_glam(&v_t);
    let s = DMat3::from_diagonal(DVec3::new(1.0, 1.0, s_last));
    let rotation = u * s * v_t; // eq. 40
    let scale = if with_scale {
        (d[0] + d[1] + s_last * d[2]) / sigma_x // eq. 42
    } else {
        1.0
    };
    let translation = mean_y - scale * (rotation * mean_x); // eq. 41
    Ok(Similarity {
        rotation,
        translation,
        scale,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{noise, random_rotation, TestRng};

    /// Tolerance on recovered transforms from exact (noise-free) correspondences.
    const EXACT_TOL: f64 = 1e-9;

    fn max_abs(m: DMat3) -> f64 {
        m.to_cols_array().iter().fold(0.0, |a, v| a.max(v.abs()))
    }

    fn cloud(rng: &mut TestRng, n: usize) -> Vec<DVec3> {
        (0..n).map(|_| rng.vec3() * 4.0).collect()
    }

    #[test]
    fn recovers_random_similarities_exactly() {
        let mut rng = TestRng::new(7);
        for case in 0..200 {
            let n = 3 + case % 40;
            let x = cloud(&mut rng, n);
            let truth = Similarity {
                rotation: random_rotation(&mut rng),
                translation: rng.vec3() * 10.0,
                scale: 0.1 + 5.0 * rng.unit(),
            };
            let y: Vec<DVec3> = x.iter().map(|p| truth.apply(*p)).collect();
            let found = umeyama(&x, &y, true).unwrap();
            assert!(
                (found.scale - truth.scale).abs() < EXACT_TOL * truth.scale,
                "case {case}"
            );
            assert!(
                max_abs(found.rotation - truth.rotation) < EXACT_TOL,
                "case {case}"
            );
            assert!(
                (found.translation - truth.translation).length() < EXACT_TOL * 10.0,
                "case {case}"
            );
            // Without scale the rotation is still the true one (the residual is isotropic).
            let rigid = umeyama(&x, &y, false).unwrap();
            assert_eq!(rigid.scale, 1.0);
            assert!(
                max_abs(rigid.rotation - truth.rotation) < EXACT_TOL,
                "case {case}"
            );
        }
    }

    #[test]
    fn result_is_a_proper_rotation_and_beats_perturbed_transforms() {
        let mut rng = TestRng::new(11);
        for case in 0..100 {
            let x = cloud(&mut rng, 30);
            let y: Vec<DVec3> = x.iter().map(|p| *p * 1.3 + noise(&mut rng, 0.5)).collect();
            for with_scale in [false, true] {
                let best = umeyama(&x, &y, with_scale).unwrap();
                let r = best.rotation;
                assert!(max_abs(r.transpose() * r - DMat3::IDENTITY) < 1e-12);
                assert!(
                    (r.determinant() - 1.0).abs() < 1e-12,
                    "case {case}: a reflection"
                );
                let cost = |t: &Similarity| {
                    x.iter()
                        .zip(&y)
                        .map(|(a, b)| (t.apply(*a) - *b).length_squared())
                        .sum::<f64>()
                };
                let optimum = cost(&best);
                for _ in 0..5 {
                    let nudged = Similarity {
                        rotation: random_small_rotation(&mut rng) * best.rotation,
                        translation: best.translation + noise(&mut rng, 1e-3),
                        scale: if with_scale {
                            best.scale * (1.0 + 1e-3 * (rng.unit() - 0.5))
                        } else {
                            1.0
                        },
                    };
                    assert!(cost(&nudged) >= optimum, "case {case}: not a minimum");
                }
            }
        }
    }

    fn random_small_rotation(rng: &mut TestRng) -> DMat3 {
        DMat3::from_axis_angle(rng.vec3().normalize(), 1e-3)
    }

    #[test]
    fn mirrored_points_still_give_a_rotation() {
        let mut rng = TestRng::new(3);
        let x = cloud(&mut rng, 20);
        let y: Vec<DVec3> = x.iter().map(|p| DVec3::new(-p.x, p.y, p.z)).collect();
        let r = umeyama(&x, &y, false).unwrap().rotation;
        assert!((r.determinant() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn static_and_collinear_sets_are_degenerate() {
        let still = vec![DVec3::new(1.0, 2.0, 3.0); 5];
        let err = umeyama(&still, &still, false).unwrap_err();
        assert_eq!(
            err.to_string(),
            "cannot align: the 5 associated positions are degenerate (they do not move); \
             Umeyama alignment needs them to span a plane (or evaluate without alignment)"
        );
        let line: Vec<DVec3> = (0..10)
            .map(|i| DVec3::new(1.0, 2.0, 3.0) * i as f64)
            .collect();
        let err = umeyama(&line, &line, true).unwrap_err();
        assert!(
            err.to_string().contains("(they lie on a straight line)"),
            "{err}"
        );
    }

    #[test]
    fn planar_sets_align() {
        let mut rng = TestRng::new(5);
        let x: Vec<DVec3> = (0..50)
            .map(|_| DVec3::new(rng.unit(), rng.unit(), 0.0))
            .collect();
        let truth = Similarity {
            rotation: random_rotation(&mut rng),
            translation: DVec3::new(1.0, -2.0, 0.5),
            scale: 2.0,
        };
        let y: Vec<DVec3> = x.iter().map(|p| truth.apply(*p)).collect();
        let found = umeyama(&x, &y, true).unwrap();
        assert!(max_abs(found.rotation - truth.rotation) < EXACT_TOL);
        assert!((found.scale - 2.0).abs() < EXACT_TOL);
    }
}
