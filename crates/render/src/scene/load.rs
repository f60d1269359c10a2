//! `--scene NAME|PATH`: a built-in scene by name, else a mesh file by its extension; a PLY whose
//! vertices carry Gaussian-splat properties is a capture.

use std::path::Path;
use std::sync::Arc;

use rslam_core::mesh_io::read_mesh_bytes;
use rslam_core::splat_io::{is_splat_ply, parse_splat_ply};

use super::{builtin, gltf, obj, ply, Mesh, Scene, BUILTIN_SCENES};
use crate::RenderError;

/// Loads a built-in scene (`room0` … `office4`), a mesh file (.ply, .gltf, .glb, .obj) or a
/// Gaussian-splat capture (.ply).
pub fn load_scene(name_or_path: &str) -> Result<Scene, RenderError> {
    load_scene_scaled(name_or_path, None)
}

/// Like [`load_scene`], a capture's lengths multiplied by `metres_per_unit`; a mesh takes no
/// scale (its units are metres).
pub fn load_scene_scaled(
    name_or_path: &str,
    metres_per_unit: Option<f64>,
) -> Result<Scene, RenderError> {
    if let Some(s) = metres_per_unit.filter(|s| !(s.is_finite() && *s > 0.0)) {
        return Err(RenderError::CaptureScale {
            name: name_or_path.to_string(),
            message: format!("{s}: expected a positive number of metres per unit"),
        });
    }
    let mut scene = load_unscaled(name_or_path)?;
    match (metres_per_unit, scene.splats.take()) {
        (None, splats) => Ok(Scene { splats, ..scene }),
        (Some(factor), Some(cloud)) => Ok(Scene {
            splats: Some(Arc::new(Arc::unwrap_or_clone(cloud).scaled(factor))),
            ..scene
        }),
        (Some(_), None) => Err(RenderError::CaptureScale {
            name: name_or_path.to_string(),
            message: "a scale applies to Gaussian-splat captures only: a mesh is in metres".into(),
        }),
    }
}

fn load_unscaled(name_or_path: &str) -> Result<Scene, RenderError> {
    if let Some(scene) = builtin::build(name_or_path) {
        return Ok(scene);
    }
    let path = Path::new(name_or_path);
    let extension = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let Some(extension) = extension else {
        return Err(RenderError::UnknownScene {
            name: name_or_path.to_string(),
            choices: BUILTIN_SCENES.join(", "),
        });
    };
    if !path.exists() {
        return Err(RenderError::io(
            path,
            std::io::Error::new(std::io::ErrorKind::NotFound, "no such file"),
        ));
    }
    let ply_bytes = (extension == "ply")
        .then(|| read_mesh_bytes(path))
        .transpose()?;
    if let Some(bytes) = ply_bytes.as_deref().filter(|b| is_splat_ply(b)) {
        let cloud =
            parse_splat_ply(bytes).map_err(|message| RenderError::bad_mesh(path, message))?;
        return Ok(Scene {
            name: name_or_path.to_string(),
            mesh: Mesh::default(),
            textures: vec![super::Texture::white()],
            default_trajectory: None,
            lights: None,
            splats: Some(Arc::new(cloud)),
            floor: None,
        });
    }
    let (mesh, textures) = match (extension.as_str(), ply_bytes) {
        (_, Some(bytes)) => (
            ply::mesh_from_ply(path, &bytes)?,
            vec![super::Texture::white()],
        ),
        ("gltf" | "glb", None) => gltf::read_gltf(path)?,
        ("obj", None) => obj::read_obj(path)?,
        _ => {
            return Err(RenderError::UnsupportedFormat {
                path: path.to_path_buf(),
                extension,
            })
        }
    };
    let scene = Scene {
        name: name_or_path.to_string(),
        mesh,
        textures,
        default_trajectory: None,
        splats: None,
        floor: None,
        lights: None,
    };
    if scene.mesh.indices.is_empty() {
        return Err(RenderError::bad_mesh(path, "the file holds no triangles"));
    }
    Ok(scene)
}
