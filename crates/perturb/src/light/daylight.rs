//! `daylight:S`: the window light drifting as clouds pass. Its intensity is 1 − DIM·c(t), where
//! the cloud cover c(t) in [0, 1] is a smooth seeded curve (a new uniform level every PERIOD
//! seconds, joined by smoothstep), and it turns bluer as it dims (overcast sky is near 6500 K,
//! sunlit daylight nearer 5500 K). It changes over seconds, so a render takes it at the middle of
//! the interval it exposes.

use std::fmt;

use serde::{Deserialize, Serialize};

use crate::rng::RngKey;

pub const NAME: &str = "daylight";

/// (DIM, PERIOD seconds) at severities 1..=5: from thin haze to heavy clouds racing past.
const TABLE: [(f64, f64); 5] = [
    (0.2, 30.0),
    (0.35, 20.0),
    (0.5, 12.0),
    (0.7, 8.0),
    (0.9, 5.0),
];

/// Relative RGB gain of fully overcast against clear daylight (bluer), scaled by the cover.
const OVERCAST_TINT: [f64; 3] = [-0.08, -0.02, 0.1];

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Daylight {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub severity: Option<u8>,
    pub dim: f64,
    pub period_s: f64,
}

impl Daylight {
    pub fn parse(value: &str) -> Result<Self, String> {
        if let Some(s) = super::severity(value) {
            let (dim, period_s) = TABLE[s as usize - 1];
            return Ok(Self {
                severity: Some(s),
                dim,
                period_s,
            });
        }
        let v = super::numbers(
            value,
            2,
            |i, x| match i {
                0 => (0.0..=1.0).contains(&x),
                _ => x > 0.0,
            },
            "a severity 1-5 or DIM/PERIOD (DIM in [0, 1], seconds > 0), e.g. daylight:3 or daylight:0.5/12",
        )?;
        Ok(Self {
            severity: None,
            dim: v[0],
            period_s: v[1],
        })
    }

    /// The severities' parameters as the catalogue's description states them: `0.2/30, …`.
    #[cfg(test)]
    pub(crate) fn severities() -> String {
        TABLE.map(|(d, p)| format!("{d}/{p}")).join(", ")
    }

    /// Cloud cover at `t` seconds, in [0, 1].
    pub fn cover(&self, seed: u64, t: f64) -> f64 {
        let x = t.max(0.0) / self.period_s;
        let k = x.floor();
        let level = |i: f64| RngKey::new(seed, NAME, i as u32, 0).uniform_f64([0, 0, 0, 0]);
        let s = x - k;
        let smooth = s * s * (3.0 - 2.0 * s);
        level(k) + (level(k + 1.0) - level(k)) * smooth
    }

    /// The RGB gain of the daylight at `t`.
    pub fn gain(&self, seed: u64, t: f64) -> [f64; 3] {
        let c = self.cover(seed, t) * self.dim;
        OVERCAST_TINT.map(|tint| (1.0 - c) * (1.0 + tint * c))
    }
}

impl fmt::Display for Daylight {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.severity {
            Some(s) => write!(f, "{NAME}:{s}"),
            None => write!(f, "{NAME}:{}/{}", self.dim, self.period_s),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cover_is_smooth_and_spans_its_range() {
        let d = Daylight::parse("3").unwrap();
        let samples: Vec<f64> = (0..120_000).map(|i| d.cover(5, i as f64 * 0.01)).collect();
        assert!(samples.iter().all(|c| (0.0..=1.0).contains(c)));
        let (lo, hi) = samples
            .iter()
            .fold((1.0f64, 0.0f64), |(l, h), &c| (l.min(c), h.max(c)));
        assert!(lo < 0.05 && hi > 0.95, "{lo} {hi}");
        // Continuous: 10 ms steps change it by far less than a level.
        let step = samples
            .windows(2)
            .map(|w| (w[1] - w[0]).abs())
            .fold(0.0, f64::max);
        assert!(step < 0.01 * 1.5 / 12.0 + 1e-9, "{step}");
        let gain = d.gain(5, 3.0);
        assert!(gain.iter().all(|g| (0.4..=1.05).contains(g)), "{gain:?}");
    }

    #[test]
    fn parses_severities_and_explicit_forms() {
        assert_eq!(Daylight::parse("high").unwrap().to_string(), "daylight:5");
        assert_eq!(
            Daylight::parse("0.5/12").unwrap().to_string(),
            "daylight:0.5/12"
        );
        for bad in ["0", "1.5/12", "0.5/0", "0.5", "x"] {
            assert!(Daylight::parse(bad).is_err(), "{bad}");
        }
    }
}
