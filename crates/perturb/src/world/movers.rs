//! The world items that move things through the scene, `actors:S` (people walking) and
//! `objects:S` (a door swinging, chairs pushed): COUNT things at SPEED metres per second coming
//! within NEAR metres of the camera (never closer than their size allows: they keep clear of the
//! camera, the scene and each other at every instant); for walkers, one of them may keep AHEAD
//! metres in front of the camera all along. Each kind states its severity table and limits
//! ([`MoverKind`]); parsing and the canonical form are shared.

use std::fmt;
use std::marker::PhantomData;

use serde::{Deserialize, Serialize};

/// What one world item moves, and its limits.
pub trait MoverKind {
    const NAME: &'static str;
    /// What COUNT counts, for messages.
    const NOUN: &'static str;
    /// (count, metres per second, closest approach to the camera in metres, how far in front of
    /// the camera one of them keeps in metres if one does) at severities 1..=5.
    const TABLE: [(u32, f64, f64, Option<f64>); 5];
    const MAX_COUNT: u32;
    const SPEEDS: (f64, f64);
    const NEAR: (f64, f64);
    /// The distances one of them may keep in front of the camera; `None`: none can (AHEAD is
    /// refused).
    const AHEAD: Option<(f64, f64)>;
    /// An explicit form for messages.
    const EXAMPLE: &'static str;
}

/// People walking through the scene (`actors`).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct WalkerKind;

/// Things moved through the scene (`objects`).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct ObjectKind;

impl MoverKind for WalkerKind {
    const NAME: &'static str = "actors";
    const NOUN: &'static str = "walkers";
    /// One walker, two, three (each severity's walkers those of the one below and one more, in
    /// the same draw, as in TUM fr2 `desk_with_person`, fr3 `walking_*` and Bonn `crowd`), then
    /// two and three with the first kept in front of the camera (Bonn `person_tracking`). Since
    /// walkers wear patterned tops a walker a metre or two away costs ORB-SLAM3 more than one
    /// brushing past the lens, and the table sets how many walkers and how long they stay in
    /// view rather than how near they pass (docs/src/validity.md, "A ladder of walkers").
    const TABLE: [(u32, f64, f64, Option<f64>); 5] = [
        (1, 1.2, 1.0, None),
        (2, 1.2, 1.0, None),
        (3, 1.2, 1.0, None),
        (2, 1.2, 0.8, Some(2.0)),
        (3, 1.2, 0.8, Some(2.0)),
    ];
    /// Each needs room on a built-in scene's floor.
    const MAX_COUNT: u32 = 8;
    /// Walking speeds a person keeps up.
    const SPEEDS: (f64, f64) = (0.2, 2.0);
    const NEAR: (f64, f64) = (0.4, 5.0);
    /// From an arm's length past the body to across a room.
    const AHEAD: Option<(f64, f64)> = Some((0.9, 3.0));
    const EXAMPLE: &'static str = "actors:3, actors:2/1.2/0.8 or actors:2/1.2/0.5/1.5";
}

impl MoverKind for ObjectKind {
    const NAME: &'static str = "objects";
    const NOUN: &'static str = "things moved";
    /// The door swings (Bonn `placing_nonobstructing_box`: one object moved at a distance); the
    /// door and a chair pushed across the room (`moving_nonobstructing_box`); a chair pushed
    /// to just over a metre from the camera (`moving_obstructing_box`); a box carried past and
    /// a chair pushed in front of it (`moving_obstructing_box2`); a box and two chairs, faster
    /// and nearer.
    const TABLE: [(u32, f64, f64, Option<f64>); 5] = [
        (1, 0.4, 2.5, None),
        (2, 0.5, 2.0, None),
        (2, 0.6, 1.2, None),
        (3, 0.7, 0.8, None),
        (4, 0.9, 0.5, None),
    ];
    /// The door, a carried box and up to four chairs.
    const MAX_COUNT: u32 = 6;
    /// How fast a pushed chair goes at most.
    const SPEEDS: (f64, f64) = (0.1, 1.5);
    const NEAR: (f64, f64) = (0.3, 5.0);
    const AHEAD: Option<(f64, f64)> = None;
    const EXAMPLE: &'static str = "objects:2 or objects:3/0.6/1";
}

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Movers<K> {
    /// The severity it was given as, if any (the canonical form then writes it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub severity: Option<u8>,
    pub count: u32,
    /// Metres per second: a walker's walking speed, a pushed object's top speed.
    pub speed_m_s: f64,
    /// How close each walker, or the first pushed object, comes to the camera: metres between
    /// its edge and the camera centre.
    pub near_m: f64,
    /// How far in front of the camera one of the walkers keeps all along, metres (between the
    /// camera centre and the walker's axis); `None` when none does.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ahead_m: Option<f64>,
    #[serde(skip)]
    kind: PhantomData<K>,
}

/// `actors:S`: people walking through the scene.
pub type Walkers = Movers<WalkerKind>;
/// `objects:S`: the room's door swinging, chairs pushed across the floor.
pub type MovingObjects = Movers<ObjectKind>;

impl<K: MoverKind> Movers<K> {
    pub fn parse(value: &str) -> Result<Self, String> {
        if let Some(s) = crate::spec::parse_severity(value) {
            let (count, speed_m_s, near_m, ahead_m) = K::TABLE[s as usize - 1];
            return Ok(Self::new(Some(s), count, speed_m_s, near_m, ahead_m));
        }
        let (forms, ahead_range) = match K::AHEAD {
            Some((least, most)) => (
                "[/AHEAD]",
                format!(", one of them keeping AHEAD = {least}-{most} m in front of the camera"),
            ),
            None => ("", String::new()),
        };
        let expected = format!(
            "a severity 1-5 or COUNT/SPEED/NEAR{forms} (1-{} {}, {}-{} m/s, a closest approach of {}-{} m{ahead_range}), e.g. {}",
            K::MAX_COUNT,
            K::NOUN,
            K::SPEEDS.0,
            K::SPEEDS.1,
            K::NEAR.0,
            K::NEAR.1,
            K::EXAMPLE
        );
        let parsed: Option<Vec<f64>> = value
            .split('/')
            .map(|v| v.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
            .collect();
        let ahead_valid =
            |a: f64| K::AHEAD.is_some_and(|(least, most)| (least..=most).contains(&a));
        let valid = |v: &Vec<f64>| {
            (v.len() == 3 || (v.len() == 4 && ahead_valid(v[3])))
                && v[0].fract() == 0.0
                && (1.0..=f64::from(K::MAX_COUNT)).contains(&v[0])
                && (K::SPEEDS.0..=K::SPEEDS.1).contains(&v[1])
                && (K::NEAR.0..=K::NEAR.1).contains(&v[2])
        };
        let v = parsed
            .filter(valid)
            .ok_or_else(|| format!("'{value}': expected {expected}"))?;
        Ok(Self::new(None, v[0] as u32, v[1], v[2], v.get(3).copied()))
    }

    fn new(
        severity: Option<u8>,
        count: u32,
        speed_m_s: f64,
        near_m: f64,
        ahead_m: Option<f64>,
    ) -> Self {
        Self {
            severity,
            count,
            speed_m_s,
            near_m,
            ahead_m,
            kind: PhantomData,
        }
    }

    /// The explicit form's values: `COUNT/SPEED/NEAR` or `COUNT/SPEED/NEAR/AHEAD`.
    fn values(count: u32, speed_m_s: f64, near_m: f64, ahead_m: Option<f64>) -> String {
        let ahead = ahead_m.map_or(String::new(), |a| format!("/{a}"));
        format!("{count}/{speed_m_s}/{near_m}{ahead}")
    }

    /// The severities' parameters as the catalogue's description states them: `1/1/3, …`.
    #[cfg(test)]
    pub(crate) fn severities() -> String {
        K::TABLE
            .map(|(c, s, n, a)| Self::values(c, s, n, a))
            .join(", ")
    }
}

impl<K: MoverKind> fmt::Display for Movers<K> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.severity {
            Some(s) => write!(f, "{}:{s}", K::NAME),
            None => write!(
                f,
                "{}:{}",
                K::NAME,
                Self::values(self.count, self.speed_m_s, self.near_m, self.ahead_m)
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
        assert_eq!((w.count, w.speed_m_s, w.near_m), (3, 1.2, 0.8));
        assert_eq!(w.ahead_m, Some(2.0));
        assert_eq!(w.to_string(), "actors:5");
        let a = Walkers::parse("2/1.2/0.5/1.5").unwrap();
        assert_eq!(a.ahead_m, Some(1.5));
        assert_eq!(a.to_string(), "actors:2/1.2/0.5/1.5");
        assert_eq!(Walkers::parse(&a.to_string()[7..]).unwrap(), a);
        let e = Walkers::parse("2/1.2/0.8").unwrap();
        assert_eq!((e.count, e.speed_m_s, e.near_m), (2, 1.2, 0.8));
        assert_eq!(e.to_string(), "actors:2/1.2/0.8");
        assert_eq!(Walkers::parse(&e.to_string()[7..]).unwrap(), e);
        for bad in [
            "0",
            "6",
            "0/1/1",
            "9/1/1",
            "1.5/1/1",
            "2/3/1",
            "2/1/0.1",
            "2/1",
            "x",
            "2/1/1/0.5",
            "2/1/1/4",
            "2/1/1/1/1",
        ] {
            let message = Walkers::parse(bad).unwrap_err();
            assert!(
                message.contains("COUNT/SPEED/NEAR[/AHEAD]"),
                "{bad}: {message}"
            );
            assert!(
                message.contains("AHEAD = 0.9-3 m in front"),
                "{bad}: {message}"
            );
        }
        let o = MovingObjects::parse("3/0.6/1").unwrap();
        assert_eq!(o.to_string(), "objects:3/0.6/1");
        assert_eq!(MovingObjects::parse("4").unwrap().count, 3);
        let message = MovingObjects::parse("7/0.5/1").unwrap_err();
        assert!(message.contains("1-6 things moved"), "{message}");
        let message = MovingObjects::parse("3/0.6/1/1.5").unwrap_err();
        assert!(!message.contains("AHEAD"), "{message}");
    }
}
