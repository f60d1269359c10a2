//! PLY files as scenes: the geometry `rslam_core::mesh_io` reads, grey where the file has no
//! vertex colours.

use std::path::Path;

use rslam_core::mesh_io::{parse_ply, read_mesh_bytes};

use super::{Mesh, Vertex};
use crate::RenderError;

/// Vertex colour when the file has none.
const DEFAULT_COLOR: [u8; 3] = [200, 200, 200];

/// Reads the triangles and vertex colours of a PLY file.
pub fn read_ply(path: &Path) -> Result<Mesh, RenderError> {
    let bytes = read_mesh_bytes(path)?;
    let geometry = parse_ply(&bytes).map_err(|message| RenderError::bad_mesh(path, message))?;
    let color = |i: usize| {
        let [r, g, b] = geometry.colors.as_ref().map_or(DEFAULT_COLOR, |c| c[i]);
        [r, g, b, 255]
    };
    let vertices = geometry
        .positions
        .iter()
        .enumerate()
        .map(|(i, &position)| Vertex {
            position,
            uv: [0.0; 2],
            color: color(i),
            layer: 0,
        })
        .collect();
    Ok(Mesh {
        vertices,
        indices: geometry.indices,
    })
}

#[cfg(test)]
mod tests;
