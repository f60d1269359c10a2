//! Ground-truth mesh export for reconstruction metrics: binary little-endian PLY, world
//! coordinates, triangle faces, per-vertex sRGB colour.
//!
//! Colour of a textured vertex = its vertex colour × the mean colour of its texture (averaged in
//! linear light): per-vertex samples of a tiling pattern would be noise, the mean is what a
//! reconstruction at mesh resolution can be compared with.

use std::io::Write;
use std::path::Path;

use super::srgb::{linear_to_srgb, srgb_to_linear};
use super::{Scene, Texture};
use crate::RenderError;

/// Writes the scene's triangle mesh to `path` as PLY; a capture has none and is refused.
pub fn write_ply(scene: &Scene, path: &Path) -> Result<(), RenderError> {
    if scene.splats.is_some() {
        return Err(RenderError::CaptureMesh {
            name: scene.name.clone(),
        });
    }
    let io = |e| RenderError::io(path, e);
    let file = std::fs::File::create(path).map_err(io)?;
    let mut out = std::io::BufWriter::new(file);
    out.write_all(&ply_bytes(scene)).map_err(io)?;
    out.flush().map_err(io)
}

/// The PLY file as bytes.
pub fn ply_bytes(scene: &Scene) -> Vec<u8> {
    let mesh = &scene.mesh;
    let means: Vec<[f32; 3]> = scene.textures.iter().map(mean_linear).collect();
    let header = format!(
        "ply\nformat binary_little_endian 1.0\ncomment rslam ground truth of '{}', world frame, metres\n\
         element vertex {}\nproperty float x\nproperty float y\nproperty float z\n\
         property uchar red\nproperty uchar green\nproperty uchar blue\n\
         element face {}\nproperty list uchar int vertex_indices\nend_header\n",
        scene.name.replace('\n', " "),
        mesh.vertices.len(),
        mesh.triangle_count()
    );
    let mut bytes =
        Vec::with_capacity(header.len() + mesh.vertices.len() * 15 + mesh.indices.len() / 3 * 13);
    bytes.extend_from_slice(header.as_bytes());
    for v in &mesh.vertices {
        for c in v.position {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
        let mean = means.get(v.layer as usize).copied().unwrap_or([1.0; 3]);
        for (k, m) in mean.iter().enumerate() {
            bytes.push(linear_to_srgb(srgb_to_linear(v.color[k]) * m));
        }
    }
    for t in mesh.indices.chunks_exact(3) {
        bytes.push(3);
        for &i in t {
            bytes.extend_from_slice(&(i as i32).to_le_bytes());
        }
    }
    bytes
}

fn mean_linear(t: &Texture) -> [f32; 3] {
    let n = (t.rgba.len() / 4).max(1) as f64;
    let mut sum = [0.0f64; 3];
    for px in t.rgba.chunks_exact(4) {
        for k in 0..3 {
            sum[k] += srgb_to_linear(px[k]) as f64;
        }
    }
    sum.map(|s| (s / n) as f32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{load_scene, Mesh, Vertex};

    #[test]
    fn exported_mesh_reads_back_with_the_same_triangles() {
        let v = |p: [f32; 3], color: [u8; 4], layer| Vertex {
            position: p,
            uv: [0.0; 2],
            color,
            layer,
        };
        let checker = Texture {
            width: 2,
            height: 1,
            rgba: vec![255, 255, 255, 255, 0, 0, 0, 255],
        };
        let scene = Scene {
            name: "fixture".into(),
            mesh: Mesh {
                vertices: vec![
                    v([0.0, 0.0, 0.0], [255, 0, 0, 255], 0),
                    v([1.0, 0.0, 0.5], [255, 255, 255, 255], 1),
                    v([0.0, 2.0, -1.0], [0, 0, 255, 255], 0),
                ],
                indices: vec![0, 1, 2],
            },
            textures: vec![Texture::white(), checker],
            default_trajectory: None,
            splats: None,
            floor: None,
            lights: None,
        };
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("gt.ply");
        write_ply(&scene, &path).unwrap();
        let back = load_scene(path.to_str().unwrap()).unwrap();
        assert_eq!(back.mesh.indices, scene.mesh.indices);
        let positions: Vec<_> = back.mesh.vertices.iter().map(|v| v.position).collect();
        assert_eq!(
            positions,
            scene
                .mesh
                .vertices
                .iter()
                .map(|v| v.position)
                .collect::<Vec<_>>()
        );
        assert_eq!(back.mesh.vertices[0].color, [255, 0, 0, 255]);
        // White × half-black checker = 50 % linear = sRGB 188.
        assert_eq!(back.mesh.vertices[1].color, [188, 188, 188, 255]);
    }
}
