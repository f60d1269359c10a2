use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// The on-disk layout of a dataset (docs/src/formats.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DatasetFormat {
    /// `results/frameNNNNNN.jpg`, `results/depthNNNNNN.png`, `traj.txt`, `cam_params.json`.
    Replica,
    /// `rgb/<t>.png`, `depth/<t>.png`, `rgb.txt`, `depth.txt`, `groundtruth.txt`, `associations.txt`.
    Tum,
}

impl DatasetFormat {
    /// 16-bit depth PNG units per metre.
    pub fn depth_scale(self) -> f64 {
        match self {
            Self::Replica => 6553.5,
            Self::Tum => 5000.0,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Self::Replica => "replica",
            Self::Tum => "tum",
        }
    }
}

impl fmt::Display for DatasetFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for DatasetFormat {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "replica" => Ok(Self::Replica),
            "tum" => Ok(Self::Tum),
            _ => Err(format!(
                "unknown dataset format '{s}': expected replica or tum"
            )),
        }
    }
}
