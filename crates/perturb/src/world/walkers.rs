//! `actors:S`: people walking through the scene. COUNT walkers, each on its own closed path over
//! the scene's free floor at SPEED metres per second, placed so that every path comes within NEAR
//! metres of the camera's (never closer than the walker's body allows: walkers keep clear of
//! the camera, the scene and each other at every instant).

use std::fmt;

use serde::{Deserialize, Serialize};

pub const NAME: &str = "actors";

/// (walkers, metres per second, closest approach to the camera in metres) at severities 1..=5,
/// each like a published dynamic sequence: one person moving slowly at a distance (TUM fr3
/// `sitting_*`: people at a desk, little in view), one walking through the room (TUM
/// `walking_static`), two walking round near the camera (TUM `walking_xyz`), two passing just
/// in front of it (Bonn `person_tracking`), three hurrying past it (Bonn `crowd`).
const TABLE: [(u32, f64, f64); 5] = [
    (1, 0.6, 2.0),
    (1, 1.0, 1.2),
    (2, 1.1, 0.8),
    (2, 1.2, 0.5),
    (3, 1.4, 0.4),
];

/// The most walkers a spec may ask for: each needs room on a built-in scene's floor.
pub const MAX_WALKERS: u32 = 8;
/// Walking speeds a person keeps up, metres per second.
pub const SPEEDS: (f64, f64) = (0.2, 2.0);

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Walkers {
    /// The severity it was given as, if any (the canonical form then writes it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub severity: Option<u8>,
    pub count: u32,
    pub speed_m_s: f64,
    /// How close each walker comes to the camera, metres between its body and the camera
    /// centre.
    pub near_m: f64,
}

impl Walkers {
    pub fn parse(value: &str) -> Result<Self, String> {
        if let Some(s) = crate::spec::parse_severity(value) {
            let (count, speed_m_s, near_m) = TABLE[s as usize - 1];
            return Ok(Self {
                severity: Some(s),
                count,
                speed_m_s,
                near_m,
            });
        }
        let expected = format!(
            "a severity 1-5 or COUNT/SPEED/NEAR (1-{MAX_WALKERS} walkers, {}-{} m/s, a closest approach of 0.4-5 m), e.g. actors:3 or actors:2/1.2/0.8",
            SPEEDS.0, SPEEDS.1
        );
        let parsed: Option<Vec<f64>> = value
            .split('/')
            .map(|v| v.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect();
        let valid = |v: &Vec<f64>| {
            v.len() == 3
                && v[0].fract() == 0.0
                && (1.0..=f64::from(MAX_WALKERS)).contains(&v[0])
                && (SPEEDS.0..=SPEEDS.1).contains(&v[1])
                && (0.4..=5.0).contains(&v[2])
        };
        let v = parsed
            .filter(valid)
            .ok_or_else(|| format!("'{value}': expected {expected}"))?;
        Ok(Self {
            severity: None,
            count: v[0] as u32,
            speed_m_s: v[1],
            near_m: v[2],
        })
    }

    /// The severities' parameters as the catalogue's description states them: `1/0.6/2, …`.
    #[cfg(test)]
    pub(crate) fn severities() -> String {
        TABLE.map(|(c, s, n)| format!("{c}/{s}/{n}")).join(", ")
    }
}

impl fmt::Display for Walkers {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.severity {
            Some(s) => write!(f, "{NAME}:{s}"),
            None => write!(
                f,
                "{NAME}:{}/{}/{}",
                self.count, self.speed_m_s, self.near_m
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_severities_and_explicit_forms() {
        let w = Walkers::parse("5").unwrap();
        assert_eq!((w.count, w.speed_m_s, w.near_m), (3, 1.4, 0.4));
        assert_eq!(w.to_string(), "actors:5");
        let e = Walkers::parse("2/1.2/0.8").unwrap();
        assert_eq!((e.count, e.speed_m_s, e.near_m), (2, 1.2, 0.8));
        assert_eq!(e.to_string(), "actors:2/1.2/0.8");
        assert_eq!(Walkers::parse(&e.to_string()[7..]).unwrap(), e);
        for bad in [
            "0", "6", "0/1/1", "9/1/1", "1.5/1/1", "2/3/1", "2/1/0.1", "2/1", "x",
        ] {
            let message = Walkers::parse(bad).unwrap_err();
            assert!(message.contains("COUNT/SPEED/NEAR"), "{bad}: {message}");
        }
    }
}
