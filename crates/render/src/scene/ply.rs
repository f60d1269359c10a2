//! PLY files as scenes: the geometry `rslam_core::mesh_io` reads, grey where the file has no
//! vertex colours.

use std::path::Path;

use rslam_core::mesh_io::parse_ply;

use super::{Mesh, Vertex};
use crate::RenderError;

/// Vertex colour when the file has none.
const DEFAULT_COLOR: [u8; 3] = [200, 200, 200];

/// The triangles and vertex colours of the PLY file `path`, whose bytes are `bytes`.
pub fn mesh_from_ply(path: &Path, bytes: &[u8]) -> Result<Mesh, RenderError> {
    let geometry = parse_ply(bytes).map_err(|message| RenderError::bad_mesh(path, message))?;
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
