//! A content hash of a scene for the dataset manifest: FNV-1a 64 over an explicit little-endian
//! serialisation of the mesh and textures, so it is the same on every run, platform and Rust version.

use rslam_core::hash::Fnv1a64;

use super::Scene;

/// FNV-1a over little-endian numbers.
struct ContentHasher(Fnv1a64);

impl ContentHasher {
    fn bytes(&mut self, bytes: &[u8]) {
        self.0.write(bytes);
    }

    fn u32(&mut self, v: u32) {
        self.bytes(&v.to_le_bytes());
    }

    fn f32(&mut self, v: f32) {
        self.u32(v.to_bits());
    }
}

impl Scene {
    /// 16 hex digits identifying the geometry, colours and textures (not the name, not the default
    /// trajectory): two scenes with the same hash render the same images from the same poses.
    pub fn content_hash(&self) -> String {
        let mut h = ContentHasher(Fnv1a64::default());
        h.u32(self.mesh.vertices.len() as u32);
        for v in &self.mesh.vertices {
            v.position.iter().for_each(|&c| h.f32(c));
            v.uv.iter().for_each(|&c| h.f32(c));
            h.bytes(&v.color);
            h.u32(v.layer);
        }
        h.u32(self.mesh.indices.len() as u32);
        self.mesh.indices.iter().for_each(|&i| h.u32(i));
        h.u32(self.textures.len() as u32);
        for t in &self.textures {
            h.u32(t.width);
            h.u32(t.height);
            h.bytes(&t.rgba);
        }
        format!("{:016x}", h.0.finish())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Mesh, Texture, Vertex};

    fn one_triangle() -> Scene {
        let v = |x: f32| Vertex {
            position: [x, 0.0, 1.0],
            uv: [0.0, 0.0],
            color: [200, 100, 50, 255],
            layer: 0,
        };
        Scene {
            name: "tri".into(),
            mesh: Mesh {
                vertices: vec![v(0.0), v(1.0), v(2.0)],
                indices: vec![0, 1, 2],
            },
            textures: vec![Texture::white()],
            default_trajectory: None,
            lights: None,
        }
    }

    #[test]
    fn hash_is_pinned_and_sees_every_part() {
        let base = one_triangle();
        let hash = base.content_hash();
        assert_eq!(hash.len(), 16);
        let mut renamed = base.clone();
        renamed.name = "other".into();
        assert_eq!(renamed.content_hash(), hash, "the name is not content");

        let mut moved = base.clone();
        moved.mesh.vertices[1].position[2] = 1.001;
        let mut recoloured = base.clone();
        recoloured.mesh.vertices[2].color[0] = 201;
        let mut reindexed = base.clone();
        reindexed.mesh.indices = vec![0, 2, 1];
        let mut retextured = base.clone();
        retextured.textures[0].rgba[3] = 0;
        for changed in [moved, recoloured, reindexed, retextured] {
            assert_ne!(changed.content_hash(), hash);
        }
    }
}
