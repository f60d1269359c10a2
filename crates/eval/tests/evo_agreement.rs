//! rslam-eval against evo 1.38.1 on a synthetic fixture (tests/fixtures, made once by a script:
//! a 100 Hz helix ground truth with a 0.25 s gap, and a ~30 Hz estimate with jittered stamps, in
//! another frame at scale 0.5, noisy, with non-unit quaternions and irregular whitespace).
//! Expected values computed once with evo's Python API (`sync.associate_trajectories`,
//! `PosePath3D.align`, `metrics.APE` / `metrics.RPE`), numpy 2.4.6, scipy 1.17.1.

use std::path::PathBuf;

use rslam_core::trajectory_io::ReadOptions;
use rslam_eval::{
    read_and_evaluate, AlignMode, DeltaUnit, ErrorStatistics, EvalOptions, Matching, RpeOptions,
};

/// Relative agreement required with evo; observed differences are ~1e-12 (SVD, summation order).
const REL_TOL: f64 = 1e-9;
/// evo's `path_length` of the whole files.
const EST_PATH: f64 = 2.8058753068908473;
const GT_PATH: f64 = 5.316469647839908;

struct Expected {
    n: usize,
    rmse: f64,
    mean: f64,
    median: f64,
    std: f64,
    min: f64,
    max: f64,
    sse: f64,
}

struct Case {
    name: &'static str,
    align: AlignMode,
    max_diff: f64,
    t_offset: f64,
    rpe: RpeOptions,
    pairs: usize,
    scale: f64,
    ate: Expected,
    rpe_trans: Expected,
    rpe_rot_deg: Expected,
}

fn fixture(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(name)
}

fn assert_close(case: &str, what: &str, got: f64, want: f64) {
    let rel = (got - want).abs() / want.abs().max(f64::MIN_POSITIVE);
    assert!(
        rel <= REL_TOL,
        "{case} {what}: rslam {got} vs evo {want} (relative {rel:.1e})"
    );
}

fn assert_stats(case: &str, what: &str, got: &ErrorStatistics, want: &Expected) {
    assert_eq!(got.n, want.n, "{case} {what}: count");
    for (stat, g, w) in [
        ("rmse", got.rmse, want.rmse),
        ("mean", got.mean, want.mean),
        ("median", got.median, want.median),
        ("std", got.std, want.std),
        ("min", got.min, want.min),
        ("max", got.max, want.max),
        ("sse", got.sse, want.sse),
    ] {
        assert_close(case, &format!("{what} {stat}"), g, w);
    }
}

fn rpe(delta: f64, delta_unit: DeltaUnit, all_pairs: bool) -> RpeOptions {
    RpeOptions {
        delta,
        delta_unit,
        all_pairs,
    }
}

#[test]
fn synthetic_fixture_matches_evo() {
    let cases = [
        Case {
            name: "se3_frames",
            align: AlignMode::Se3,
            max_diff: 0.01,
            t_offset: 0.0,
            rpe: rpe(1.0, DeltaUnit::Frames, false),
            pairs: 83,
            scale: 1.0,
            ate: Expected {
                n: 83,
                rmse: 0.6420861803806412,
                mean: 0.6143537465987343,
                median: 0.6395413406635857,
                std: 0.18666584335624878,
                min: 0.33187405408484744,
                max: 0.9666934285498224,
                sse: 34.21879703197151,
            },
            rpe_trans: Expected {
                n: 82,
                rmse: 0.04427004495769036,
                mean: 0.03430217471368013,
                median: 0.03255527243156542,
                std: 0.02798566937680943,
                min: 0.008283106916891422,
                max: 0.26864365856899425,
                sse: 0.1607066242055859,
            },
            rpe_rot_deg: Expected {
                n: 82,
                rmse: 1.378544855873066,
                mean: 1.2844427025090002,
                median: 1.2958934059702638,
                std: 0.5005925125543408,
                min: 0.30217102728674883,
                max: 2.8133431823841595,
                sse: 155.83164541163558,
            },
        },
        Case {
            name: "sim3_frames",
            align: AlignMode::Sim3,
            max_diff: 0.01,
            t_offset: 0.0,
            rpe: rpe(1.0, DeltaUnit::Frames, false),
            pairs: 83,
            scale: 1.9978283607464498,
            ate: Expected {
                n: 83,
                rmse: 0.018333360458153338,
                mean: 0.017050703731938666,
                median: 0.01598221173477102,
                std: 0.006736884141369305,
                min: 0.0030629615777959447,
                max: 0.03306207734036925,
                sse: 0.027897304772152173,
            },
            rpe_trans: Expected {
                n: 82,
                rmse: 0.02693973621962009,
                mean: 0.02564284486720837,
                median: 0.02563204549482263,
                std: 0.00825795947549974,
                min: 0.008123149523830805,
                max: 0.04904745977178727,
                sse: 0.05951144978178225,
            },
            rpe_rot_deg: Expected {
                n: 82,
                rmse: 1.378544855873066,
                mean: 1.2844427025090002,
                median: 1.2958934059702638,
                std: 0.5005925125543408,
                min: 0.30217102728674883,
                max: 2.8133431823841595,
                sse: 155.83164541163558,
            },
        },
        Case {
            name: "none_frames",
            align: AlignMode::None,
            max_diff: 0.01,
            t_offset: 0.0,
            rpe: rpe(1.0, DeltaUnit::Frames, false),
            pairs: 83,
            scale: 1.0,
            ate: Expected {
                n: 83,
                rmse: 2.937133368024359,
                mean: 2.7847498920992018,
                median: 3.1890863265682317,
                std: 0.9337668124406626,
                min: 1.150819157070703,
                max: 3.7222400801716624,
                sse: 716.0204509896555,
            },
            rpe_trans: Expected {
                n: 82,
                rmse: 0.04427004495769037,
                mean: 0.03430217471368014,
                median: 0.03255527243156582,
                std: 0.02798566937680944,
                min: 0.008283106916891542,
                max: 0.26864365856899436,
                sse: 0.16070662420558599,
            },
            rpe_rot_deg: Expected {
                n: 82,
                rmse: 1.378544855873066,
                mean: 1.2844427025090002,
                median: 1.295893405970264,
                std: 0.5005925125543409,
                min: 0.30217102728674855,
                max: 2.813343182384162,
                sse: 155.83164541163555,
            },
        },
        Case {
            name: "sim3_metres_all",
            align: AlignMode::Sim3,
            max_diff: 0.01,
            t_offset: 0.0,
            rpe: rpe(0.2, DeltaUnit::Meters, true),
            pairs: 83,
            scale: 1.9978283607464498,
            ate: Expected {
                n: 83,
                rmse: 0.018333360458153338,
                mean: 0.017050703731938666,
                median: 0.01598221173477102,
                std: 0.006736884141369305,
                min: 0.0030629615777959447,
                max: 0.03306207734036925,
                sse: 0.027897304772152173,
            },
            rpe_trans: Expected {
                n: 46,
                rmse: 0.025826588797013668,
                mean: 0.023465362479177448,
                median: 0.02536211638177603,
                std: 0.010788394348133718,
                min: 0.003390083295724482,
                max: 0.04963028246347982,
                sse: 0.03068258368894147,
            },
            rpe_rot_deg: Expected {
                n: 46,
                rmse: 1.3397566581595677,
                mean: 1.2515020504383414,
                median: 1.315443768795351,
                std: 0.47821597718135705,
                min: 0.20187181877546115,
                max: 2.372917580074803,
                sse: 82.56760354181307,
            },
        },
        Case {
            name: "se3_degrees",
            align: AlignMode::Se3,
            max_diff: 0.01,
            t_offset: 0.0,
            rpe: rpe(10.0, DeltaUnit::Degrees, false),
            pairs: 83,
            scale: 1.0,
            ate: Expected {
                n: 83,
                rmse: 0.6420861803806412,
                mean: 0.6143537465987343,
                median: 0.6395413406635857,
                std: 0.18666584335624878,
                min: 0.33187405408484744,
                max: 0.9666934285498224,
                sse: 34.21879703197151,
            },
            rpe_trans: Expected {
                n: 16,
                rmse: 0.1737848890312324,
                mean: 0.16473205653686687,
                median: 0.15335671258814404,
                std: 0.05535826229870534,
                min: 0.11301486674967258,
                max: 0.35878178294569213,
                sse: 0.4832190024895642,
            },
            rpe_rot_deg: Expected {
                n: 16,
                rmse: 1.2791534254324233,
                mean: 1.1590547532820252,
                median: 1.036358455687739,
                std: 0.5411335922762932,
                min: 0.3230350385653254,
                max: 2.292019172106058,
                sse: 26.179735772728034,
            },
        },
        Case {
            name: "se3_offset",
            align: AlignMode::Se3,
            max_diff: 0.004,
            t_offset: 0.003,
            rpe: rpe(3.0, DeltaUnit::Frames, true),
            pairs: 59,
            scale: 1.0,
            ate: Expected {
                n: 59,
                rmse: 0.6416164454377657,
                mean: 0.6172854986862728,
                median: 0.6436034791973655,
                std: 0.1750150741160117,
                min: 0.3444918433530998,
                max: 0.9689384406371369,
                sse: 24.288628120315412,
            },
            rpe_trans: Expected {
                n: 56,
                rmse: 0.15072581338376972,
                mean: 0.13398095482614072,
                median: 0.11117919181083727,
                std: 0.06904617704170607,
                min: 0.06252069577756739,
                max: 0.3588434563883503,
                sse: 1.272223165931143,
            },
            rpe_rot_deg: Expected {
                n: 56,
                rmse: 1.301606438585786,
                mean: 1.2166323050977448,
                median: 1.2267631600258837,
                std: 0.46258529501111645,
                min: 0.2296894360972415,
                max: 2.340860654407557,
                sse: 94.87404197420652,
            },
        },
    ];
    for case in &cases {
        let options = EvalOptions {
            matching: Matching::Time {
                max_diff: case.max_diff,
                t_offset: case.t_offset,
            },
            align: case.align,
            rpe: case.rpe,
        };
        let e = read_and_evaluate(
            &fixture("synthetic_est.txt"),
            &fixture("synthetic_gt.txt"),
            &ReadOptions::default(),
            &options,
        )
        .unwrap_or_else(|err| panic!("{}: {err}", case.name));
        assert_eq!(e.pairs, case.pairs, "{}: pairs", case.name);
        assert_close(case.name, "scale", e.alignment.scale, case.scale);
        assert_stats(case.name, "ATE", &e.ate, &case.ate);
        assert_stats(case.name, "RPE trans", &e.rpe_trans, &case.rpe_trans);
        assert_stats(case.name, "RPE rot", &e.rpe_rot_deg, &case.rpe_rot_deg);
        let lengths = &e.success_rate.path_length;
        assert_close(case.name, "GT path", lengths.ground_truth, GT_PATH);
        assert_close(
            case.name,
            "SR path ratio",
            e.success_rate.sr_path_ratio.unwrap(),
            EST_PATH * case.scale / GT_PATH,
        );
    }
}
