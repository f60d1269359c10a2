//! What real indoor photographs give for the realism statistics: the target a built-in scene's
//! frames should fall in.
//!
//! Measured with `scripts/realism-target.sh`, which runs `rslam scene stats` on the indoor
//! photographs that scikit-image 0.26 ships in `skimage/data` (no download): `motorcycle_left`
//! and `motorcycle_right` (Middlebury 2014 stereo, a garage: concrete floor, wooden walls,
//! shelves; 741 × 500), `coffee` (a cup on a table, 600 × 400) and `chelsea` (a cat on a wooden
//! floor, 451 × 300). Each band runs from the least to the most of the photographs' values.
//! They are few, smaller than a SLAM camera's frames and not rooms; the book's scenes page says
//! what that means for reading them.

/// The least and most that the real photographs gave for one statistic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Band {
    pub low: f32,
    pub high: f32,
}

impl Band {
    pub fn holds(&self, value: f32) -> bool {
        (self.low..=self.high).contains(&value)
    }
}

/// The bands of the statistics that say how a frame's texture answers contrast loss.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RealPhotographs {
    pub weak_corner_density: Band,
    pub corner_strength_p50: Band,
    pub strong_corners: Band,
    pub contrast_p10: Band,
    pub contrast_p50: Band,
    pub contrast_p90: Band,
}

pub const REAL_PHOTOGRAPHS: RealPhotographs = RealPhotographs {
    weak_corner_density: Band {
        low: 270.85,
        high: 336.59,
    },
    corner_strength_p50: Band {
        low: 14.0,
        high: 18.0,
    },
    strong_corners: Band {
        low: 0.0316,
        high: 0.2561,
    },
    contrast_p10: Band {
        low: 1.48,
        high: 2.89,
    },
    contrast_p50: Band {
        low: 8.34,
        high: 13.43,
    },
    contrast_p90: Band {
        low: 20.75,
        high: 43.44,
    },
};
