//! Mesh files as plain geometry: positions, optional vertex colours, triangles. A file with
//! vertices and no faces is a point cloud (what many SLAM systems write as their map).
//! The renderer builds its scenes from this, the reconstruction metrics measure it.

mod ply;

pub use ply::{
    parse_ply, parse_ply_vertex_columns, ply_vertex_properties, read_mesh_bytes, read_ply,
};

/// Vertices and triangles of a mesh file, in the file's coordinates (metres for rslam).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshGeometry {
    pub positions: Vec<[f32; 3]>,
    /// sRGB vertex colours, one per position; `None` when the file has none.
    pub colors: Option<Vec<[u8; 3]>>,
    /// Three indices into `positions` per triangle; empty for a point cloud.
    pub indices: Vec<u32>,
}

impl MeshGeometry {
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// Vertices without faces.
    pub fn is_point_cloud(&self) -> bool {
        self.indices.is_empty()
    }
}
