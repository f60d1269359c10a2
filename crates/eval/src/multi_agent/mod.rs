//! Several agents' estimates, each with its ground truth, all in one world frame (a multi-agent
//! SLAM system such as COVINS-G, whose agents share one map): ATE and SSE per agent and jointly.
//!
//! Each agent's poses are associated with its own ground truth exactly as for one estimate
//! ([`crate::associate`]). Then:
//!
//! - **own alignment**: each agent aligned on its own (Umeyama, the chosen [`crate::AlignMode`]),
//!   as if it were evaluated alone;
//! - **joint alignment**: ONE alignment of the same mode fitted over every agent's associated
//!   pairs stacked together and applied to every agent, as a multi-agent system is judged. Agents
//!   that are each right but disagree with one another (an agent whose map is offset from the
//!   others) show in the joint ATE, not in their own.
//!
//! **SSE** (sum of squared errors, m²) = Σ ‖p_est_aligned − p_gt‖² over the associated pairs after
//! alignment: per agent (own and joint alignment) and over all agents' pairs (joint). It is
//! n · RMSE² for n pairs; unlike the RMSE it adds up over agents.
//!
//! Data flow: [`agents_from_pairs`] (repeated `EST GT` pairs) or [`agents_in_folder`]
//! (`DIR/<agent>/estimate.txt` and `traj.txt` or `groundtruth.txt`) → [`read_and_evaluate_agents`]
//! → [`evaluate_agents`] → [`MultiAgentEvaluation`], shown by [`multi_agent_report`], serialised
//! as JSON.

mod evaluate;
mod files;
mod report;

pub use evaluate::{
    evaluate_agents, Agent, AgentEvaluation, JointEvaluation, MultiAgentEvaluation,
};
pub use files::{
    agents_from_pairs, agents_in_folder, read_and_evaluate_agents, AgentFiles, AGENT_ESTIMATE_FILE,
};
pub use report::multi_agent_report;
