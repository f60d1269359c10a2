//! The console report of one evaluation, laid out like evo's (statistics sorted by name, the name
//! right-aligned to 10 characters, a tab, the value with 6 decimals).

use std::fmt::Write as _;

use crate::alignment::{AlignMode, Similarity};
use crate::association::Matching;
use crate::statistics::ErrorStatistics;
use crate::Evaluation;

pub fn text_report(e: &Evaluation) -> String {
    let mut out = String::new();
    let alignment_line = alignment_line(e.options.align);
    let matching = match e.options.matching {
        Matching::Time { max_diff, t_offset } => {
            format!("nearest timestamp within {max_diff} s, t-offset {t_offset} s")
        }
        Matching::Index => "matched by index: a file has no timestamps".to_string(),
    };
    let rpe = &e.options.rpe;
    let rpe_title = format!(
        "for delta = {} ({}) using {} pairs\n{alignment_line}",
        rpe.delta,
        rpe.delta_unit.long_name(),
        if rpe.all_pairs { "all" } else { "consecutive" }
    );
    // Writing to a String cannot fail.
    let _ = writeln!(
        out,
        "pairs\t{} of max. {} ({matching})\n",
        e.pairs, e.max_pairs
    );
    section(
        &mut out,
        &format!("APE w.r.t. translation part (m)\n{alignment_line}"),
        &e.ate,
    );
    section(
        &mut out,
        &format!("RPE w.r.t. translation part (m)\n{rpe_title}"),
        &e.rpe_trans,
    );
    section(
        &mut out,
        &format!("RPE w.r.t. rotation angle in degrees (deg)\n{rpe_title}"),
        &e.rpe_rot_deg,
    );
    let s = &e.success_rate;
    let lengths = &s.path_length;
    let ratio = |v: Option<f64>| {
        v.map_or_else(
            || "n/a (the ground truth does not move)".to_string(),
            |v| format!("{v:.6}"),
        )
    };
    let _ = writeln!(
        out,
        "SR (success rate of tracking)\t{}\n  = covered ground-truth path {:.6} m / ground-truth \
         path {:.6} m\n    (segments between consecutive ground-truth poses both paired with an \
         estimate pose)",
        ratio(s.sr),
        lengths.covered,
        lengths.ground_truth
    );
    let _ = writeln!(
        out,
        "tracked fraction\t{:.6}\n  = {} of {} ground-truth poses paired with an estimate pose",
        s.tracked_fraction, s.tracked_poses, s.ground_truth_poses
    );
    let _ = writeln!(
        out,
        "SR path ratio (the paper's SR formula; grows with jitter, not a success rate)\t{}\n  \
         = estimate path {:.6} m{} / ground-truth path {:.6} m\n",
        ratio(s.sr_path_ratio),
        lengths.estimate,
        if e.options.align == AlignMode::Sim3 {
            " (Sim(3)-scaled)"
        } else {
            ""
        },
        lengths.ground_truth
    );
    let _ = writeln!(out, "alignment (p_gt = scale * R * p_est + t)");
    write_alignment(&mut out, &e.alignment);
    out
}

/// evo's line under a title saying how the estimate was aligned.
pub(crate) fn alignment_line(mode: AlignMode) -> &'static str {
    match mode {
        AlignMode::Se3 => "(with SE(3) Umeyama alignment)",
        AlignMode::Sim3 => "(with Sim(3) Umeyama alignment)",
        AlignMode::None => "(not aligned)",
    }
}

/// The rows of R, t and the scale, values right-aligned after a tab.
pub(crate) fn write_alignment(out: &mut String, a: &Similarity) {
    for (i, row) in a.rotation.transpose().to_cols_array_2d().iter().enumerate() {
        let label = if i == 0 { "R" } else { "" };
        let _ = writeln!(
            out,
            "{label:>11}\t{:>10.6} {:>10.6} {:>10.6}",
            row[0], row[1], row[2]
        );
    }
    let t = a.translation;
    let _ = writeln!(
        out,
        "{:>11}\t{:>10.6} {:>10.6} {:>10.6}",
        "t", t.x, t.y, t.z
    );
    let _ = writeln!(out, "{:>11}\t{:.9}", "scale", a.scale);
}

fn section(out: &mut String, title: &str, s: &ErrorStatistics) {
    let _ = writeln!(out, "{title}\n({} values)\n", s.n);
    for (name, value) in [
        ("max", s.max),
        ("mean", s.mean),
        ("median", s.median),
        ("min", s.min),
        ("rmse", s.rmse),
        ("sse", s.sse),
        ("std", s.std),
    ] {
        let _ = writeln!(out, "{name:>10}\t{value:.6}");
    }
    out.push('\n');
}
