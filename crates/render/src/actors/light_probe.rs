//! The light on an actor: what the scene's surfaces send towards a point, per light layer, as an
//! ambient cube (the light a surface facing each of ±x, ±y, ±z receives). The scene's surfaces
//! show their light-layer colours times their texture's mean albedo, so an actor is lit by the
//! same lamps and daylight as the room (its glowing fixtures and windows included) and follows
//! the light items' weights like every vertex of the scene.

use glam::Vec3;

use crate::raycast::RayCaster;
use crate::scene::srgb::srgb_to_linear;
use crate::{Scene, Texture};

/// Rays per probe: a Fibonacci sphere.
const RAYS: usize = 256;
const AXES: [Vec3; 6] = [
    Vec3::X,
    Vec3::NEG_X,
    Vec3::Y,
    Vec3::NEG_Y,
    Vec3::Z,
    Vec3::NEG_Z,
];

/// Linear RGB per axis (±x, ±y, ±z) and light layer: `[axis][layer]`.
pub type AmbientCube = [Vec<Vec3>; 6];

pub struct LightProbe {
    caster: RayCaster,
    /// Linear colour per vertex and layer of the scene, vertex-major.
    layer_colours: Vec<Vec3>,
    layers: usize,
    /// Texture layer of each vertex.
    vertex_texture: Vec<u32>,
    indices: Vec<u32>,
    /// Mean linear colour of each texture.
    albedo: Vec<Vec3>,
    directions: Vec<Vec3>,
}

impl LightProbe {
    /// The probe of `scene`; `None` when its light is not kept as layers.
    pub fn new(scene: &Scene) -> Option<Self> {
        let lights = scene.lights.as_ref()?;
        Some(Self {
            caster: RayCaster::from_mesh(&scene.mesh),
            layer_colours: lights.colours.iter().map(|&c| Vec3::from(c)).collect(),
            layers: lights.kinds.len(),
            vertex_texture: scene.mesh.vertices.iter().map(|v| v.layer).collect(),
            indices: scene.mesh.indices.clone(),
            albedo: scene.textures.iter().map(mean_albedo).collect(),
            directions: fibonacci_sphere(RAYS),
        })
    }

    pub fn layer_count(&self) -> usize {
        self.layers
    }

    /// The light arriving at `point` from every direction, as an ambient cube.
    pub fn cube(&self, point: Vec3) -> AmbientCube {
        let mut cube: AmbientCube = std::array::from_fn(|_| vec![Vec3::ZERO; self.layers]);
        // Irradiance over π of a face with normal a: (4π / N) Σ L max(0, ω·a) / π.
        let weight = 4.0 / self.directions.len() as f32;
        for &direction in &self.directions {
            let Some(hit) = self.caster.cast(point, direction) else {
                continue;
            };
            let corners = &self.indices[3 * hit.triangle as usize..3 * hit.triangle as usize + 3];
            let albedo = self.albedo[self.vertex_texture[corners[0] as usize] as usize];
            for (axis, sums) in AXES.iter().zip(cube.iter_mut()) {
                let facing = direction.dot(*axis);
                if facing <= 0.0 {
                    continue;
                }
                for (layer, sum) in sums.iter_mut().enumerate() {
                    let radiance: Vec3 = corners
                        .iter()
                        .zip(hit.barycentrics)
                        .map(|(&v, b)| self.layer_colours[v as usize * self.layers + layer] * b)
                        .sum();
                    *sum += radiance * albedo * facing * weight;
                }
            }
        }
        cube
    }
}

/// The light of `layer` on a surface with unit normal `n` from an ambient cube.
pub fn cube_light(cube: &AmbientCube, n: Vec3, layer: usize) -> Vec3 {
    let pick = |positive: usize, c: f32| {
        cube[if c >= 0.0 { positive } else { positive + 1 }][layer] * (c * c)
    };
    pick(0, n.x) + pick(2, n.y) + pick(4, n.z)
}

fn mean_albedo(texture: &Texture) -> Vec3 {
    let texels = texture.rgba.chunks_exact(4);
    let count = texels.len().max(1) as f32;
    let sum: Vec3 = texels
        .map(|t| {
            Vec3::new(
                srgb_to_linear(t[0]),
                srgb_to_linear(t[1]),
                srgb_to_linear(t[2]),
            )
        })
        .sum();
    sum / count
}

fn fibonacci_sphere(n: usize) -> Vec<Vec3> {
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    (0..n)
        .map(|i| {
            let z = 1.0 - 2.0 * (i as f32 + 0.5) / n as f32;
            let r = (1.0 - z * z).sqrt();
            let a = golden * i as f32;
            Vec3::new(r * a.cos(), r * a.sin(), z)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cube_of_uniform_light_gives_every_face_that_light() {
        // Inside a closed box whose walls all show the same light, every face of an actor
        // receives it: the cube's faces and any normal between them.
        let uniform: AmbientCube = std::array::from_fn(|_| vec![Vec3::splat(0.5)]);
        for n in [
            Vec3::X,
            Vec3::new(1.0, 1.0, 1.0).normalize(),
            Vec3::new(-0.3, 0.4, -0.866),
        ] {
            let light = cube_light(&uniform, n.normalize(), 0);
            assert!(
                (light - Vec3::splat(0.5)).abs().max_element() < 1e-5,
                "{n}: {light}"
            );
        }
        // The Fibonacci sphere's cosine sums: each face gets (4/N) Σ max(0, ω·a) ≈ 1.
        let dirs = fibonacci_sphere(RAYS);
        for axis in AXES {
            let sum: f32 =
                dirs.iter().map(|d| d.dot(axis).max(0.0)).sum::<f32>() * 4.0 / RAYS as f32;
            assert!((sum - 1.0).abs() < 0.01, "{axis}: {sum}");
        }
    }
}
