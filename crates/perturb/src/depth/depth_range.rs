//! depth_range: depth outside the valid range [min, max] becomes invalid, like a sensor's
//! working range. Severity levels from docs/src/perturbations.md §4, or explicit `depth_range:MIN-MAX`.

use rslam_core::DepthImage;

use super::depth_pass::DepthPointwise;
use crate::image::color_pass::KeyedParams;
use crate::perturbation::{Between, CatalogueEntry, ExplicitForm, FrameKey, Group};
use crate::twin::{Tolerance, Twin};

const SHADER: &str = "perturb/depth/depth_range.wgsl";

/// Valid range in metres per severity (docs/src/perturbations.md §4, the Robust-SLAM benchmark).
pub const RANGE: [(f32, f32); 5] = [(0.2, 4.4), (0.3, 4.2), (0.4, 4.0), (0.5, 3.8), (0.6, 3.6)];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: "depth_range",
    group: Group::Depth,
    description:
        "voids depth outside [min, max] metres (a sensor's working range); also depth_range:MIN-MAX",
    parameters: |s| {
        let (min, max) = RANGE[s as usize - 1];
        format!("[{min}, {max}] m")
    },
    build: |kit| DepthPointwise::boxed(kit, SHADER, |_, key| params(key)),
    between: Between::Interpolated("MIN linear from 0, MAX linear in 1/MAX from no limit"),
    explicit: Some(ExplicitForm {
        syntax: "MIN-MAX in metres, e.g. depth_range:0.42-10",
        example: "0.42-10",
        parse: parse_range,
        format: |v| format!("{}-{}", v[0], v[1]),
    }),
    twin: Twin::Depth(twin),
    // The same f32 comparisons on both sides.
    twin_tolerance: Tolerance::EXACT,
    uniforms: &[KeyedParams::layout(SHADER)],
};

/// `MIN-MAX` with 0 ≤ MIN < MAX, finite.
pub fn parse_range(text: &str) -> Result<Vec<f64>, String> {
    let bad = || format!("'{text}' is not a range MIN-MAX");
    let (min, max) = text.split_once('-').ok_or_else(bad)?;
    let min: f64 = min.trim().parse().map_err(|_| bad())?;
    let max: f64 = max.trim().parse().map_err(|_| bad())?;
    if !(min.is_finite() && max.is_finite() && 0.0 <= min && min < max) {
        return Err(format!("range '{text}' needs 0 ≤ MIN < MAX"));
    }
    Ok(vec![min, max])
}

/// The range this frame uses: the explicit one, or the severity's (the minimum linear from 0,
/// the maximum linear in 1/max from no limit at severity 0).
pub fn range(key: &FrameKey) -> (f32, f32) {
    match key.explicit {
        Some([min, max, ..]) => (*min as f32, *max as f32),
        _ => {
            let min = key.interpolate(0.0, &RANGE.map(|(min, _)| min));
            let max = key.interpolate_in(0.0, &RANGE.map(|(_, max)| max), |m| 1.0 / m, |r| 1.0 / r);
            (min as f32, max as f32)
        }
    }
}

fn params(key: &FrameKey) -> KeyedParams {
    let (min, max) = range(key);
    KeyedParams {
        key: [0; 4],
        values: [min, max, 0.0, 0.0],
    }
}

/// CPU twin of `depth_range.wgsl`.
pub fn twin(depth: &DepthImage, key: &FrameKey) -> DepthImage {
    let (min, max) = range(key);
    let mut out = depth.clone();
    for z in &mut out.data {
        if *z < min || *z > max {
            *z = 0.0;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn depth_outside_the_explicit_range_is_voided() {
        let depth = DepthImage {
            width: 5,
            height: 1,
            data: vec![0.0, 1.4, 1.5, 3.0, 3.1],
        };
        let values = [1.5, 3.0];
        let key = FrameKey {
            explicit: Some(&values),
            ..testing::key(0, 5)
        };
        assert_eq!(twin(&depth, &key).data, [0.0, 0.0, 1.5, 3.0, 0.0]);
        // Severity 1 keeps [0.2, 4.4] m.
        assert_eq!(twin(&depth, &testing::key(0, 1)), depth);
    }

    #[test]
    fn explicit_ranges_parse_and_reject_nonsense() {
        assert_eq!(parse_range("0.42-10"), Ok(vec![0.42, 10.0]));
        for bad in ["", "3", "a-b", "5-1", "-1-3", "1-inf"] {
            assert!(parse_range(bad).is_err(), "{bad}");
        }
    }
}
