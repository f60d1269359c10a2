//! Embedded WGSL with one small include resolver: a line `#include "common/rng.wgsl"` is replaced
//! by that file (once per shader, recursively). Paths are relative to `shaders/`.

use crate::GpuError;

include!(concat!(env!("OUT_DIR"), "/embedded_shaders.rs"));

/// Every embedded shader path, sorted.
pub fn paths() -> impl Iterator<Item = &'static str> {
    EMBEDDED_SHADERS.iter().map(|(path, _)| *path)
}

fn raw(path: &str) -> Option<&'static str> {
    EMBEDDED_SHADERS
        .iter()
        .find(|(p, _)| *p == path)
        .map(|(_, text)| *text)
}

/// The shader's source with includes resolved.
pub fn source(path: &str) -> Result<String, GpuError> {
    resolve(path, &|p| raw(p).map(str::to_string))
}

/// Resolves includes of `path` through `lookup`; shared by the runtime and the naga test.
pub fn resolve(path: &str, lookup: &dyn Fn(&str) -> Option<String>) -> Result<String, GpuError> {
    let mut out = String::new();
    let mut seen = Vec::new();
    append(path, lookup, &mut seen, &mut out)?;
    Ok(out)
}

fn append(
    path: &str,
    lookup: &dyn Fn(&str) -> Option<String>,
    seen: &mut Vec<String>,
    out: &mut String,
) -> Result<(), GpuError> {
    if seen.iter().any(|s| s == path) {
        return Ok(());
    }
    seen.push(path.to_string());
    let text = lookup(path).ok_or_else(|| GpuError::Shader {
        path: path.to_string(),
        message: "no such shader under shaders/".into(),
    })?;
    for (i, line) in text.lines().enumerate() {
        match line.trim().strip_prefix("#include") {
            Some(rest) => {
                let target = rest.trim().trim_matches('"');
                if target.is_empty() {
                    return Err(GpuError::Shader {
                        path: path.to_string(),
                        message: format!("line {}: expected #include \"file.wgsl\"", i + 1),
                    });
                }
                append(target, lookup, seen, out)?;
            }
            None => {
                out.push_str(line);
                out.push('\n');
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn includes_are_inlined_once_and_missing_ones_named() {
        let files = |p: &str| match p {
            "a.wgsl" => Some("#include \"c.wgsl\"\n#include \"b.wgsl\"\nfn a() {}".to_string()),
            "b.wgsl" => Some("#include \"c.wgsl\"\nfn b() {}".to_string()),
            "c.wgsl" => Some("fn c() {}".to_string()),
            "bad.wgsl" => Some("#include \"nope.wgsl\"".to_string()),
            _ => None,
        };
        let text = resolve("a.wgsl", &files).unwrap();
        assert_eq!(text, "fn c() {}\nfn b() {}\nfn a() {}\n");
        let err = resolve("bad.wgsl", &files).unwrap_err().to_string();
        assert!(err.contains("nope.wgsl"), "{err}");
    }
}
