//! Collects a scene while its layout is built: the mesh, the texture specs it asked for (each
//! generated once, in parallel, at the end) and the scene's random stream.

use std::collections::HashMap;

use glam::Vec3;
use rayon::prelude::*;
use rslam_core::Trajectory;

use super::lighting::Lighting;
use super::mesh_builder::{Faces, Frame, Material, MeshBuilder, UvMap};
use super::rng::Rng;
use super::textures::{self, Pattern, Rgb, TextureSpec};
use crate::scene::srgb::srgb_to_linear;
use crate::{Door, Scene, Texture};

pub struct SceneBuilder {
    pub mesh: MeshBuilder,
    pub rng: Rng,
    /// The room's doors, as they are built.
    pub doors: Vec<Door>,
    specs: Vec<TextureSpec>,
    layers: HashMap<TextureSpec, u32>,
}

impl SceneBuilder {
    pub fn new(seed: u64, lighting: Lighting) -> Self {
        Self {
            mesh: MeshBuilder::new(lighting),
            rng: Rng::new(seed),
            doors: Vec::new(),
            specs: Vec::new(),
            layers: HashMap::new(),
        }
    }

    /// A random stream of its own for one piece of furniture.
    pub fn sub_rng(&mut self) -> Rng {
        Rng::new(self.rng.seed())
    }

    /// The texture layer for a pattern and seed, registered on first use.
    pub fn texture(&mut self, pattern: Pattern, seed: u64) -> u32 {
        let spec = TextureSpec { pattern, seed };
        if let Some(&layer) = self.layers.get(&spec) {
            return layer;
        }
        self.specs.push(spec);
        let layer = self.specs.len() as u32; // layer 0 is white
        self.layers.insert(spec, layer);
        layer
    }

    /// A material on a texture with a seed of its own, repeating every `metres`.
    pub fn tiled(&mut self, pattern: Pattern, seed: u64, tint: Rgb, metres: f32) -> Material {
        Material {
            layer: self.texture(pattern, seed),
            tint,
            uv: UvMap::Metres(metres),
            emissive: false,
        }
    }

    /// A material whose texture spans each face once.
    pub fn fitted(&mut self, pattern: Pattern, seed: u64, tint: Rgb) -> Material {
        Material {
            layer: self.texture(pattern, seed),
            tint,
            uv: UvMap::Fit,
            emissive: false,
        }
    }

    /// A fitted material with a fresh seed: a unique poster, painting, screen, …
    pub fn unique(&mut self, pattern: Pattern) -> Material {
        let seed = self.rng.seed();
        self.fitted(pattern, seed, [1.0; 3])
    }

    pub fn cuboid(&mut self, frame: &Frame, min: Vec3, max: Vec3, faces: impl Into<Faces>) {
        self.mesh.cuboid(frame, min, max, faces);
    }

    pub fn finish(self, name: &str, trajectory: Trajectory) -> Scene {
        let mut textures = vec![Texture::white()];
        textures.extend(
            self.specs
                .par_iter()
                .map(textures::cache::texture)
                .collect::<Vec<_>>(),
        );
        let layer_albedo: Vec<Vec3> = textures.iter().map(mean_linear).collect();
        let (mesh, lights) = self.mesh.finish(&layer_albedo);
        Scene {
            name: name.to_string(),
            mesh,
            textures,
            default_trajectory: Some(trajectory),
            splats: None,
            floor: None,
            lights: Some(lights),
        }
    }
}

/// Mean colour of a texture in linear light: the albedo the bake gives its surfaces.
fn mean_linear(t: &Texture) -> Vec3 {
    let sum = t.rgba.chunks_exact(4).fold(Vec3::ZERO, |s, px| {
        s + Vec3::new(
            srgb_to_linear(px[0]),
            srgb_to_linear(px[1]),
            srgb_to_linear(px[2]),
        )
    });
    sum / (t.rgba.len() / 4).max(1) as f32
}
