//! Wavefront OBJ + MTL reader (tobj): polygons triangulated, colour = material Kd (as sRGB) ×
//! vertex colour × `map_Kd` texture (PNG or JPEG, path relative to the OBJ file). OBJ's v axis
//! points up, ours down, so v is flipped.

use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

use rslam_core::limits::{MAX_MESH_TRIANGLES, MAX_MESH_VERTICES};
use rslam_core::mesh_io::read_mesh_bytes;
use rslam_core::printable;

use super::{Mesh, Texture, Vertex};
use crate::RenderError;

mod face_indices;

/// Reads the triangles, colours and diffuse textures of an .obj file and its .mtl.
pub fn read_obj(path: &Path) -> Result<(Mesh, Vec<Texture>), RenderError> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ..Default::default()
    };
    let dir = path.parent().unwrap_or(Path::new("."));
    let bytes = read_mesh_bytes(path)?;
    face_indices::check_face_indices(path, &String::from_utf8_lossy(&bytes))?;
    let library = RefCell::new(PathBuf::new());
    let (models, materials) = tobj::load_obj_buf(&mut bytes.as_slice(), &options, |mtl| {
        library.replace(dir.join(mtl));
        load_mtl(&library.borrow())
    })
    .map_err(|e| RenderError::bad_mesh(path, format!("cannot parse OBJ: {e}")))?;
    let materials = materials.map_err(|e| {
        RenderError::bad_mesh(
            path,
            format!(
                "cannot read its material library {}: {e}",
                printable(&library.borrow().display().to_string())
            ),
        )
    })?;
    check_geometry(path, &models)?;
    let mut textures = vec![Texture::white()];
    let mut layer_of_file: HashMap<PathBuf, u32> = HashMap::new();
    let mut material_layers = Vec::with_capacity(materials.len());
    for m in &materials {
        let layer = match &m.diffuse_texture {
            Some(file) => {
                let full = dir.join(file);
                match layer_of_file.get(&full) {
                    Some(&layer) => layer,
                    None => {
                        textures.push(load_texture(path, &full)?);
                        let layer = textures.len() as u32 - 1;
                        layer_of_file.insert(full, layer);
                        layer
                    }
                }
            }
            None => 0,
        };
        material_layers.push(layer);
    }
    let mut mesh = Mesh::default();
    for model in &models {
        let m = &model.mesh;
        let material = m
            .material_id
            .and_then(|i| materials.get(i).map(|mat| (mat, material_layers[i])));
        let kd = material
            .and_then(|(mat, _)| mat.diffuse)
            .unwrap_or([1.0; 3]);
        let layer = material.map_or(0, |(_, layer)| layer);
        let base = mesh.vertices.len() as u32;
        for i in 0..m.positions.len() / 3 {
            let vc = |k: usize| m.vertex_color.get(3 * i + k).copied().unwrap_or(1.0);
            let rgb: [u8; 3] =
                std::array::from_fn(|k| ((kd[k] * vc(k)).clamp(0.0, 1.0) * 255.0).round() as u8);
            let uv = match (m.texcoords.get(2 * i), m.texcoords.get(2 * i + 1)) {
                (Some(&u), Some(&v)) => [u, 1.0 - v],
                _ => [0.0; 2],
            };
            mesh.vertices.push(Vertex {
                position: [
                    m.positions[3 * i],
                    m.positions[3 * i + 1],
                    m.positions[3 * i + 2],
                ],
                uv,
                color: [rgb[0], rgb[1], rgb[2], 255],
                layer,
            });
        }
        mesh.indices.extend(m.indices.iter().map(|i| base + i));
    }
    Ok((mesh, textures))
}

/// A material library as tobj reads it, less the lines tobj 4.0.5 panics on (`parse_float3`
/// unwraps): a colour (`Ka`, `Kd`, `Ks`, `Ke`) with fewer than three numbers is refused first.
fn load_mtl(path: &Path) -> tobj::MTLLoadResult {
    let bytes = std::fs::read(path).map_err(|_| tobj::LoadError::OpenFileFailed)?;
    let short_colour = String::from_utf8_lossy(&bytes).lines().any(|line| {
        let mut words = line.split_whitespace();
        matches!(words.next(), Some("Ka" | "Kd" | "Ks" | "Ke")) && words.count() < 3
    });
    if short_colour {
        return Err(tobj::LoadError::MaterialParseError);
    }
    tobj::load_mtl_buf(&mut bytes.as_slice())
}

/// Refuses what tobj reads without complaint but the renderer cannot draw: non-finite positions
/// or texture coordinates (`v nan 0 0`), more than the mesh limits.
fn check_geometry(path: &Path, models: &[tobj::Model]) -> Result<(), RenderError> {
    let vertices: usize = models.iter().map(|m| m.mesh.positions.len() / 3).sum();
    let triangles: usize = models.iter().map(|m| m.mesh.indices.len() / 3).sum();
    if vertices > MAX_MESH_VERTICES || triangles > MAX_MESH_TRIANGLES {
        return Err(RenderError::bad_mesh(
            path,
            format!(
                "{vertices} vertices and {triangles} triangles, over the limits of \
                 {MAX_MESH_VERTICES} and {MAX_MESH_TRIANGLES}"
            ),
        ));
    }
    for model in models {
        let m = &model.mesh;
        if let Some(v) = m
            .positions
            .iter()
            .chain(&m.texcoords)
            .find(|v| !v.is_finite())
        {
            return Err(RenderError::bad_mesh(
                path,
                format!(
                    "object '{}': coordinate {v} is not a finite number",
                    printable(&model.name)
                ),
            ));
        }
    }
    Ok(())
}

fn load_texture(obj: &Path, file: &Path) -> Result<Texture, RenderError> {
    let bad = |message: String| RenderError::BadTexture {
        path: obj.to_path_buf(),
        texture: printable(&file.display().to_string()),
        message,
    };
    let image = image::open(file)
        .map_err(|e| bad(e.to_string()))?
        .to_rgba8();
    Ok(Texture {
        width: image.width(),
        height: image.height(),
        rgba: image.into_raw(),
    })
}

#[cfg(test)]
mod tests;
