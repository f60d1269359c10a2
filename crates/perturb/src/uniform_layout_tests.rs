//! Every parameter struct the catalogue's passes write into a uniform block has the size and
//! member offsets of the WGSL struct it binds to, as naga lays that out (WGSL §13.4 memory
//! layout); and every struct-typed buffer of a perturbation shader has such a Rust struct.

use std::path::PathBuf;

use naga::{AddressSpace, TypeInner};

use crate::uniform_layout::UniformLayout;
use crate::CATALOGUE;

/// The catalogue's uniform structs and the sensor effects' one.
fn all_layouts() -> Vec<&'static UniformLayout> {
    CATALOGUE
        .iter()
        .flat_map(|e| e.uniforms)
        .chain([&crate::sensor::UNIFORMS])
        .collect()
}

/// A shader with its includes resolved, parsed by naga.
fn parse(shader: &str) -> Result<naga::Module, String> {
    let source = rslam_gpu::shader::source(shader).map_err(|e| e.to_string())?;
    naga::front::wgsl::parse_str(&source).map_err(|e| e.emit_to_string(&source))
}

/// What differs between `layout`'s Rust struct and its WGSL struct.
fn differences(layout: &UniformLayout) -> Vec<String> {
    let what = format!(
        "{} / `{}` of {}",
        layout.rust.name, layout.wgsl, layout.shader
    );
    let module = match parse(layout.shader) {
        Ok(module) => module,
        Err(e) => return vec![format!("{what}: {e}")],
    };
    let mut layouter = naga::proc::Layouter::default();
    if let Err(e) = layouter.update(module.to_ctx()) {
        return vec![format!("{what}: {e}")];
    }
    let wgsl = module
        .types
        .iter()
        .find(|(_, ty)| ty.name.as_deref() == Some(layout.wgsl));
    let Some((
        _,
        naga::Type {
            inner: TypeInner::Struct { members, span },
            ..
        },
    )) = wgsl
    else {
        return vec![format!("{what}: no such WGSL struct")];
    };
    let mut out = Vec::new();
    if *span as usize != layout.rust.size {
        out.push(format!(
            "{what}: {} bytes in Rust, {span} in WGSL",
            layout.rust.size
        ));
    }
    for field in layout.rust.fields {
        let Some(member) = members
            .iter()
            .find(|m| m.name.as_deref() == Some(field.name))
        else {
            out.push(format!("{what}: no WGSL member `{}`", field.name));
            continue;
        };
        let size = layouter[member.ty].size as usize;
        if (member.offset as usize, size) != (field.offset, field.size) {
            out.push(format!(
                "{what}: `{}` at byte {} ({} bytes) in Rust, {} ({size} bytes) in WGSL",
                field.name, field.offset, field.size, member.offset
            ));
        }
    }
    for member in members {
        let name = member.name.as_deref().unwrap_or_default();
        if !name.starts_with('_') && layout.rust.fields.iter().all(|f| f.name != name) {
            out.push(format!(
                "{what}: WGSL member `{name}` is not in the Rust layout"
            ));
        }
    }
    out
}

#[test]
fn every_uniform_struct_matches_its_wgsl_layout() {
    let layouts = all_layouts();
    assert!(!layouts.is_empty(), "the catalogue lists no uniform struct");
    let failures: Vec<String> = layouts.iter().flat_map(|l| differences(l)).collect();
    assert!(
        failures.is_empty(),
        "{} differences in {} uniform structs:\n{}",
        failures.len(),
        layouts.len(),
        failures.join("\n")
    );
}

/// Shaders that other shaders `#include` (fragments such as `pointwise_runs.wgsl` use what
/// their includer defines, so they are checked as part of it).
fn included() -> Vec<String> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shaders");
    rslam_gpu::shader::paths()
        .filter_map(|path| std::fs::read_to_string(root.join(path)).ok())
        .flat_map(|text| {
            text.lines()
                .filter_map(|line| line.trim().strip_prefix("#include"))
                .map(|rest| rest.trim().trim_matches('"').to_string())
                .collect::<Vec<_>>()
        })
        .collect()
}

/// A new pass cannot forget its layout: every uniform or storage buffer of struct type (or
/// array of structs) in a perturbation shader must be listed by some catalogue entry.
#[test]
fn every_struct_buffer_of_a_perturbation_shader_is_listed() {
    let layouts = all_layouts();
    let included = included();
    let shaders: Vec<&str> = rslam_gpu::shader::paths()
        .filter(|path| path.starts_with("perturb/") && !included.iter().any(|i| i == path))
        .collect();
    assert!(!shaders.is_empty(), "no perturbation shader found");
    let mut missing = Vec::new();
    for shader in &shaders {
        let module = match parse(shader) {
            Ok(module) => module,
            Err(e) => {
                missing.push(format!("{shader}: {e}"));
                continue;
            }
        };
        for (_, global) in module.global_variables.iter() {
            if !matches!(
                global.space,
                AddressSpace::Uniform | AddressSpace::Storage { .. }
            ) {
                continue;
            }
            let ty = match module.types[global.ty].inner {
                TypeInner::Array { base, .. } => base,
                _ => global.ty,
            };
            let (TypeInner::Struct { .. }, Some(name)) =
                (&module.types[ty].inner, &module.types[ty].name)
            else {
                continue;
            };
            let listed = layouts
                .iter()
                .any(|l| l.shader == *shader && l.wgsl == name.as_str());
            if !listed {
                missing.push(format!(
                    "{shader}: `{name}` (binding of `{}`) has no Rust layout in the catalogue",
                    global.name.as_deref().unwrap_or_default()
                ));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "{} buffers in {} shaders are not listed:\n{}",
        missing.len(),
        shaders.len(),
        missing.join("\n")
    );
}
