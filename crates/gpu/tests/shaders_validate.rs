//! Walks `shaders/`, resolves includes with the runtime resolver and validates every file with
//! naga; all failures are reported at once. A file that other shaders `#include` is validated as
//! part of them (a fragment such as `pointwise_runs.wgsl` calls what its includer defines).

use std::path::{Path, PathBuf};

fn wgsl_files(dir: &Path, root: &Path, out: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).expect("read shaders/") {
        let path = entry.expect("dir entry").path();
        if path.is_dir() {
            wgsl_files(&path, root, out);
        } else if path.extension().is_some_and(|e| e == "wgsl") {
            let rel = path.strip_prefix(root).expect("under shaders/");
            out.push(rel.to_string_lossy().replace('\\', "/"));
        }
    }
}

fn validate(source: &str) -> Result<(), String> {
    let module = naga::front::wgsl::parse_str(source).map_err(|e| e.emit_to_string(source))?;
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::default(),
    )
    .validate(&module)
    .map_err(|e| e.emit_to_string(source))?;
    Ok(())
}

#[test]
fn every_shader_parses_and_validates() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shaders");
    let mut files = Vec::new();
    wgsl_files(&root, &root, &mut files);
    files.sort();
    assert!(
        !files.is_empty(),
        "no shader found under {}",
        root.display()
    );

    let embedded: Vec<&str> = rslam_gpu::shader::paths().collect();
    let lookup = |p: &str| std::fs::read_to_string(root.join(p)).ok();
    let included: Vec<String> = files
        .iter()
        .filter_map(|f| lookup(f))
        .flat_map(|source| {
            source
                .lines()
                .filter_map(|line| line.trim().strip_prefix("#include"))
                .map(|rest| rest.trim().trim_matches('"').to_string())
                .collect::<Vec<_>>()
        })
        .collect();
    let mut failures = Vec::new();
    for file in files.iter().filter(|f| !included.contains(f)) {
        if !embedded.contains(&file.as_str()) {
            failures.push(format!(
                "{file}: on disk but not embedded (rebuild rslam-gpu)"
            ));
            continue;
        }
        let result = rslam_gpu::shader::resolve(file, &lookup)
            .map_err(|e| e.to_string())
            .and_then(|source| validate(&source));
        if let Err(message) = result {
            failures.push(format!("{file}:\n{message}"));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} shaders failed:\n{}",
        failures.len(),
        files.len(),
        failures.join("\n\n")
    );
}
