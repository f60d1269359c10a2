//! exposure:MS[@K] — motion blur from the camera's own motion: the frame is the average, in
//! linear light, of K renders from the poses the camera passes through during an exposure of MS
//! milliseconds centred on the frame's timestamp. The timestamp and ground-truth pose stay those
//! of mid-exposure.

use std::fmt;

use serde::{Deserialize, Serialize};

use super::parse_milliseconds;

pub const NAME: &str = "exposure";

/// The most sub-frames per exposure, automatic or written as `@K`.
pub const MAX_SUBFRAMES: u32 = 64;

/// The automatic K keeps the image point that moves most within this many pixels between
/// consecutive sub-frames: steps of a pixel or less disappear into the blur.
pub const STEP_PX: f64 = 1.0;

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Exposure {
    /// Exposure time, milliseconds.
    pub ms: f64,
    /// `@K`: sub-frames per exposure; `None`: chosen per frame from the predicted pixel motion.
    pub subframes: Option<u32>,
}

impl Exposure {
    /// Parses `MS` and the optional `@K` of `exposure:MS@K`; the error says what was expected.
    pub fn parse(value: &str, mode: Option<&str>) -> Result<Self, String> {
        let ms = parse_milliseconds(value, "an exposure time", "exposure:20")?;
        let subframes = match mode {
            None => None,
            Some(k) => Some(
                k.parse::<u32>()
                    .ok()
                    .filter(|k| (1..=MAX_SUBFRAMES).contains(k))
                    .ok_or_else(|| {
                        format!("'@{k}': expected a sub-frame count K in 1-{MAX_SUBFRAMES}, e.g. exposure:20@16")
                    })?,
            ),
        };
        Ok(Self { ms, subframes })
    }

    pub fn seconds(&self) -> f64 {
        self.ms / 1000.0
    }

    /// K for an exposure over which the image point that moves most moves `motion_px` pixels:
    /// `@K` when given, else one sub-frame per [`STEP_PX`] of motion (at least one, at most
    /// [`MAX_SUBFRAMES`]); a zero exposure is one sub-frame.
    pub fn subframes_for(&self, motion_px: f64) -> u32 {
        match self.subframes {
            _ if self.ms == 0.0 => 1,
            Some(k) => k,
            None => ((motion_px / STEP_PX).ceil() as u32).clamp(1, MAX_SUBFRAMES),
        }
    }

    /// The capture instants of `k` sub-frames relative to the timestamp, seconds: the centres
    /// of k equal slices of the exposure, so their mean is 0 and one sub-frame alone sits at 0.
    pub fn offsets(&self, k: u32) -> Vec<f64> {
        let t = self.seconds();
        (0..k)
            .map(|j| ((j as f64 + 0.5) / k as f64 - 0.5) * t)
            .collect()
    }
}

impl fmt::Display for Exposure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{NAME}:{}", self.ms)?;
        match self.subframes {
            Some(k) => write!(f, "@{k}"),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_time_and_optional_subframes() {
        assert_eq!(
            Exposure::parse("20", None).unwrap(),
            Exposure {
                ms: 20.0,
                subframes: None
            }
        );
        assert_eq!(
            Exposure::parse("7.5", Some("12")).unwrap().subframes,
            Some(12)
        );
        for (value, mode) in [
            ("-1", None),
            ("x", None),
            ("20", Some("0")),
            ("20", Some("65")),
        ] {
            assert!(Exposure::parse(value, mode).is_err(), "{value} @{mode:?}");
        }
    }

    #[test]
    fn subframes_follow_the_motion_and_offsets_centre_on_the_timestamp() {
        let auto = Exposure::parse("20", None).unwrap();
        assert_eq!(auto.subframes_for(0.0), 1);
        assert_eq!(auto.subframes_for(7.2), 8);
        assert_eq!(auto.subframes_for(1e6), MAX_SUBFRAMES);
        assert_eq!(Exposure::parse("0", None).unwrap().subframes_for(50.0), 1);
        assert_eq!(
            Exposure::parse("20", Some("5")).unwrap().subframes_for(0.0),
            5
        );
        let offsets = auto.offsets(4);
        assert_eq!(offsets, vec![-0.0075, -0.0025, 0.0025, 0.0075]);
        assert_eq!(auto.offsets(1), vec![0.0]);
    }
}
