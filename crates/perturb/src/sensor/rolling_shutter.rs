//! rolling_shutter:MS — rows are read out one after the other, top to bottom over MS
//! milliseconds, and each row sees the scene from the pose at its own read-out time. The
//! timestamp (and ground-truth pose) is the read-out of the middle of the frame. Depth is read
//! out the same way (no global-shutter depth option).

use std::fmt;
use std::ops::Range;

use serde::{Deserialize, Serialize};

use super::parse_milliseconds;

pub const NAME: &str = "rolling_shutter";

/// The most bands of rows rendered from one pose each.
pub const MAX_BANDS: u32 = 64;

/// The automatic band count keeps the image point that moves most within this many pixels
/// between consecutive bands.
pub const STEP_PX: f64 = 0.5;

#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RollingShutter {
    /// Read-out time from the first row to the last, milliseconds.
    pub ms: f64,
}

/// Rows read out (to within a band) at one instant.
#[derive(Clone, Debug, PartialEq)]
pub struct Band {
    pub rows: Range<u32>,
    /// Read-out time of the band's middle row relative to the timestamp, seconds.
    pub offset: f64,
}

impl RollingShutter {
    pub fn parse(value: &str, mode: Option<&str>) -> Result<Self, String> {
        if let Some(m) = mode {
            return Err(format!("rolling_shutter takes no mode, got '@{m}'"));
        }
        let ms = parse_milliseconds(value, "a read-out time", "rolling_shutter:30")?;
        Ok(Self { ms })
    }

    /// Read-out time of row `y` (centre) of `height` relative to the timestamp, seconds.
    pub fn row_offset(&self, y: f64, height: u32) -> f64 {
        ((y + 0.5) / height as f64 - 0.5) * self.ms / 1000.0
    }

    /// Bands of rows of a `height`-row frame over whose read-out the image point that moves
    /// most moves `motion_px` pixels: one per [`STEP_PX`] of motion, at most [`MAX_BANDS`] and
    /// one per row; a zero read-out time is one band.
    pub fn bands(&self, motion_px: f64, height: u32) -> Vec<Band> {
        let count = if self.ms == 0.0 {
            1
        } else {
            ((motion_px / STEP_PX).ceil() as u32).clamp(1, MAX_BANDS.min(height))
        };
        (0..count)
            .map(|b| {
                let rows = b * height / count..(b + 1) * height / count;
                let middle = (rows.start + rows.end) as f64 / 2.0 - 0.5;
                let offset = self.row_offset(middle, height);
                Band { rows, offset }
            })
            .collect()
    }
}

impl fmt::Display for RollingShutter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{NAME}:{}", self.ms)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_tile_the_rows_and_read_out_top_to_bottom() {
        let shutter = RollingShutter::parse("30", None).unwrap();
        let bands = shutter.bands(10.0, 480);
        assert_eq!(bands.len(), 20);
        assert_eq!(bands[0].rows.start, 0);
        assert_eq!(bands.last().unwrap().rows.end, 480);
        assert!(bands.windows(2).all(|w| w[0].rows.end == w[1].rows.start));
        assert!(bands.windows(2).all(|w| w[0].offset < w[1].offset));
        // Symmetric about the middle of the frame: the timestamp's instant.
        assert!((bands[0].offset + bands[19].offset).abs() < 1e-12);
        assert!((shutter.row_offset(0.0, 480) - (0.5 / 480.0 - 0.5) * 0.03).abs() < 1e-12);
        assert_eq!(shutter.bands(1e9, 40).len(), 40, "at most one band per row");
        assert_eq!(RollingShutter { ms: 0.0 }.bands(9.0, 480).len(), 1);
        assert!(RollingShutter::parse("30", Some("2")).is_err());
        assert!(RollingShutter::parse("-3", None).is_err());
    }
}
