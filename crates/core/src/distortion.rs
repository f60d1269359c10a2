//! Lens distortion on normalised image coordinates (x, y) = (X/Z, Y/Z), as OpenCV defines it:
//! radial-tangential (`cv::projectPoints` with `[k1, k2, p1, p2]`, ORB-SLAM3's `PinHole`, EuRoC's
//! `radial-tangential`) and equidistant (Kannala-Brandt: `cv::fisheye`, ORB-SLAM3's
//! `KannalaBrandt8`, EuRoC's `equidistant`). A pixel is (fx·x_d + cx, fy·y_d + cy) of the
//! distorted point (x_d, y_d) = [`Distortion::distort`] of the undistorted one.

use std::fmt;

use glam::{DMat2, DVec2};
use serde::{Deserialize, Serialize};

/// Largest |distort(undistort(p)) − p| [`Distortion::undistort`] accepts, normalised units:
/// under 1e-3 px for any focal length below 10⁶ px.
pub const UNDISTORT_TOLERANCE: f64 = 1e-9;

/// Newton steps [`Distortion::undistort`] takes at most; it converges quadratically in a few.
const MAX_NEWTON_STEPS: usize = 50;

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "model", rename_all = "snake_case")]
pub enum Distortion {
    /// x_d = x·(1 + k1 r² + k2 r⁴) + 2 p1 x y + p2 (r² + 2x²), y_d likewise with p1 ↔ p2.
    Radtan { k1: f64, k2: f64, p1: f64, p2: f64 },
    /// θ = atan r, θ_d = θ (1 + k1 θ² + k2 θ⁴ + k3 θ⁶ + k4 θ⁸), (x_d, y_d) = (θ_d / r)·(x, y).
    Equidistant { k1: f64, k2: f64, k3: f64, k4: f64 },
}

impl Distortion {
    pub const RADTAN: &'static str = "radtan";
    pub const EQUIDISTANT: &'static str = "equidistant";

    /// `radtan(k1,k2,p1,p2)` or `equidistant(k1,k2,k3,k4)`; the error says what was expected.
    pub fn parse(text: &str) -> Result<Self, String> {
        let expected = "expected radtan(k1,k2,p1,p2) or equidistant(k1,k2,k3,k4), e.g. radtan(-0.28,0.07,0.0002,0.00002)";
        let (model, rest) = text
            .split_once('(')
            .ok_or_else(|| format!("'{text}': {expected}"))?;
        let arguments = rest
            .strip_suffix(')')
            .ok_or_else(|| format!("'{text}': no closing ')'; {expected}"))?;
        let values: Vec<f64> = arguments
            .split(',')
            .map(|v| v.trim().parse::<f64>().ok().filter(|v| v.is_finite()))
            .collect::<Option<_>>()
            .ok_or_else(|| format!("'{text}': the coefficients must be numbers; {expected}"))?;
        let [a, b, c, d] = values[..] else {
            return Err(format!(
                "'{text}': {} coefficients, expected 4; {expected}",
                values.len()
            ));
        };
        let model = model.trim();
        Self::from_coefficients(model, [a, b, c, d])
            .ok_or_else(|| format!("unknown lens model '{model}'; {expected}"))
    }

    /// The lens of `model` ([`Distortion::RADTAN`] or [`Distortion::EQUIDISTANT`]) with
    /// [`Distortion::coefficients`] `[a, b, c, d]`; `None` for another model.
    pub fn from_coefficients(model: &str, [a, b, c, d]: [f64; 4]) -> Option<Self> {
        match model {
            Self::RADTAN => Some(Self::Radtan {
                k1: a,
                k2: b,
                p1: c,
                p2: d,
            }),
            Self::EQUIDISTANT => Some(Self::Equidistant {
                k1: a,
                k2: b,
                k3: c,
                k4: d,
            }),
            _ => None,
        }
    }

    pub fn model(&self) -> &'static str {
        match self {
            Self::Radtan { .. } => Self::RADTAN,
            Self::Equidistant { .. } => Self::EQUIDISTANT,
        }
    }

    /// The four coefficients in the order OpenCV takes them: [k1, k2, p1, p2] or [k1, k2, k3, k4].
    pub fn coefficients(&self) -> [f64; 4] {
        match *self {
            Self::Radtan { k1, k2, p1, p2 } => [k1, k2, p1, p2],
            Self::Equidistant { k1, k2, k3, k4 } => [k1, k2, k3, k4],
        }
    }

    /// The distorted normalised point of the undistorted one `p`.
    pub fn distort(&self, p: DVec2) -> DVec2 {
        self.distort_with_jacobian(p).0
    }

    /// The undistorted normalised point whose distortion is `distorted`, by Newton's method
    /// from `distorted` itself; `None` where it does not converge to within
    /// [`UNDISTORT_TOLERANCE`], where the model folds over (a non-positive Jacobian: two rays
    /// meet at one pixel) or, for the equidistant model, where the ray is 90° or more off the
    /// axis (no pinhole sees it).
    pub fn undistort(&self, distorted: DVec2) -> Option<DVec2> {
        let mut p = distorted;
        for _ in 0..MAX_NEWTON_STEPS {
            let (at, jacobian) = self.distort_with_jacobian(p);
            let residual = at - distorted;
            let determinant = jacobian.determinant();
            if determinant.is_nan() || determinant <= 0.0 || !at.is_finite() {
                return None;
            }
            if residual.length() <= UNDISTORT_TOLERANCE {
                return Some(p);
            }
            p -= jacobian.inverse() * residual;
            if let Self::Equidistant { .. } = self {
                if p.length().atan() >= std::f64::consts::FRAC_PI_2 - 1e-9 || !p.is_finite() {
                    return None;
                }
            }
        }
        None
    }

    fn distort_with_jacobian(&self, p: DVec2) -> (DVec2, DMat2) {
        let DVec2 { x, y } = p;
        let r2 = x * x + y * y;
        match *self {
            Self::Radtan { k1, k2, p1, p2 } => {
                let radial = 1.0 + k1 * r2 + k2 * r2 * r2;
                // d(radial)/dx = 2x·(k1 + 2 k2 r²), likewise for y.
                let slope = k1 + 2.0 * k2 * r2;
                let distorted = DVec2::new(
                    x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
                    y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y,
                );
                let dxdx = radial + 2.0 * x * x * slope + 2.0 * p1 * y + 6.0 * p2 * x;
                let dxdy = 2.0 * x * y * slope + 2.0 * p1 * x + 2.0 * p2 * y;
                let dydy = radial + 2.0 * y * y * slope + 6.0 * p1 * y + 2.0 * p2 * x;
                let jacobian = DMat2::from_cols(DVec2::new(dxdx, dxdy), DVec2::new(dxdy, dydy));
                (distorted, jacobian)
            }
            Self::Equidistant { k1, k2, k3, k4 } => {
                let r = r2.sqrt();
                let theta = r.atan();
                let t2 = theta * theta;
                let theta_d = theta * (1.0 + t2 * (k1 + t2 * (k2 + t2 * (k3 + t2 * k4))));
                let dtheta_d =
                    1.0 + t2 * (3.0 * k1 + t2 * (5.0 * k2 + t2 * (7.0 * k3 + t2 * 9.0 * k4)));
                if r < 1e-12 {
                    // θ_d / r → 1 + … at the axis: the identity to first order.
                    return (p, DMat2::IDENTITY);
                }
                let scale = theta_d / r;
                // d(scale)/dr = (θ_d'(θ)·θ'(r)·r − θ_d) / r², θ'(r) = 1 / (1 + r²).
                let dscale = (dtheta_d / (1.0 + r2) * r - theta_d) / r2;
                let outer = |a: f64, b: f64| dscale * a * b / r;
                let jacobian = DMat2::from_cols(
                    DVec2::new(scale + outer(x, x), outer(x, y)),
                    DVec2::new(outer(x, y), scale + outer(y, y)),
                );
                (p * scale, jacobian)
            }
        }
    }
}

impl fmt::Display for Distortion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [a, b, c, d] = self.coefficients();
        write!(f, "{}({a},{b},{c},{d})", self.model())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const RADTAN: Distortion = Distortion::Radtan {
        k1: -0.28,
        k2: 0.07,
        p1: 2e-4,
        p2: -3e-4,
    };
    const EQUIDISTANT: Distortion = Distortion::Equidistant {
        k1: 0.02,
        k2: -0.01,
        k3: 0.003,
        k4: -0.0005,
    };

    #[test]
    fn parses_both_models_and_prints_them_back() {
        for text in [
            "radtan(-0.28,0.07,0.0002,-0.0003)",
            "equidistant(0.02,-0.01,0.003,-0.0005)",
        ] {
            let lens = Distortion::parse(text).unwrap();
            assert_eq!(lens.to_string(), text);
        }
        assert_eq!(
            Distortion::parse(" radtan( -0.28 , 0.07,2e-4,-3e-4)").unwrap(),
            RADTAN
        );
        for (bad, says) in [
            ("radtan", "expected radtan("),
            ("radtan(1,2,3", "closing"),
            ("radtan(1,2,3)", "3 coefficients"),
            ("radtan(1,x,3,4)", "numbers"),
            ("radtan(1,inf,3,4)", "numbers"),
            ("fisheye(1,2,3,4)", "unknown lens model 'fisheye'"),
        ] {
            let message = Distortion::parse(bad).unwrap_err();
            assert!(message.contains(says), "{bad}: {message}");
        }
    }

    /// Hand-computed: radtan at (0.3, −0.2): r² = 0.13, radial = 1 − 0.0364 + 0.001183.
    #[test]
    fn radtan_matches_the_formula_by_hand() {
        let radial = 1.0 - 0.28 * 0.13 + 0.07 * 0.13 * 0.13;
        let x = 0.3 * radial + 2.0 * 2e-4 * 0.3 * -0.2 + -3e-4 * (0.13 + 2.0 * 0.09);
        let y = -0.2 * radial + 2e-4 * (0.13 + 2.0 * 0.04) + 2.0 * -3e-4 * 0.3 * -0.2;
        let got = RADTAN.distort(DVec2::new(0.3, -0.2));
        assert!((got - DVec2::new(x, y)).length() < 1e-15, "{got}");
    }

    /// Equidistant without coefficients is the ideal fisheye: radius = angle off the axis.
    #[test]
    fn equidistant_radius_is_the_angle() {
        let ideal = Distortion::Equidistant {
            k1: 0.0,
            k2: 0.0,
            k3: 0.0,
            k4: 0.0,
        };
        let got = ideal.distort(DVec2::new(1.0, 0.0));
        assert!((got.x - std::f64::consts::FRAC_PI_4).abs() < 1e-15 && got.y == 0.0);
    }

    #[test]
    fn undistort_inverts_distort_and_the_jacobian_is_the_derivative() {
        for lens in [RADTAN, EQUIDISTANT] {
            for &(x, y) in &[
                (0.0, 0.0),
                (0.4, 0.3),
                (-0.6, 0.2),
                (0.05, -0.7),
                (-0.8, -0.5),
            ] {
                let p = DVec2::new(x, y);
                let back = lens.undistort(lens.distort(p)).unwrap();
                assert!((back - p).length() < 1e-9, "{lens}: {p} → {back}");
                let (_, jacobian) = lens.distort_with_jacobian(p);
                let h = 1e-6;
                for (axis, column) in [(DVec2::X, jacobian.x_axis), (DVec2::Y, jacobian.y_axis)] {
                    let numeric =
                        (lens.distort(p + axis * h) - lens.distort(p - axis * h)) / (2.0 * h);
                    assert!(
                        (numeric - column).length() < 1e-7,
                        "{lens} at {p}: {numeric} vs {column}"
                    );
                }
            }
        }
    }

    /// Strong barrel distortion folds over far out: undistort refuses those points instead of
    /// answering with a ray from the other branch.
    #[test]
    fn undistort_refuses_a_folded_model() {
        let strong = Distortion::Radtan {
            k1: -0.5,
            k2: 0.0,
            p1: 0.0,
            p2: 0.0,
        };
        // x·(1 − 0.5x²) peaks at x = √(2/3), x_d ≈ 0.544; nothing distorts beyond.
        assert!(strong.undistort(DVec2::new(0.6, 0.0)).is_none());
        assert!(strong.undistort(DVec2::new(0.4, 0.0)).is_some());
    }
}
