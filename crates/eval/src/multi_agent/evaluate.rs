//! Per-agent and joint ATE / SSE of agents sharing one world frame.

use glam::DVec3;
use rslam_core::Trajectory;
use serde::Serialize;

use crate::alignment::{fit_alignment, AlignMode, Similarity};
use crate::association::{associate, Matching};
use crate::statistics::ErrorStatistics;
use crate::EvalError;

/// One agent: its estimate and its ground truth, both in the common world frame.
#[derive(Clone, Debug, PartialEq)]
pub struct Agent {
    /// Shown in the report and named in errors.
    pub name: String,
    pub estimate: Trajectory,
    pub ground_truth: Trajectory,
    /// How this agent's poses are paired (by index when one of its files has no timestamps).
    pub matching: Matching,
}

/// One agent's errors; `ate.sse` and `ate_joint.sse` are its SSE (m²).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct AgentEvaluation {
    pub name: String,
    /// Associated pose pairs.
    pub pairs: usize,
    /// The most pairs there could be (poses of the shorter trajectory).
    pub max_pairs: usize,
    /// ATE (m) after this agent's own alignment.
    pub ate: ErrorStatistics,
    /// This agent's own alignment.
    pub alignment: Similarity,
    /// ATE (m) of this agent under the joint alignment.
    pub ate_joint: ErrorStatistics,
}

/// Every agent's pairs together under the one joint alignment.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct JointEvaluation {
    /// Pairs of all agents.
    pub pairs: usize,
    /// ATE (m) over all pairs; `ate.sse` is the joint SSE (m²).
    pub ate: ErrorStatistics,
    /// The one alignment fitted over all pairs and applied to every agent.
    pub alignment: Similarity,
}

/// The result of [`evaluate_agents`]; serialises to the `rslam eval --agent/--agents --json`
/// object.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MultiAgentEvaluation {
    pub align: AlignMode,
    pub agents: Vec<AgentEvaluation>,
    pub joint: JointEvaluation,
}

/// One agent's associated positions.
struct Pairs {
    est: Vec<DVec3>,
    gt: Vec<DVec3>,
    max_pairs: usize,
}

/// Evaluates every agent on its own and all together under one alignment of mode `align`.
/// Errors (named after the agent): no associated pair, a degenerate own alignment; a degenerate
/// joint alignment; no agent at all.
pub fn evaluate_agents(
    agents: &[Agent],
    align: AlignMode,
) -> Result<MultiAgentEvaluation, EvalError> {
    if agents.is_empty() {
        return Err(EvalError::BadOption {
            name: "agents",
            value: "none".to_string(),
            expected: "at least one agent (an estimate with its ground truth)",
        });
    }
    let in_agent = |agent: &Agent| {
        let name = agent.name.clone();
        move |error| EvalError::Agent {
            agent: name,
            error: Box::new(error),
        }
    };
    let pairs = agents
        .iter()
        .map(|agent| associated_positions(agent).map_err(in_agent(agent)))
        .collect::<Result<Vec<_>, _>>()?;
    let own = agents
        .iter()
        .zip(&pairs)
        .map(|(agent, p)| fit_alignment(align, &p.est, &p.gt).map_err(in_agent(agent)))
        .collect::<Result<Vec<_>, _>>()?;

    // The joint alignment: the same Umeyama fit over every agent's pairs stacked.
    let all_est: Vec<DVec3> = pairs.iter().flat_map(|p| p.est.iter().copied()).collect();
    let all_gt: Vec<DVec3> = pairs.iter().flat_map(|p| p.gt.iter().copied()).collect();
    let joint_alignment = fit_alignment(align, &all_est, &all_gt)?;

    let stats = |errors: &[f64]| ErrorStatistics::of(errors).expect("association is non-empty");
    let mut all_joint_errors = Vec::with_capacity(all_est.len());
    let evaluations = agents
        .iter()
        .zip(&pairs)
        .zip(own)
        .map(|((agent, p), alignment)| {
            let joint_errors = position_errors(&joint_alignment, p);
            all_joint_errors.extend_from_slice(&joint_errors);
            AgentEvaluation {
                name: agent.name.clone(),
                pairs: p.est.len(),
                max_pairs: p.max_pairs,
                ate: stats(&position_errors(&alignment, p)),
                alignment,
                ate_joint: stats(&joint_errors),
            }
        })
        .collect();
    Ok(MultiAgentEvaluation {
        align,
        agents: evaluations,
        joint: JointEvaluation {
            pairs: all_est.len(),
            ate: stats(&all_joint_errors),
            alignment: joint_alignment,
        },
    })
}

fn associated_positions(agent: &Agent) -> Result<Pairs, EvalError> {
    let association = associate(&agent.estimate, &agent.ground_truth, &agent.matching)?;
    let positions = |t: &Trajectory, indices: &[usize]| -> Vec<DVec3> {
        indices.iter().map(|&i| t.poses[i].translation).collect()
    };
    Ok(Pairs {
        est: positions(&agent.estimate, &association.est_indices),
        gt: positions(&agent.ground_truth, &association.gt_indices),
        max_pairs: association.max_pairs,
    })
}

/// ‖alignment(p_est) − p_gt‖ per pair.
fn position_errors(alignment: &Similarity, pairs: &Pairs) -> Vec<f64> {
    pairs
        .est
        .iter()
        .zip(&pairs.gt)
        .map(|(e, g)| (alignment.apply(*e) - *g).length())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_support::{random_quat, TestRng};
    use glam::{DMat3, DQuat};
    use rslam_core::Pose;

    /// Tolerance on errors that are exactly zero or a hand-computed value (noise-free input).
    const EXACT_TOL: f64 = 1e-9;

    /// A wavy loop of `n` positions (one whole turn); `phase` and `radius` make agents differ.
    fn loop_positions(n: usize, radius: f64, phase: f64) -> Vec<DVec3> {
        (0..n)
            .map(|i| {
                let a = phase + std::f64::consts::TAU * i as f64 / n as f64;
                DVec3::new(
                    radius * a.cos(),
                    0.7 * radius * a.sin(),
                    0.3 * (3.0 * a).sin(),
                )
            })
            .collect()
    }

    fn trajectory(positions: &[DVec3], orientations: &[DQuat]) -> Trajectory {
        Trajectory::new(
            (0..positions.len()).map(|i| i as f64 / 30.0).collect(),
            positions
                .iter()
                .zip(orientations)
                .map(|(p, q)| Pose::new(*q, *p))
                .collect(),
        )
    }

    /// An agent whose estimate is its ground truth mapped by `to_estimate`.
    fn agent(name: &str, gt: &[DVec3], mut to_estimate: impl FnMut(DVec3) -> DVec3) -> Agent {
        let mut rng = TestRng::new(name.len() as u64);
        let orientations: Vec<DQuat> = gt.iter().map(|_| random_quat(&mut rng)).collect();
        let est: Vec<DVec3> = gt.iter().map(|p| to_estimate(*p)).collect();
        Agent {
            name: name.to_string(),
            estimate: trajectory(&est, &orientations),
            ground_truth: trajectory(gt, &orientations),
            matching: Matching::default(),
        }
    }

    /// Ground truth of agent b, moved so that its centroid is that of `a`: with equal
    /// centroids the joint SE(3) fit under a pure offset of one agent has R = I (the
    /// cross-covariance stays the symmetric covariance of the ground truth) and only splits the
    /// offset, which makes the expected errors hand-computable.
    fn recentred(b: Vec<DVec3>, a: &[DVec3]) -> Vec<DVec3> {
        let centroid = |p: &[DVec3]| p.iter().copied().sum::<DVec3>() / p.len() as f64;
        let shift = centroid(a) - centroid(&b);
        b.into_iter().map(|p| p + shift).collect()
    }

    fn common() -> Similarity {
        let mut rng = TestRng::new(42);
        Similarity {
            rotation: DMat3::from_quat(random_quat(&mut rng)),
            translation: DVec3::new(3.0, -1.0, 0.5),
            scale: 1.0,
        }
    }

    fn assert_sse_is_n_rmse_squared(s: &ErrorStatistics) {
        let expected = s.n as f64 * s.rmse * s.rmse;
        assert!(
            (s.sse - expected).abs() < EXACT_TOL * (1.0 + expected),
            "sse {} vs n·rmse² {expected}",
            s.sse
        );
    }

    fn assert_all_sse(e: &MultiAgentEvaluation) {
        assert_sse_is_n_rmse_squared(&e.joint.ate);
        for a in &e.agents {
            assert_sse_is_n_rmse_squared(&a.ate);
            assert_sse_is_n_rmse_squared(&a.ate_joint);
        }
        let summed: f64 = e.agents.iter().map(|a| a.ate_joint.sse).sum();
        assert!((e.joint.ate.sse - summed).abs() < EXACT_TOL * (1.0 + summed));
    }

    #[test]
    fn agents_moved_by_one_rigid_transform_have_zero_joint_and_own_ate() {
        let t = common();
        let gts = [
            loop_positions(60, 2.0, 0.0),
            loop_positions(45, 3.0, 1.0),
            loop_positions(80, 1.0, 2.0),
        ];
        let agents: Vec<Agent> = gts
            .iter()
            .enumerate()
            .map(|(i, gt)| agent(&format!("agent{i}"), gt, |p| t.apply(p)))
            .collect();
        let e = evaluate_agents(&agents, AlignMode::Se3).unwrap();
        assert!(e.joint.ate.rmse < EXACT_TOL, "joint {}", e.joint.ate.rmse);
        assert_eq!(e.joint.pairs, 60 + 45 + 80);
        for a in &e.agents {
            assert!(a.ate.rmse < EXACT_TOL, "{} own {}", a.name, a.ate.rmse);
            assert!(a.ate_joint.rmse < EXACT_TOL, "{} joint", a.name);
        }
        assert_all_sse(&e);
    }

    #[test]
    fn one_shifted_agent_shows_in_the_joint_ate_not_in_its_own() {
        // Two agents, equal pose counts and centroids; b's estimate also shifted by d. The joint
        // SE(3) fit puts half the shift on each: every pair is off by |d|/2.
        let t = common();
        let d = DVec3::new(0.3, -0.4, 1.2); // |d| = 1.3
        let gt_a = loop_positions(50, 2.0, 0.0);
        let gt_b = recentred(loop_positions(50, 1.5, 0.7), &gt_a);
        let agents = [
            agent("a", &gt_a, |p| t.apply(p)),
            agent("b", &gt_b, |p| t.apply(p) + d),
        ];
        let e = evaluate_agents(&agents, AlignMode::Se3).unwrap();
        for a in &e.agents {
            assert!(a.ate.rmse < EXACT_TOL, "{} own ATE {}", a.name, a.ate.rmse);
            assert!((a.ate_joint.rmse - 0.65).abs() < EXACT_TOL, "{}", a.name);
            assert!((a.ate_joint.sse - 50.0 * 0.65 * 0.65).abs() < EXACT_TOL);
        }
        assert!((e.joint.ate.rmse - 0.65).abs() < EXACT_TOL);
        assert!((e.joint.ate.sse - 100.0 * 0.65 * 0.65).abs() < EXACT_TOL);
        assert_all_sse(&e);
    }

    #[test]
    fn the_joint_fit_leaves_more_of_the_shift_on_the_smaller_agent() {
        // 150 poses of a, 50 of shifted b (weight w = 1/4): the joint translation moves b back
        // by 3|d|/4, so a is off by |d|/4 and b by 3|d|/4; joint RMSE² = (150/16 + 50·9/16)/200
        // · |d|² = 3|d|²/16.
        let t = common();
        let d = DVec3::new(0.0, 2.0, 0.0);
        let gt_a = loop_positions(150, 2.0, 0.0);
        let gt_b = recentred(loop_positions(50, 1.0, 0.3), &gt_a);
        let agents = [
            agent("a", &gt_a, |p| t.apply(p)),
            agent("b", &gt_b, |p| t.apply(p) + d),
        ];
        let e = evaluate_agents(&agents, AlignMode::Se3).unwrap();
        assert!(e.agents[1].ate.rmse < EXACT_TOL, "b on its own is exact");
        assert!((e.agents[0].ate_joint.rmse - 0.5).abs() < EXACT_TOL);
        assert!((e.agents[1].ate_joint.rmse - 1.5).abs() < EXACT_TOL);
        let expected = (3.0_f64 / 16.0).sqrt() * 2.0;
        assert!((e.joint.ate.rmse - expected).abs() < EXACT_TOL);
        assert_all_sse(&e);
    }

    #[test]
    fn sim3_with_a_common_scale_gives_zero_and_finds_the_scale() {
        let t = Similarity {
            scale: 0.25,
            ..common()
        };
        let agents = [
            agent("a", &loop_positions(40, 2.0, 0.0), |p| t.apply(p)),
            agent("b", &loop_positions(70, 4.0, 1.3), |p| t.apply(p)),
        ];
        let e = evaluate_agents(&agents, AlignMode::Sim3).unwrap();
        assert!(e.joint.ate.rmse < EXACT_TOL);
        assert!((e.joint.alignment.scale - 4.0).abs() < EXACT_TOL);
        for a in &e.agents {
            assert!(a.ate.rmse < EXACT_TOL && a.ate_joint.rmse < EXACT_TOL);
            assert!((a.alignment.scale - 4.0).abs() < EXACT_TOL);
        }
        assert_all_sse(&e);
        // Under SE(3) the scale is an error the joint fit cannot remove.
        let rigid = evaluate_agents(&agents, AlignMode::Se3).unwrap();
        assert!(rigid.joint.ate.rmse > 0.1);
    }

    #[test]
    fn one_agent_alone_matches_the_single_estimate_evaluation() {
        let mut rng = TestRng::new(9);
        let gt = loop_positions(90, 2.0, 0.0);
        let a = agent("solo", &gt, |p| {
            p + crate::test_support::noise(&mut rng, 0.05)
        });
        let e = evaluate_agents(std::slice::from_ref(&a), AlignMode::Se3).unwrap();
        let single = crate::evaluate(&a.estimate, &a.ground_truth, &Default::default()).unwrap();
        assert!((e.agents[0].ate.rmse - single.ate.rmse).abs() < 1e-15);
        assert!((e.joint.ate.rmse - single.ate.rmse).abs() < 1e-15);
        assert_eq!(e.joint.alignment, single.alignment);
    }

    #[test]
    fn an_agent_without_pairs_is_named() {
        let gt = loop_positions(30, 2.0, 0.0);
        let mut late = agent("late", &gt, |p| p);
        late.estimate
            .timestamps
            .iter_mut()
            .for_each(|t| *t += 100.0);
        let agents = [agent("ok", &gt, |p| p), late];
        let err = evaluate_agents(&agents, AlignMode::Se3).unwrap_err();
        assert!(
            err.to_string()
                .starts_with("agent late: no matching timestamps"),
            "{err}"
        );
        let err = evaluate_agents(&[], AlignMode::Se3).unwrap_err();
        assert!(err.to_string().contains("at least one agent"), "{err}");
    }

    #[test]
    fn json_has_agents_and_the_joint_object() {
        let gt = loop_positions(30, 2.0, 0.0);
        let e = evaluate_agents(&[agent("a", &gt, |p| p)], AlignMode::Sim3).unwrap();
        let json = serde_json::to_value(&e).unwrap();
        assert_eq!(json["align"], "sim3");
        assert_eq!(json["agents"][0]["name"], "a");
        for key in ["ate", "ate_joint"] {
            assert!(json["agents"][0][key]["sse"].is_number(), "{key}");
        }
        assert_eq!(json["joint"]["pairs"], 30);
        assert!(json["joint"]["alignment"]["scale"].is_number());
    }
}
