//! The overlapping Allan variance of a sensor's error and the fit of Kalibr's two noise
//! parameters to it: σ²(τ) = N²/τ + K²τ/3 (IEEE Std 952-1997, annex C; Kalibr's "IMU Noise
//! Model"). The check that a noise model, or a perturbation of it, is what it says.

/// White-noise density N and random walk K fitted to an Allan variance curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NoiseFit {
    pub noise_density: f64,
    pub random_walk: f64,
}

/// Overlapping Allan variance at τ = `m` bins of `bin_s` seconds, from the running integral
/// `x[j] = bin_s · Σ_{i<j} y_i` of the bin means y (IEEE 1139 / Riley's "Handbook of Frequency
/// Stability Analysis", eq. 14, in phase form). NaN when `x` is too short for one cluster
/// (fewer than 2m + 1 points).
pub fn allan_variance(x: &[f64], m: usize, bin_s: f64) -> f64 {
    let tau = m as f64 * bin_s;
    let terms = x.len().saturating_sub(2 * m);
    if terms == 0 {
        return f64::NAN;
    }
    let sum: f64 = (0..terms)
        .map(|j| (x[j + 2 * m] - 2.0 * x[j + m] + x[j]).powi(2))
        .sum();
    sum / (2.0 * tau * tau * terms as f64)
}

/// N and K from the weighted least-squares fit of σ²(τ) = N²/τ + K²τ/3 (linear in N², K²):
/// relative residuals, each weighted by 1/√τ since the estimate's relative variance grows like
/// τ / (record length).
pub fn fit_white_and_walk(points: &[(f64, f64)]) -> NoiseFit {
    let (mut a11, mut a12, mut a22, mut b1, mut b2) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for &(tau, variance) in points {
        let w = 1.0 / tau.sqrt();
        let (p, q) = (w / (tau * variance), w * tau / (3.0 * variance));
        a11 += p * p;
        a12 += p * q;
        a22 += q * q;
        b1 += w * p;
        b2 += w * q;
    }
    let det = a11 * a22 - a12 * a12;
    let white = (b1 * a22 - b2 * a12) / det;
    let walk = (a11 * b2 - a12 * b1) / det;
    NoiseFit {
        noise_density: white.sqrt(),
        random_walk: walk.sqrt(),
    }
}
