//! ATE over the frames where much of the view moves (`rslam eval --dynamic-above F`), as
//! dynamic-SLAM papers report it: the estimate aligned over all frames as usual, the errors of the
//! frames whose dynamic fraction (the share of pixels people cover, from the instance masks of
//! the ground truth's dataset, `extra.masks` in its `rslam.json`) exceeds F.

use std::path::Path;

use rslam_core::dataset::Manifest;
use rslam_core::CoreError;
use serde::Serialize;

use crate::{ErrorStatistics, EvalError, Evaluation};

/// The ATE of the dynamic frames; serialised as `dynamic_ate` in `rslam eval --json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DynamicAte {
    /// Frames count as dynamic above this fraction of moving pixels.
    pub threshold: f64,
    /// Ground-truth frames above it, of all.
    pub dynamic_frames: usize,
    pub frames: usize,
    /// The ATE of the associated pairs on dynamic frames (the alignment is the one fitted over
    /// every pair); `None` when no estimate pose lies on a dynamic frame.
    pub ate: Option<ErrorStatistics>,
}

/// The dataset folder a ground truth `gt` belongs to: the folder of a file, a bag folder itself.
pub fn dataset_of(gt: &Path) -> &Path {
    match gt.is_dir() {
        true => gt,
        false => gt.parent().unwrap_or(Path::new(".")),
    }
}

/// Each output frame's dynamic fraction from the manifest of the one-camera dataset in `folder`
/// (one per output frame, as its ground truth has one pose per output frame).
pub fn read_dynamic_fractions(folder: &Path) -> Result<Vec<f64>, EvalError> {
    let manifest = Manifest::read(folder)?;
    let listed = &manifest.extra["masks"]["dynamic_fraction"];
    let not_listed = || {
        CoreError::bad_file(
            folder.join(rslam_core::dataset::MANIFEST_FILE),
            "extra.masks.dynamic_fraction: expected one fraction per frame of a one-camera \
             dataset rendered with actors",
        )
    };
    let fractions = listed.as_array().ok_or_else(not_listed)?;
    (fractions.iter())
        .map(|f| f.as_f64().ok_or_else(not_listed))
        .collect::<Result<_, _>>()
        .map_err(EvalError::from)
}

/// The ATE of `evaluation`'s pairs on ground-truth frames whose fraction in `fractions` (one per
/// ground-truth pose) exceeds `threshold`.
pub fn dynamic_ate(
    evaluation: &Evaluation,
    fractions: &[f64],
    threshold: f64,
) -> Result<DynamicAte, EvalError> {
    let frames = evaluation.series.gt_positions.len();
    if fractions.len() != frames {
        return Err(EvalError::BadOption {
            name: "dynamic fractions",
            value: format!("{} for {frames} ground-truth poses", fractions.len()),
            expected: "one per ground-truth pose (the dataset's own ground truth)",
        });
    }
    if !(0.0..1.0).contains(&threshold) {
        return Err(EvalError::BadOption {
            name: "--dynamic-above",
            value: threshold.to_string(),
            expected: "a fraction of the frame from 0 up to 1",
        });
    }
    let series = &evaluation.series;
    let errors: Vec<f64> = (series.pair_gt_indices.iter().zip(&series.ate_errors))
        .filter(|(&gt, _)| fractions[gt] > threshold)
        .map(|(_, &error)| error)
        .collect();
    Ok(DynamicAte {
        threshold,
        dynamic_frames: fractions.iter().filter(|&&f| f > threshold).count(),
        frames,
        ate: ErrorStatistics::of(&errors),
    })
}

#[cfg(test)]
mod tests {
    use glam::{DQuat, DVec3};
    use rslam_core::{Pose, Trajectory};

    use super::dynamic_ate;
    use crate::{evaluate, EvalOptions};

    /// A square path; the estimate is off by 0.1 m along x on frames 10–19 only: under SE(3)
    /// alignment over all frames, the dynamic frames carry the error and the others little.
    #[test]
    fn the_dynamic_frames_errors_under_the_alignment_of_all_frames() {
        let n = 40;
        let at = |i: usize| {
            let a = i as f64 / n as f64 * std::f64::consts::TAU;
            Pose::new(DQuat::IDENTITY, DVec3::new(a.cos(), a.sin(), 0.1 * a))
        };
        let times: Vec<f64> = (0..n).map(|i| i as f64 * 0.05).collect();
        let gt = Trajectory::new(times.clone(), (0..n).map(at).collect());
        let off = |i: usize| {
            let p = at(i);
            match i {
                10..20 => Pose::new(p.rotation, p.translation + DVec3::X * 0.1),
                _ => p,
            }
        };
        let est = Trajectory::new(times, (0..n).map(off).collect());
        let evaluation = evaluate(&est, &gt, &EvalOptions::default()).unwrap();
        let fractions: Vec<f64> = (0..n)
            .map(|i| if (10..20).contains(&i) { 0.3 } else { 0.01 })
            .collect();
        let dynamic = dynamic_ate(&evaluation, &fractions, 0.1).unwrap();
        assert_eq!((dynamic.dynamic_frames, dynamic.frames), (10, 40));
        let ate = dynamic.ate.unwrap();
        assert_eq!(ate.n, 10);
        let others: Vec<f64> = fractions.iter().map(|f| 0.31 - f).collect();
        let still = dynamic_ate(&evaluation, &others, 0.1).unwrap().ate.unwrap();
        assert_eq!(still.n, 30);
        assert!(ate.rmse > 2.0 * still.rmse, "{ate:?} vs {still:?}");
        let quiet = dynamic_ate(&evaluation, &fractions, 0.5).unwrap();
        assert_eq!((quiet.dynamic_frames, quiet.ate), (0, None));
        assert!(dynamic_ate(&evaluation, &fractions[1..], 0.1).is_err());
        assert!(dynamic_ate(&evaluation, &fractions, 1.0).is_err());
    }
}
