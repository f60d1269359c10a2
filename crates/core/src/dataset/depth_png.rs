use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

/// How a dataset's depth PNGs are compressed. Either way they are standard 16-bit grayscale
/// PNGs holding the same samples (deflate is lossless); `small` spends more encoding time on the
/// worker threads for smaller files (docs/src/performance.md, "Depth PNG encoding").
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DepthPng {
    #[default]
    Fast,
    Small,
}

impl DepthPng {
    pub fn name(self) -> &'static str {
        match self {
            Self::Fast => "fast",
            Self::Small => "small",
        }
    }
}

impl fmt::Display for DepthPng {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for DepthPng {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "fast" => Ok(Self::Fast),
            "small" => Ok(Self::Small),
            _ => Err(format!(
                "unknown depth PNG encoding '{s}': expected fast or small"
            )),
        }
    }
}
