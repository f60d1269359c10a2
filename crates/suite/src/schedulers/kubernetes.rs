//! `rslam suite k8s`: a Kubernetes Indexed Job, pod i making shard i of N
//! (`suite run` reads `JOB_COMPLETION_INDEX`; `--shard-count` gives N). The suite folder lives on
//! a PersistentVolumeClaim every pod mounts; an ephemeral bench makes its frames in the pod's
//! `emptyDir`. Written as JSON, which `kubectl apply -f` reads
//! like YAML.

use std::path::{Path, PathBuf};

use serde_json::json;

use super::TaskOptions;
use crate::SuiteError;

pub const KUBERNETES_DIR: &str = "k8s";
const MANIFEST_FILE: &str = "suite-job.json";
/// Where an ephemeral pod's node-local scratch (an `emptyDir`) is mounted.
const SCRATCH_MOUNT: &str = "/scratch";

#[derive(Clone, Debug)]
pub struct KubernetesOptions {
    pub tasks: usize,
    /// Pods at once; `None`: all.
    pub parallelism: Option<usize>,
    /// Container image with `rslam` on its PATH.
    pub image: String,
    /// The PersistentVolumeClaim that holds the suite folder.
    pub claim: String,
    /// Where the claim is mounted: the suite folder inside the pods.
    pub mount: String,
    /// GPUs per pod (`nvidia.com/gpu`); 0: none.
    pub gpus: usize,
    pub task: TaskOptions,
}

/// Writes `<suite>/k8s/suite-job.json`; returns its path.
pub fn write_kubernetes_job(
    suite_dir: &Path,
    options: &KubernetesOptions,
) -> Result<PathBuf, SuiteError> {
    if options.tasks == 0 {
        return Err(SuiteError::option(
            "--tasks",
            "0: expected at least one task",
        ));
    }
    if options.image.is_empty() {
        return Err(SuiteError::option(
            "--image",
            "empty: expected a container image with rslam",
        ));
    }
    let dir = suite_dir.join(KUBERNETES_DIR);
    std::fs::create_dir_all(&dir).map_err(|e| SuiteError::io(&dir, e))?;
    let path = dir.join(MANIFEST_FILE);
    let text =
        serde_json::to_string_pretty(&job(options)).map_err(|e| SuiteError::io(&path, e.into()))?;
    std::fs::write(&path, text + "\n").map_err(|e| SuiteError::io(&path, e))?;
    Ok(path)
}

fn job(options: &KubernetesOptions) -> serde_json::Value {
    let mut command = vec![
        "rslam".to_string(),
        "suite".into(),
        options.task.subcommand().into(),
        options.mount.clone(),
        "--shard-count".into(),
        options.tasks.to_string(),
    ];
    let mut task = options.task.clone();
    let mut mounts = vec![json!({ "name": "suite", "mountPath": options.mount })];
    let mut volumes = vec![json!({
        "name": "suite",
        "persistentVolumeClaim": { "claimName": options.claim },
    })];
    // Ephemeral frames go to the pod's node-local emptyDir unless told otherwise.
    if let Some(ephemeral) = task.ephemeral.as_mut().filter(|e| e.scratch.is_none()) {
        ephemeral.scratch = Some(SCRATCH_MOUNT.into());
        mounts.push(json!({ "name": "scratch", "mountPath": SCRATCH_MOUNT }));
        volumes.push(json!({ "name": "scratch", "emptyDir": {} }));
    }
    command.extend(task.run_arguments());
    let mut container = json!({
        "name": "rslam",
        "image": options.image,
        "command": command,
        "volumeMounts": mounts,
    });
    if options.gpus > 0 {
        container["resources"] = json!({ "limits": { "nvidia.com/gpu": options.gpus } });
    }
    json!({
        "apiVersion": "batch/v1",
        "kind": "Job",
        "metadata": { "name": "rslam-suite" },
        "spec": {
            "completionMode": "Indexed",
            "completions": options.tasks,
            "parallelism": options.parallelism.unwrap_or(options.tasks),
            // A pod that fails is retried in place; its shard resumes where it stopped.
            "backoffLimit": 3 * options.tasks,
            "template": {
                "spec": {
                    "restartPolicy": "OnFailure",
                    "containers": [container],
                    "volumes": volumes,
                },
            },
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_ephemeral_pod_makes_its_frames_in_its_empty_dir() {
        let options = KubernetesOptions {
            tasks: 2,
            parallelism: None,
            image: "rslam".into(),
            claim: "suite".into(),
            mount: "/suite".into(),
            gpus: 1,
            task: TaskOptions {
                jobs: 1,
                adapter: None,
                ephemeral: Some(super::super::EphemeralTask {
                    methods: vec!["/suite/methods/orb.toml".into()],
                    scratch: None,
                    search: None,
                }),
            },
        };
        let job = job(&options);
        let pod = &job["spec"]["template"]["spec"];
        let command = pod["containers"][0]["command"].to_string();
        assert!(
            command.contains(r#""suite","bench","/suite","--shard-count","2","--ephemeral","--methods","/suite/methods/orb.toml","--scratch","/scratch""#),
            "{command}"
        );
        assert_eq!(
            pod["volumes"][1],
            json!({ "name": "scratch", "emptyDir": {} })
        );
        assert_eq!(
            pod["containers"][0]["volumeMounts"][1]["mountPath"],
            "/scratch"
        );
    }

    #[test]
    fn the_job_is_indexed_with_one_shard_per_completion() {
        let dir = tempfile::tempdir().unwrap();
        let options = KubernetesOptions {
            tasks: 16,
            parallelism: Some(4),
            image: "ghcr.io/lab/rslam:1".into(),
            claim: "datasets".into(),
            mount: "/suite".into(),
            gpus: 1,
            task: TaskOptions {
                jobs: 2,
                adapter: None,
                ephemeral: None,
            },
        };
        let path = write_kubernetes_job(dir.path(), &options).unwrap();
        let job: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        let spec = &job["spec"];
        assert_eq!(spec["completionMode"], "Indexed");
        assert_eq!(
            (spec["completions"].as_u64(), spec["parallelism"].as_u64()),
            (Some(16), Some(4))
        );
        let container = &spec["template"]["spec"]["containers"][0];
        let command: Vec<&str> = container["command"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_str().unwrap())
            .collect();
        assert_eq!(
            command,
            [
                "rslam",
                "suite",
                "run",
                "/suite",
                "--shard-count",
                "16",
                "--jobs",
                "2"
            ]
        );
        assert_eq!(container["resources"]["limits"]["nvidia.com/gpu"], 1);
        assert_eq!(
            spec["template"]["spec"]["volumes"][0]["persistentVolumeClaim"]["claimName"],
            "datasets"
        );
    }
}
