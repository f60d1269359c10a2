//! N agents in one built-in scene, each walking a path of its own
//! ([`rslam_render::agent_trajectory`]) in the scene's world frame, each written as a complete
//! dataset of its own in `OUT/agent<k>` — the folder of agents a multi-agent evaluation reads. Agent
//! k draws its perturbations with seed `seed + k`, so agent 0 is exactly what `rslam render`
//! writes without agents.

use std::path::{Path, PathBuf};

use rslam_core::CoreError;

use crate::{JobPart, PipelineError, SceneJob};

/// The scene job of agent `agent` of a multi-agent render of `scene`.
pub fn agent_scene_job(scene: &SceneJob, agent: usize) -> SceneJob {
    SceneJob {
        seed: scene.seed.wrapping_add(agent as u64),
        agent: Some(agent),
        ..scene.clone()
    }
}

/// The folders of `count` agents in `out`, which is new or holds nothing but agent folders (each
/// is then prepared, resumed or refused like any output folder).
pub fn agent_folders(out: &Path, count: usize) -> Result<Vec<PathBuf>, PipelineError> {
    if count == 0 {
        return Err(PipelineError::option(
            JobPart::Agents,
            "0: expected at least one agent",
        ));
    }
    if !out.exists() {
        return Ok(folders(out, count));
    }
    for entry in std::fs::read_dir(out).map_err(|e| CoreError::io(out, e))? {
        let entry = entry.map_err(|e| CoreError::io(out, e))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let is_dir = entry
            .file_type()
            .map_err(|e| CoreError::io(out, e))?
            .is_dir();
        if !(is_dir && agent_number(&name).is_some()) {
            return Err(PipelineError::output(
                out,
                format!(
                    "holds '{}', which is no agent folder (agent0, agent1, …); choose an empty or new folder",
                    rslam_core::printable(&name)
                ),
            ));
        }
    }
    Ok(folders(out, count))
}

fn folders(out: &Path, count: usize) -> Vec<PathBuf> {
    (0..count).map(|k| out.join(format!("agent{k}"))).collect()
}

/// Adds the agent's number to a manifest's `extra` part when `scene` is one agent of several.
pub(crate) fn record_agent(extra: &mut serde_json::Value, scene: &SceneJob) {
    if let Some(agent) = scene.agent {
        extra["agent"] = agent.into();
    }
}

fn agent_number(name: &str) -> Option<usize> {
    let digits = name.strip_prefix("agent")?;
    let canonical = !digits.is_empty() && (digits == "0" || !digits.starts_with('0'));
    canonical.then(|| digits.parse().ok()).flatten()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn agent_folders_are_numbered_and_nothing_else_may_be_there() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("agents");
        let folders = agent_folders(&out, 3).unwrap();
        assert_eq!(folders, [0, 1, 2].map(|k| out.join(format!("agent{k}"))));
        std::fs::create_dir_all(out.join("agent1")).unwrap();
        assert!(agent_folders(&out, 2).is_ok());
        std::fs::write(out.join("notes.txt"), "x").unwrap();
        let err = agent_folders(&out, 2).unwrap_err().to_string();
        assert!(
            err.contains("'notes.txt', which is no agent folder"),
            "{err}"
        );
        assert!(agent_folders(&dir.path().join("b"), 0)
            .unwrap_err()
            .to_string()
            .contains("agents: 0: expected at least one agent"));
        assert_eq!(agent_number("agent12"), Some(12));
        assert_eq!(agent_number("agent012"), None);
        assert_eq!(agent_number("agent"), None);
    }
}
