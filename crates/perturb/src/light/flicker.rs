//! `flicker:HZ[/DEPTH]`: the lamps' intensity I(t) = 1 + DEPTH·sin(2π·HZ·t + φ), with a seeded
//! phase φ, all lamps in phase (one mains). A render takes the mean of I over the interval it
//! exposes, in closed form, so a camera sampling at its frame rate sees the flicker alias to
//! |HZ − n·rate| with the amplitude DEPTH·|sinc(HZ·T)| an exposure of T seconds leaves.

use std::f64::consts::TAU;
use std::fmt;

use serde::{Deserialize, Serialize};

use crate::rng::RngKey;

pub const NAME: &str = "flicker";

/// Modulation depth (percent flicker) without an explicit one: a fluorescent tube on a magnetic
/// ballast (IEEE 1789-2015 lists 10–40 % for them).
pub const DEFAULT_DEPTH: f64 = 0.3;

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Flicker {
    pub hz: f64,
    /// Written only when given (`flicker:100/0.8`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub depth: Option<f64>,
}

impl Flicker {
    pub fn parse(value: &str) -> Result<Self, String> {
        let expected = "a frequency HZ > 0 or HZ/DEPTH with DEPTH in [0, 1], e.g. flicker:100 or flicker:120/0.8";
        let v = super::numbers(
            value,
            if value.contains('/') { 2 } else { 1 },
            |i, x| match i {
                0 => x > 0.0,
                _ => (0.0..=1.0).contains(&x),
            },
            expected,
        )?;
        Ok(Self {
            hz: v[0],
            depth: v.get(1).copied(),
        })
    }

    pub fn depth(&self) -> f64 {
        self.depth.unwrap_or(DEFAULT_DEPTH)
    }

    /// The phase at t = 0 for `seed`.
    pub fn phase(seed: u64) -> f64 {
        TAU * RngKey::new(seed, NAME, 0, 0).uniform_f64([0, 0, 0, 0])
    }

    /// ∫ I(t) dt over [a, b] (a ≤ b): the lit time, weighted by the flicker.
    pub fn integral(&self, phase: f64, a: f64, b: f64) -> f64 {
        let w = TAU * self.hz;
        (b - a) + self.depth() * ((w * a + phase).cos() - (w * b + phase).cos()) / w
    }

    /// I(t) at one instant.
    pub fn at(&self, phase: f64, t: f64) -> f64 {
        1.0 + self.depth() * (TAU * self.hz * t + phase).sin()
    }
}

impl fmt::Display for Flicker {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.depth {
            Some(d) => write!(f, "{NAME}:{}/{d}", self.hz),
            None => write!(f, "{NAME}:{}", self.hz),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_integral_is_the_sum_of_the_intensity() {
        let f = Flicker::parse("100/0.8").unwrap();
        let (a, b, phase) = (0.0123, 0.0321, 1.3);
        let steps = 100_000;
        let h = (b - a) / steps as f64;
        let sum: f64 = (0..steps)
            .map(|k| f.at(phase, a + (k as f64 + 0.5) * h) * h)
            .sum();
        assert!((sum - f.integral(phase, a, b)).abs() < 1e-9, "{sum}");
        // A whole number of periods averages to 1.
        assert!((f.integral(phase, 0.0, 0.03) - 0.03).abs() < 1e-12);
    }

    #[test]
    fn parses_a_frequency_and_a_depth() {
        assert_eq!(Flicker::parse("100").unwrap().depth(), DEFAULT_DEPTH);
        assert_eq!(
            Flicker::parse("120/0.8").unwrap().to_string(),
            "flicker:120/0.8"
        );
        assert_eq!(Flicker::parse("100").unwrap().to_string(), "flicker:100");
        for bad in ["0", "-100", "100/1.5", "100/0.3/2", "x"] {
            assert!(Flicker::parse(bad).is_err(), "{bad}");
        }
    }
}
