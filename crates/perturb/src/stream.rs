//! Stream operations (docs/src/perturbations.md §6) as a frame plan: which source frame each output
//! frame's colour and depth come from.
//!
//! `fast:K` keeps source frames 0, K, 2K, …; the caller re-stamps them at the sensor rate.
//! `misalign:D` then delays depth on that stream: output frame j carries the depth of output
//! frame max(0, j − D_j), with D_j = D, or under `@dynamic` uniform in {D−1, D, D+1}.

use crate::applies::{ItemEntry, Need};
use crate::rng::RngKey;
use crate::spec::PerturbSpec;

pub static STREAM_ITEMS: &[ItemEntry] = &[
    ItemEntry {
        name: "fast",
        syntax: "fast:K",
        description: "keeps frames 0, K, 2K, … re-stamped at the sensor rate: the camera moves K× faster (benchmark: 2, 4, 8)",
        needs: &[Need::Sequence, Need::SpeedUp],
    },
    ItemEntry {
        name: "misalign",
        syntax: "misalign:FRAMES[@dynamic]",
        description: "depth lags colour: RGB frame i pairs with depth frame max(0, i−D); @dynamic: D_i uniform in {D−1, D, D+1} per frame (benchmark: 5, 10, 20)",
        needs: &[Need::Sequence, Need::Depth],
    },
];

const PURPOSE_LAG: u32 = 1;

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StreamPlan {
    /// Per output frame: the source frame of its colour.
    pub rgb_source: Vec<usize>,
    /// Per output frame: the source frame of its depth.
    pub depth_source: Vec<usize>,
    /// Per output frame: the lag D_j drawn, in output frames (before clamping at frame 0).
    pub depth_lag: Vec<u32>,
}

/// The plan for `source_frames` frames.
pub fn plan(source_frames: usize, spec: &PerturbSpec, seed: u64) -> StreamPlan {
    let step = spec.fast.unwrap_or(1).max(1) as usize;
    let rgb_source: Vec<usize> = (0..source_frames).step_by(step).collect();
    let depth_lag: Vec<u32> = (0..rgb_source.len())
        .map(|j| match spec.misalign {
            None => 0,
            Some(m) if !m.dynamic => m.frames,
            Some(m) => {
                let u = RngKey::new(seed, "misalign", j as u32, PURPOSE_LAG).uniform_f64([0; 4]);
                (m.frames + (u * 3.0) as u32).saturating_sub(1)
            }
        })
        .collect();
    let depth_source = depth_lag
        .iter()
        .enumerate()
        .map(|(j, &lag)| rgb_source[j.saturating_sub(lag as usize)])
        .collect();
    StreamPlan {
        rgb_source,
        depth_source,
        depth_lag,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan_for(spec: &str, n: usize) -> StreamPlan {
        plan(n, &PerturbSpec::parse(spec).unwrap(), 9)
    }

    #[test]
    fn fast_keeps_every_kth_frame() {
        let p = plan_for("fast:4", 2000);
        assert_eq!(p.rgb_source.len(), 500);
        assert!(p.rgb_source.iter().enumerate().all(|(j, &s)| s == 4 * j));
        assert_eq!(p.rgb_source, p.depth_source);
    }

    #[test]
    fn misalign_delays_depth_and_clamps_at_the_start() {
        let p = plan_for("misalign:10", 30);
        assert_eq!(p.rgb_source, (0..30).collect::<Vec<_>>());
        for j in 0..30 {
            assert_eq!(p.depth_source[j], j.saturating_sub(10));
        }
    }

    #[test]
    fn dynamic_misalign_stays_within_one_frame_and_uses_all_three_lags() {
        let p = plan_for("misalign:10@dynamic", 2000);
        let mut counts = [0usize; 3];
        for &lag in &p.depth_lag {
            assert!((9..=11).contains(&lag));
            counts[(lag - 9) as usize] += 1;
        }
        for c in counts {
            assert!((c as f64 / 2000.0 - 1.0 / 3.0).abs() < 0.05, "{counts:?}");
        }
    }

    #[test]
    fn misalign_acts_on_the_fast_stream() {
        let p = plan_for("fast:2,misalign:3", 20);
        assert_eq!(p.rgb_source[5], 10);
        assert_eq!(p.depth_source[5], 4);
    }
}
