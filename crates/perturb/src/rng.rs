//! Counter-based randomness, the same hash in Rust and in `shaders/common/rng.wgsl`.
//!
//! Every random number is `pcg4d(counter ^ key)`: the [`RngKey`] is derived from
//! (seed, perturbation name, frame, purpose) and the counter names the draw (pixel x, y, channel,
//! round). A frame's randomness therefore depends on nothing that ran before it. PCG4D is from
//! Jarzynski & Olano 2020, "Hash Functions for GPU Rendering", JCGT 9(3).

/// The PCG4D hash; every operation wraps like WGSL `u32` arithmetic.
pub fn pcg4d(input: [u32; 4]) -> [u32; 4] {
    let mut v = input.map(|x| x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223));
    mix(&mut v);
    for x in &mut v {
        *x ^= *x >> 16;
    }
    mix(&mut v);
    v
}

fn mix(v: &mut [u32; 4]) {
    v[0] = v[0].wrapping_add(v[1].wrapping_mul(v[3]));
    v[1] = v[1].wrapping_add(v[2].wrapping_mul(v[0]));
    v[2] = v[2].wrapping_add(v[0].wrapping_mul(v[1]));
    v[3] = v[3].wrapping_add(v[1].wrapping_mul(v[2]));
}

/// 32-bit FNV-1a of a perturbation name: the name's part of every key.
pub fn name_hash(name: &str) -> u32 {
    rslam_core::hash::fnv1a32(name.as_bytes())
}

/// The key of one stream of draws: (seed, perturbation, frame, purpose) hashed twice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RngKey(pub [u32; 4]);

impl RngKey {
    pub fn new(seed: u64, perturbation: &str, frame: u32, purpose: u32) -> Self {
        let k = pcg4d([
            seed as u32,
            (seed >> 32) as u32,
            name_hash(perturbation),
            frame,
        ]);
        Self(pcg4d([k[0] ^ purpose, k[1], k[2], k[3]]))
    }

    /// Four random words for the draw named by `counter` (the WGSL `rng_draw`).
    pub fn draw(&self, counter: [u32; 4]) -> [u32; 4] {
        pcg4d(std::array::from_fn(|i| counter[i] ^ self.0[i]))
    }

    /// Three standard normals for the draw named by `counter` (the WGSL `rng_normal3`).
    pub fn normal3(&self, counter: [u32; 4]) -> [f32; 3] {
        let u = self.draw(counter);
        let a = normal_pair(u[0], u[1]);
        let b = normal_pair(u[2], u[3]);
        [a[0], a[1], b[0]]
    }

    /// f64 uniform in [0, 1) from two words, for CPU-side draws (poses, severities, offsets).
    pub fn uniform_f64(&self, counter: [u32; 4]) -> f64 {
        let u = self.draw(counter);
        unit_f64(u[0], u[1])
    }

    /// f64 standard normal (Box-Muller) for CPU-side draws, from the four words of one draw: two
    /// 53-bit uniforms from one PCG4D output, which are independent. (Uniforms from two counters
    /// one bit apart are not: that gave draws with mean −0.015 and std 1.018 over frame keys.)
    pub fn normal_f64(&self, counter: [u32; 4]) -> f64 {
        let u = self.draw(counter);
        let (u1, u2) = (1.0 - unit_f64(u[0], u[1]), unit_f64(u[2], u[3]));
        (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
    }
}

/// f64 uniform in [0, 1) from 53 bits of two words.
fn unit_f64(hi: u32, lo: u32) -> f64 {
    let bits = ((hi as u64) << 21) ^ (lo as u64 >> 11);
    (bits & ((1 << 53) - 1)) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Uniform in [0, 1): the top 24 bits (WGSL `rng_uniform`).
pub fn uniform(bits: u32) -> f32 {
    (bits >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Uniform in (0, 1], safe for log (WGSL `rng_uniform_open`).
pub fn uniform_open(bits: u32) -> f32 {
    ((bits >> 8) + 1) as f32 * (1.0 / 16_777_216.0)
}

/// Two independent standard normals (Box-Muller, WGSL `rng_normal_pair`).
pub fn normal_pair(a: u32, b: u32) -> [f32; 2] {
    let r = (-2.0 * uniform_open(a).ln()).sqrt();
    let theta = 6.283_185_5 * uniform(b);
    [r * theta.cos(), r * theta.sin()]
}

/// ln Γ(x) for x ≥ 1 (WGSL `log_gamma`): Stirling series at x + n ≥ 7, shifted down by the
/// recurrence, as numpy's `random_loggam` truncated to the terms that matter in f32.
pub fn log_gamma(x: f32) -> f32 {
    if x == 1.0 || x == 2.0 {
        return 0.0;
    }
    let mut x0 = x;
    let mut product = 1.0f32;
    while x0 < 7.0 {
        product *= x0;
        x0 += 1.0;
    }
    let x2 = 1.0 / (x0 * x0);
    let series = (0.083_333_33 + x2 * (-0.002_777_777_8 + x2 * 0.000_793_650_8)) / x0;
    series + 0.918_938_5 + (x0 - 0.5) * x0.ln() - x0 - product.ln()
}

impl RngKey {
    /// An exact Poisson(lambda) sample for `site` = (x, y, channel) (WGSL `rng_poisson`):
    /// inversion by sequential search below 10, Hörmann's PTRS rejection (1993) from 10 up.
    pub fn poisson(&self, site: [u32; 3], lambda: f32) -> f32 {
        if lambda <= 0.0 {
            return 0.0;
        }
        let counter = |round: u32| [site[0], site[1], site[2], round];
        if lambda < 10.0 {
            let u = uniform(self.draw(counter(0))[0]);
            let mut p = (-lambda).exp();
            let mut cdf = p;
            let mut k = 0.0f32;
            while u > cdf && k < 64.0 {
                k += 1.0;
                p *= lambda / k;
                cdf += p;
            }
            return k;
        }
        let slam = lambda.sqrt();
        let loglam = lambda.ln();
        let b = 0.931 + 2.53 * slam;
        let a = -0.059 + 0.02483 * b;
        let invalpha = 1.1239 + 1.1328 / (b - 3.4);
        let vr = 0.9277 - 3.6224 / (b - 2.0);
        for round in 0..64 {
            let w = self.draw(counter(round));
            let u = ((w[0] >> 8) as f32 + 0.5) * (1.0 / 16_777_216.0) - 0.5;
            let v = uniform_open(w[1]);
            let us = 0.5 - u.abs();
            let k = ((2.0 * a / us + b) * u + lambda + 0.43).floor();
            if us >= 0.07 && v <= vr {
                return k;
            }
            if k < 0.0 || (us < 0.013 && v > us) {
                continue;
            }
            let lhs = v.ln() + invalpha.ln() - (a / (us * us) + b).ln();
            if lhs <= -lambda + k * loglam - log_gamma(k + 1.0) {
                return k;
            }
        }
        lambda.floor()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_differ_by_every_component() {
        let base = RngKey::new(7, "fog", 3, 0);
        assert_ne!(base, RngKey::new(8, "fog", 3, 0));
        assert_ne!(base, RngKey::new(7 | (1 << 40), "fog", 3, 0));
        assert_ne!(base, RngKey::new(7, "snow", 3, 0));
        assert_ne!(base, RngKey::new(7, "fog", 4, 0));
        assert_ne!(base, RngKey::new(7, "fog", 3, 1));
        assert_eq!(base, RngKey::new(7, "fog", 3, 0));
    }

    #[test]
    fn uniforms_are_uniform_and_normals_standard() {
        const N: u32 = 200_000;
        let key = RngKey::new(1, "test", 0, 0);
        let mut bins = [0u32; 10];
        let (mut sum, mut sum_sq) = (0.0f64, 0.0f64);
        for i in 0..N {
            let u = uniform(key.draw([i, 0, 0, 0])[0]);
            assert!((0.0..1.0).contains(&u));
            bins[(u * 10.0) as usize] += 1;
            let n = key.normal3([i, 1, 0, 0]);
            for z in n {
                sum += z as f64;
                sum_sq += (z as f64).powi(2);
            }
        }
        // Each decile holds 10% ± 5 binomial standard deviations.
        let expected = N as f64 / 10.0;
        let tol = 5.0 * (expected * 0.9).sqrt();
        for (i, &b) in bins.iter().enumerate() {
            assert!((b as f64 - expected).abs() < tol, "decile {i}: {b}");
        }
        let n = 3.0 * N as f64;
        let mean = sum / n;
        let std = (sum_sq / n - mean * mean).sqrt();
        assert!(mean.abs() < 0.01, "mean {mean}");
        assert!((std - 1.0).abs() < 0.01, "std {std}");
    }

    #[test]
    fn f64_normals_are_standard() {
        let key = RngKey::new(2, "rot", 0, 0);
        let n = 100_000;
        let draws: Vec<f64> = (0..n).map(|i| key.normal_f64([i, 0, 0, 0])).collect();
        let mean = draws.iter().sum::<f64>() / n as f64;
        let var = draws.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / n as f64;
        assert!(mean.abs() < 0.015, "mean {mean}");
        assert!((var.sqrt() - 1.0).abs() < 0.015, "std {}", var.sqrt());
    }

    /// Over keys (one per frame) and over counters alike: mean 0, std 1, kurtosis 3.
    #[test]
    fn one_draw_f64_normals_are_standard_over_keys_and_counters() {
        let n = 100_000u32;
        let over_keys: Vec<f64> = (0..n)
            .map(|k| RngKey::new(3, "imu_jitter", k, 0).normal_f64([0; 4]))
            .collect();
        let key = RngKey::new(3, "imu_jitter", 0, 0);
        let over_counters: Vec<f64> = (0..n).map(|k| key.normal_f64([k, 0, 0, 0])).collect();
        for draws in [over_keys, over_counters] {
            let m = |p: i32| draws.iter().map(|d| d.powi(p)).sum::<f64>() / n as f64;
            // Standard errors: mean 0.0032, std 0.0022, kurtosis 0.0077.
            assert!(m(1).abs() < 0.016, "mean {}", m(1));
            assert!((m(2).sqrt() - 1.0).abs() < 0.011, "std {}", m(2).sqrt());
            assert!((m(4) - 3.0).abs() < 0.08, "kurtosis {}", m(4));
        }
    }

    #[test]
    fn log_gamma_matches_factorials() {
        let mut ln_factorial = 0.0f64;
        for n in 1..=80u32 {
            // log_gamma(n + 1) = ln n!
            ln_factorial += (n as f64).ln();
            let got = log_gamma(n as f32 + 1.0) as f64;
            assert!(
                (got - ln_factorial).abs() < 2e-6 * ln_factorial.max(1.0),
                "ln {n}! = {ln_factorial}, got {got}"
            );
        }
    }

    /// The sampler's histogram against the exact pmf, on both branches (inversion, PTRS).
    #[test]
    fn poisson_samples_follow_the_pmf() {
        const N: u32 = 100_000;
        for lambda in [0.3f32, 2.5, 9.9, 10.0, 17.0, 60.0] {
            let key = RngKey::new(3, "poisson", 0, 0);
            let mut counts = vec![0u32; 200];
            for i in 0..N {
                let k = key.poisson([i, 7, 1], lambda);
                assert!(k >= 0.0 && k.fract() == 0.0, "λ={lambda}: {k}");
                counts[(k as usize).min(199)] += 1;
            }
            let l = lambda as f64;
            let mut pmf = (-l).exp();
            let (mut mean, mut var_sum) = (0.0f64, 0.0f64);
            for (k, &c) in counts.iter().enumerate() {
                if k > 0 {
                    pmf *= l / k as f64;
                }
                let expected = pmf * N as f64;
                // Each bin within 5 binomial standard deviations (+1 for tiny bins).
                let tol = 5.0 * expected.sqrt() + 1.0;
                assert!(
                    (c as f64 - expected).abs() < tol,
                    "λ={lambda} k={k}: {c} vs {expected:.1}"
                );
                mean += k as f64 * c as f64;
                var_sum += (k as f64).powi(2) * c as f64;
            }
            mean /= N as f64;
            let var = var_sum / N as f64 - mean * mean;
            assert!(
                (mean - l).abs() < 5.0 * (l / N as f64).sqrt(),
                "λ={lambda}: mean {mean}"
            );
            assert!((var / l - 1.0).abs() < 0.03, "λ={lambda}: variance {var}");
        }
    }
}
