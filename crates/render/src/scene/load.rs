//! `--scene NAME|PATH`: a built-in scene by name, else a mesh file by its extension.

use std::path::Path;

use super::{builtin, gltf, obj, ply, Scene, BUILTIN_SCENES};
use crate::RenderError;

/// Loads a built-in scene (`room0` … `office4`) or a mesh file (.ply, .gltf, .glb, .obj).
pub fn load_scene(name_or_path: &str) -> Result<Scene, RenderError> {
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
    let (mesh, textures) = match extension.as_str() {
        "ply" => (ply::read_ply(path)?, vec![super::Texture::white()]),
        "gltf" | "glb" => gltf::read_gltf(path)?,
        "obj" => obj::read_obj(path)?,
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
        lights: None,
    };
    if scene.mesh.indices.is_empty() {
        return Err(RenderError::bad_mesh(path, "the file holds no triangles"));
    }
    Ok(scene)
}
