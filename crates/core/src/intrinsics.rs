use serde::{Deserialize, Serialize};

use crate::limits::MAX_IMAGE_SIDE;
use crate::{printable, CoreError};

/// Frame rate of the Replica camera preset and of Replica `traj.txt` files (docs/src/formats.md, "Camera conventions").
pub const REPLICA_RATE_HZ: f64 = 20.0;
/// Frame rate of the TUM camera preset (docs/src/formats.md, "Camera conventions").
pub const TUM_RATE_HZ: f64 = 30.0;

/// Pinhole intrinsics, pixel centres at integer coordinates (OpenCV convention).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Intrinsics {
    pub width: u32,
    pub height: u32,
    pub fx: f64,
    pub fy: f64,
    pub cx: f64,
    pub cy: f64,
}

impl Intrinsics {
    /// The Replica SLAM camera (NICE-SLAM's config): 1200×680, f = 600.
    pub const REPLICA: Intrinsics = Intrinsics {
        width: 1200,
        height: 680,
        fx: 600.0,
        fy: 600.0,
        cx: 599.5,
        cy: 339.5,
    };

    /// The TUM RGB-D default camera (ROS default calibration): 640×480, f = 525.
    pub const TUM: Intrinsics = Intrinsics {
        width: 640,
        height: 480,
        fx: 525.0,
        fy: 525.0,
        cx: 319.5,
        cy: 239.5,
    };

    /// The rate of the preset `text` names (`tum`: 30 Hz); 20 Hz for `replica` and explicit
    /// cameras, the documented default of `rslam render`.
    pub fn preset_rate_hz(text: &str) -> f64 {
        if text == "tum" {
            TUM_RATE_HZ
        } else {
            REPLICA_RATE_HZ
        }
    }

    /// `replica`, `tum` or `W,H,FX,FY,CX,CY`.
    pub fn parse(text: &str) -> Result<Self, CoreError> {
        match text {
            "replica" => return Ok(Self::REPLICA),
            "tum" => return Ok(Self::TUM),
            _ => {}
        }
        let bad = || CoreError::BadCamera {
            text: printable(text),
        };
        let parts: Vec<&str> = text.split(',').map(str::trim).collect();
        if parts.len() != 6 {
            return Err(bad());
        }
        let width: u32 = parts[0].parse().map_err(|_| bad())?;
        let height: u32 = parts[1].parse().map_err(|_| bad())?;
        let f: Vec<f64> = parts[2..]
            .iter()
            .map(|p| p.parse::<f64>().map_err(|_| bad()))
            .collect::<Result<_, _>>()?;
        let k = Self {
            width,
            height,
            fx: f[0],
            fy: f[1],
            cx: f[2],
            cy: f[3],
        };
        k.check().map_err(|_| bad())?;
        Ok(k)
    }

    /// A camera from EuRoC's and Kalibr's `resolution: [w, h]` and `intrinsics: [fu, fv, cu,
    /// cv]`, checked as [`Intrinsics::check`] does.
    pub fn from_pinhole(
        (width, height): (u32, u32),
        [fx, fy, cx, cy]: [f64; 4],
    ) -> Result<Self, String> {
        let camera = Self {
            width,
            height,
            fx,
            fy,
            cx,
            cy,
        };
        camera.check()?;
        Ok(camera)
    }

    /// Whether this is a camera rslam can use: 1 to [`MAX_IMAGE_SIDE`] pixels a side, positive
    /// finite focal lengths, a finite principal point. The error says what is wrong.
    pub fn check(&self) -> Result<(), String> {
        for (name, side) in [("width", self.width), ("height", self.height)] {
            if !(1..=MAX_IMAGE_SIDE).contains(&side) {
                return Err(format!(
                    "{name} {side}: expected 1 to {MAX_IMAGE_SIDE} pixels"
                ));
            }
        }
        for (name, f) in [("fx", self.fx), ("fy", self.fy)] {
            if !(f.is_finite() && f > 0.0) {
                return Err(format!(
                    "{name} {f}: expected a positive finite focal length"
                ));
            }
        }
        for (name, c) in [("cx", self.cx), ("cy", self.cy)] {
            if !c.is_finite() {
                return Err(format!("{name} {c}: expected a finite principal point"));
            }
        }
        Ok(())
    }

    pub fn pixel_count(&self) -> usize {
        self.width as usize * self.height as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_presets_and_explicit_form() {
        assert_eq!(Intrinsics::parse("tum").unwrap(), Intrinsics::TUM);
        let k = Intrinsics::parse("64,48,50,51,31.5,23.5").unwrap();
        assert_eq!((k.width, k.height, k.fy, k.cy), (64, 48, 51.0, 23.5));
    }

    #[test]
    fn rejects_malformed_camera() {
        for bad in [
            "",
            "1,2,3",
            "0,48,50,50,1,1",
            "64,48,-1,50,1,1",
            "a,b,c,d,e,f",
            "64,48,50,50,nan,1",
            "64,48,inf,50,1,1",
            "16385,48,50,50,1,1",
        ] {
            assert!(Intrinsics::parse(bad).is_err(), "{bad}");
        }
    }
}
