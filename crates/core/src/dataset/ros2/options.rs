//! How a bag rslam makes is written, beyond its layout: the depth encoding, ground truth on
//! `/tf` too, and the MCAP chunks' compression. The defaults are what a bag without options
//! holds; a manifest records only options that differ from them.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct BagOptions {
    #[serde(default, skip_serializing_if = "is_default")]
    pub depth: BagDepth,
    /// The ground truth also as `world → body` transforms on `/tf`, for tools that follow the
    /// TF tree (rviz, rtabmap's `odom_frame_id` checks).
    #[serde(default, skip_serializing_if = "is_default")]
    pub tf: bool,
    #[serde(default, skip_serializing_if = "is_default")]
    pub compression: BagCompression,
}

impl BagOptions {
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }
}

fn is_default<T: Default + PartialEq>(value: &T) -> bool {
    *value == T::default()
}

/// The depth image's encoding.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum BagDepth {
    /// `16UC1`, millimetres, 0 = no measurement: REP 118's raw form, what depth drivers publish.
    #[default]
    #[serde(rename = "16UC1")]
    Millimetres,
    /// `32FC1`, metres, NaN = no measurement: REP 118's preferred form, the depth as rendered.
    #[serde(rename = "32FC1")]
    Metres,
}

impl BagDepth {
    pub fn encoding(self) -> &'static str {
        match self {
            Self::Millimetres => "16UC1",
            Self::Metres => "32FC1",
        }
    }
}

impl fmt::Display for BagDepth {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.encoding())
    }
}

impl FromStr for BagDepth {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "16UC1" => Ok(Self::Millimetres),
            "32FC1" => Ok(Self::Metres),
            _ => Err(format!(
                "unknown bag depth encoding '{s}': expected 16UC1 or 32FC1"
            )),
        }
    }
}

/// How the MCAP chunks are compressed. `ros2 bag play` (the MCAP storage plugin) reads each.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BagCompression {
    /// Raw chunks: the fastest to write and to play.
    #[default]
    None,
    /// zstd chunks, what `ros2 bag record` writes with `--storage-preset-profile zstd_fast`.
    Zstd,
    Lz4,
}

impl BagCompression {
    pub fn name(self) -> &'static str {
        match self {
            Self::None => "none",
            Self::Zstd => "zstd",
            Self::Lz4 => "lz4",
        }
    }

    pub(super) fn mcap(self) -> Option<mcap::Compression> {
        match self {
            Self::None => None,
            Self::Zstd => Some(mcap::Compression::Zstd),
            Self::Lz4 => Some(mcap::Compression::Lz4),
        }
    }
}

impl fmt::Display for BagCompression {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for BagCompression {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "none" => Ok(Self::None),
            "zstd" => Ok(Self::Zstd),
            "lz4" => Ok(Self::Lz4),
            _ => Err(format!(
                "unknown bag compression '{s}': expected none, zstd or lz4"
            )),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_options_serialise_to_nothing_and_others_by_their_ros_names() {
        assert_eq!(
            serde_json::to_value(BagOptions::default()).unwrap(),
            serde_json::json!({})
        );
        let options = BagOptions {
            depth: BagDepth::Metres,
            tf: true,
            compression: BagCompression::Zstd,
        };
        let value = serde_json::to_value(options).unwrap();
        assert_eq!(
            value,
            serde_json::json!({"depth": "32FC1", "tf": true, "compression": "zstd"})
        );
        assert_eq!(
            serde_json::from_value::<BagOptions>(value).unwrap(),
            options
        );
    }

    #[test]
    fn names_parse_back() {
        for depth in [BagDepth::Millimetres, BagDepth::Metres] {
            assert_eq!(depth.to_string().parse::<BagDepth>(), Ok(depth));
        }
        for compression in [
            BagCompression::None,
            BagCompression::Zstd,
            BagCompression::Lz4,
        ] {
            assert_eq!(compression.to_string().parse(), Ok(compression));
        }
        assert!("16uc1"
            .parse::<BagDepth>()
            .unwrap_err()
            .contains("16UC1 or 32FC1"));
    }
}
