//! `lights:S`: lamps switched off and back on. Events arrive as a Poisson process (mean gap
//! EVERY seconds, from the sequence's start); each turns off a seeded choice of FRACTION of the
//! lamps (at least one) for DARK seconds. A lamp is dark while any event holds it off. Switching
//! is instant (LED lamps), so a frame exposed across a switch sees the lit fraction of its
//! exposure.

use std::fmt;

use serde::{Deserialize, Serialize};

use crate::rng::RngKey;

pub const NAME: &str = "lights";

/// (fraction of the lamps, mean seconds between events, seconds dark) at severities 1..=5: from
/// one lamp now and then (someone leaving a desk) to every lamp often (a room on motion sensors).
const TABLE: [(f64, f64, f64); 5] = [
    (0.25, 20.0, 2.0),
    (0.25, 10.0, 3.0),
    (0.5, 8.0, 4.0),
    (0.75, 6.0, 5.0),
    (1.0, 5.0, 6.0),
];

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Switching {
    /// The severity it was given as, if any (the canonical form then writes it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub severity: Option<u8>,
    pub fraction: f64,
    pub every_s: f64,
    pub dark_s: f64,
}

/// Lamps `lamps` off over `[start, end)` seconds.
#[derive(Clone, Debug, PartialEq)]
pub struct Outage {
    pub start: f64,
    pub end: f64,
    pub lamps: Vec<usize>,
}

impl Switching {
    pub fn parse(value: &str) -> Result<Self, String> {
        if let Some(s) = super::severity(value) {
            let (fraction, every_s, dark_s) = TABLE[s as usize - 1];
            return Ok(Self {
                severity: Some(s),
                fraction,
                every_s,
                dark_s,
            });
        }
        let v = super::numbers(
            value,
            3,
            |i, x| match i {
                0 => x > 0.0 && x <= 1.0,
                _ => x > 0.0,
            },
            "a severity 1-5 or FRACTION/EVERY/DARK (fraction of lamps in (0, 1], seconds > 0), e.g. lights:3 or lights:0.5/8/4",
        )?;
        Ok(Self {
            severity: None,
            fraction: v[0],
            every_s: v[1],
            dark_s: v[2],
        })
    }

    /// The severities' parameters as the catalogue's description states them: `0.25/20/2, …`.
    #[cfg(test)]
    pub(crate) fn severities() -> String {
        TABLE.map(|(f, e, d)| format!("{f}/{e}/{d}")).join(", ")
    }

    /// The outages of `lamps` lamps that start before `horizon` seconds, in time order.
    pub fn outages(&self, seed: u64, lamps: usize, horizon: f64) -> Vec<Outage> {
        let mut outages = Vec::new();
        if lamps == 0 {
            return outages;
        }
        let count = ((self.fraction * lamps as f64).round() as usize).clamp(1, lamps);
        let mut t = 0.0;
        for event in 0u32.. {
            let key = RngKey::new(seed, NAME, event, 0);
            // Exponential gap: −mean·ln(1 − u), u in [0, 1).
            t += -self.every_s * (1.0 - key.uniform_f64([0, 0, 0, 0])).ln();
            if t >= horizon {
                break;
            }
            // A seeded choice of `count` lamps: the first `count` of a shuffled order.
            let mut order: Vec<usize> = (0..lamps).collect();
            for i in (1..lamps).rev() {
                let j = (key.uniform_f64([1, i as u32, 0, 0]) * (i + 1) as f64) as usize;
                order.swap(i, j.min(i));
            }
            order.truncate(count);
            order.sort_unstable();
            outages.push(Outage {
                start: t,
                end: t + self.dark_s,
                lamps: order,
            });
        }
        outages
    }
}

impl fmt::Display for Switching {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.severity {
            Some(s) => write!(f, "{NAME}:{s}"),
            None => write!(
                f,
                "{NAME}:{}/{}/{}",
                self.fraction, self.every_s, self.dark_s
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outages_arrive_at_the_stated_rate_and_darken_the_stated_share() {
        let s = Switching::parse("3").unwrap();
        let outages = s.outages(7, 4, 80_000.0);
        // Poisson with a mean gap of 8 s: 10 000 events expected, sd 100.
        assert!(
            (outages.len() as f64 - 10_000.0).abs() < 400.0,
            "{}",
            outages.len()
        );
        assert!(outages
            .iter()
            .all(|o| o.lamps.len() == 2 && (o.end - o.start - 4.0).abs() < 1e-9));
        // Each lamp is chosen half the time.
        let lamp0 = outages.iter().filter(|o| o.lamps.contains(&0)).count() as f64;
        assert!((lamp0 / outages.len() as f64 - 0.5).abs() < 0.03);
        assert_eq!(s.outages(7, 4, 100.0), s.outages(7, 4, 100.0), "seeded");
        assert_ne!(s.outages(7, 4, 100.0), s.outages(8, 4, 100.0));
    }

    #[test]
    fn parses_severities_and_explicit_forms() {
        assert_eq!(Switching::parse("5").unwrap().to_string(), "lights:5");
        let e = Switching::parse("0.5/8/4").unwrap();
        assert_eq!((e.fraction, e.every_s, e.dark_s), (0.5, 8.0, 4.0));
        assert_eq!(e.to_string(), "lights:0.5/8/4");
        for bad in ["0", "6", "1.5/8/4", "0.5/0/4", "0.5/8", "x"] {
            assert!(Switching::parse(bad).is_err(), "{bad}");
        }
    }
}
