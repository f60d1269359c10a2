//! The console table of a multi-agent evaluation: one row per agent, then the joint row, then the
//! joint alignment.

use std::fmt::Write as _;

use super::evaluate::MultiAgentEvaluation;
use crate::text_report::{alignment_line, write_alignment};

const JOINT: &str = "joint";
/// Width of a numeric column (values with 6 decimals, right-aligned).
const NUMBER_WIDTH: usize = 12;

pub fn multi_agent_report(e: &MultiAgentEvaluation) -> String {
    let mut out = String::new();
    let name_width = e
        .agents
        .iter()
        .map(|a| a.name.chars().count())
        .chain(["agent".len(), JOINT.len()])
        .max()
        .unwrap_or(JOINT.len());
    // Writing to a String cannot fail.
    let _ = writeln!(
        out,
        "{} agents, {} pairs {}\n\
         ATE = RMSE of |p_est - p_gt| (m), SSE = sum of squared errors (m^2)\n\
         own: each agent aligned on its own; joint: one alignment fitted over all agents' pairs\n",
        e.agents.len(),
        e.joint.pairs,
        alignment_line(e.align)
    );
    let w = NUMBER_WIDTH;
    let _ = writeln!(
        out,
        "{:<name_width$}  {:>8}  {:>w$}  {:>w$}  {:>w$}  {:>w$}",
        "agent", "pairs", "ATE own", "SSE own", "ATE joint", "SSE joint"
    );
    for a in &e.agents {
        let _ = writeln!(
            out,
            "{:<name_width$}  {:>8}  {:>w$.6}  {:>w$.6}  {:>w$.6}  {:>w$.6}",
            a.name, a.pairs, a.ate.rmse, a.ate.sse, a.ate_joint.rmse, a.ate_joint.sse
        );
    }
    let _ = writeln!(
        out,
        "{JOINT:<name_width$}  {:>8}  {:>w$}  {:>w$}  {:>w$.6}  {:>w$.6}\n",
        e.joint.pairs, "-", "-", e.joint.ate.rmse, e.joint.ate.sse
    );
    let _ = writeln!(out, "joint alignment (p_gt = scale * R * p_est + t)");
    write_alignment(&mut out, &e.joint.alignment);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::alignment::{AlignMode, Similarity};
    use crate::multi_agent::{AgentEvaluation, JointEvaluation};
    use crate::statistics::ErrorStatistics;

    #[test]
    fn one_row_per_agent_and_a_joint_row() {
        let stats = |errors: &[f64]| ErrorStatistics::of(errors).unwrap();
        let e = MultiAgentEvaluation {
            align: AlignMode::Se3,
            agents: vec![
                AgentEvaluation {
                    name: "drone_long_name".to_string(),
                    pairs: 2,
                    max_pairs: 2,
                    ate: stats(&[0.0, 0.0]),
                    alignment: Similarity::IDENTITY,
                    ate_joint: stats(&[0.5, 0.5]),
                },
                AgentEvaluation {
                    name: "b".to_string(),
                    pairs: 1,
                    max_pairs: 3,
                    ate: stats(&[0.0]),
                    alignment: Similarity::IDENTITY,
                    ate_joint: stats(&[1.0]),
                },
            ],
            joint: JointEvaluation {
                pairs: 3,
                ate: stats(&[0.5, 0.5, 1.0]),
                alignment: Similarity::IDENTITY,
            },
        };
        let text = multi_agent_report(&e);
        let table: Vec<&str> = text.lines().skip(4).take(4).collect();
        assert_eq!(
            table,
            [
                "agent               pairs       ATE own       SSE own     ATE joint     SSE joint",
                "drone_long_name         2      0.000000      0.000000      0.500000      0.500000",
                "b                       1      0.000000      0.000000      1.000000      1.000000",
                "joint                   3             -             -      0.707107      1.500000",
            ],
            "{text}"
        );
        assert!(text.starts_with("2 agents, 3 pairs (with SE(3) Umeyama alignment)\n"));
        assert!(text.contains("joint alignment (p_gt = scale * R * p_est + t)\n          R\t"));
    }
}
