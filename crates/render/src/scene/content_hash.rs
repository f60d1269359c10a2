//! A content hash of a scene for the dataset manifest: FNV-1a 64 over an explicit little-endian
//! serialisation of the mesh and textures (and a capture's Gaussians), so it is the same on every run, platform and Rust version.

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
    /// 16 hex digits identifying the geometry, colours, textures and Gaussians (not the name, not the default
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
        // Only captures hash their Gaussians, so that every mesh keeps its hash.
        if let Some(cloud) = &self.splats {
            h.u32(cloud.len() as u32);
            h.u32(cloud.sh_degree);
            let floats = (cloud.means.iter().flatten())
                .chain(cloud.sh.iter().flatten())
                .chain(&cloud.opacity_logits)
                .chain(cloud.log_scales.iter().flatten())
                .chain(cloud.rotations.iter().flatten());
            floats.for_each(|&v| h.f32(v));
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
            splats: None,
            floor: None,
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

    #[test]
    fn captures_hash_every_gaussian_property() {
        let cloud = rslam_core::splat_io::SplatCloud {
            means: vec![[0.0, 0.0, 1.0]],
            sh_degree: 0,
            sh: vec![[0.1, 0.2, 0.3]],
            opacity_logits: vec![1.0],
            log_scales: vec![[-2.0; 3]],
            rotations: vec![[1.0, 0.0, 0.0, 0.0]],
        };
        let capture = |change: &dyn Fn(&mut rslam_core::splat_io::SplatCloud)| {
            let mut cloud = cloud.clone();
            change(&mut cloud);
            Scene {
                mesh: Mesh::default(),
                splats: Some(std::sync::Arc::new(cloud)),
                ..one_triangle()
            }
            .content_hash()
        };
        let hash = capture(&|_| {});
        let changes: [&dyn Fn(&mut rslam_core::splat_io::SplatCloud); 5] = [
            &|c| c.means[0][2] = 1.5,
            &|c| c.sh[0][1] = 0.0,
            &|c| c.opacity_logits[0] = 0.0,
            &|c| c.log_scales[0][0] = -1.0,
            &|c| c.rotations[0][3] = 0.5,
        ];
        for change in changes {
            assert_ne!(capture(change), hash);
        }
    }
}
