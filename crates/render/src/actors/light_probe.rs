//! The light on an actor: what the scene's surfaces send towards a point, per light layer, as an
//! ambient cube (the light a surface facing each of ±x, ±y, ±z receives). The scene's surfaces
//! show their light-layer colours times their texture's mean albedo, so an actor is lit by the
//! same lamps and daylight as the room (its glowing fixtures and windows included) and follows
//! the light items' weights like every vertex of the scene.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use glam::{Vec2, Vec3};

use crate::raycast::RayCaster;
use crate::scene::srgb::srgb_to_linear;
use crate::{Scene, Texture};

/// Heights of the probes on a walker's axis, metres: light between them is interpolated.
pub const PROBE_HEIGHTS: [f32; 3] = [0.3, 0.9, 1.5];
/// Probes stand on a grid of this spacing over the floor, metres; a walker between four takes
/// their bilinear blend (the light changes over metres, and each is gathered once per job).
const GRID: f32 = 0.25;

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
/// The cubes at [`PROBE_HEIGHTS`] on one vertical axis.
pub type ProbeColumn = [AmbientCube; 3];
/// The columns of the grid nodes gathered so far, by node; `None` for a node inside furniture
/// or a wall.
type NodeCache = Mutex<HashMap<(i64, i64), Option<Arc<ProbeColumn>>>>;

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
    nodes: NodeCache,
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
            nodes: Mutex::new(HashMap::new()),
        })
    }

    pub fn layer_count(&self) -> usize {
        self.layers
    }

    /// The light on an axis standing at `at`, at each of [`PROBE_HEIGHTS`]: the blend of the
    /// four grid nodes round it that lie in the open, or gathered at `at` itself when none does.
    pub fn cubes_at(&self, at: Vec2) -> ProbeColumn {
        let g = at / GRID;
        let (i, j) = (g.x.floor() as i64, g.y.floor() as i64);
        let (fx, fy) = (g.x - i as f32, g.y - j as f32);
        let corners = [
            (i, j, (1.0 - fx) * (1.0 - fy)),
            (i + 1, j, fx * (1.0 - fy)),
            (i, j + 1, (1.0 - fx) * fy),
            (i + 1, j + 1, fx * fy),
        ];
        let open: Vec<(Arc<ProbeColumn>, f32)> = (corners.into_iter())
            .filter_map(|(i, j, weight)| Some((self.node(i, j)?, weight)))
            .collect();
        let total: f32 = open.iter().map(|(_, w)| w).sum();
        if total <= 1e-6 {
            return PROBE_HEIGHTS.map(|z| self.cube(at.extend(z)).unwrap_or_else(|| self.dark()));
        }
        let mut blend: ProbeColumn = std::array::from_fn(|_| self.dark());
        for (node, weight) in open {
            let weight = weight / total;
            for (sum, cube) in blend.iter_mut().zip(node.iter()) {
                for (sum_axis, axis) in sum.iter_mut().zip(cube) {
                    for (s, c) in sum_axis.iter_mut().zip(axis) {
                        *s += *c * weight;
                    }
                }
            }
        }
        blend
    }

    fn node(&self, i: i64, j: i64) -> Option<Arc<ProbeColumn>> {
        if let Some(known) = self.nodes.lock().expect("probe cache").get(&(i, j)) {
            return known.clone();
        }
        let at = Vec2::new(i as f32, j as f32) * GRID;
        let cubes: Option<Vec<AmbientCube>> = PROBE_HEIGHTS
            .iter()
            .map(|&z| self.cube(at.extend(z)))
            .collect();
        let cubes = cubes.map(|c| Arc::new(ProbeColumn::try_from(c).expect("three")));
        let mut nodes = self.nodes.lock().expect("probe cache");
        nodes.insert((i, j), cubes.clone());
        cubes
    }

    fn dark(&self) -> AmbientCube {
        std::array::from_fn(|_| vec![Vec3::ZERO; self.layers])
    }

    /// The light arriving at `point` from every direction, as an ambient cube; `None` when
    /// `point` is enclosed (most rays meet the back of a surface: inside furniture or a wall).
    fn cube(&self, point: Vec3) -> Option<AmbientCube> {
        let mut cube = self.dark();
        let mut backs = 0;
        // Irradiance over π of a face with normal a: (4π / N) Σ L max(0, ω·a) / π.
        let weight = 4.0 / self.directions.len() as f32;
        for &direction in &self.directions {
            let Some(hit) = self.caster.cast(point, direction) else {
                continue;
            };
            if self.caster.triangle_normal(hit.triangle).dot(direction) > 0.0 {
                backs += 1;
            }
            let corners = &self.indices[3 * hit.triangle as usize..3 * hit.triangle as usize + 3];
            let albedo = self.albedo[self.vertex_texture[corners[0] as usize] as usize];
            let radiance: Vec<Vec3> = (0..self.layers)
                .map(|layer| {
                    let at_hit: Vec3 = (corners.iter().zip(hit.barycentrics))
                        .map(|(&v, b)| self.layer_colours[v as usize * self.layers + layer] * b)
                        .sum();
                    at_hit * albedo * weight
                })
                .collect();
            for (axis, sums) in AXES.iter().zip(cube.iter_mut()) {
                let facing = direction.dot(*axis);
                if facing > 0.0 {
                    for (sum, r) in sums.iter_mut().zip(&radiance) {
                        *sum += *r * facing;
                    }
                }
            }
        }
        (backs * 2 < self.directions.len()).then_some(cube)
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
    use crate::{LightKind, LightLayers, Mesh, Vertex};

    /// An axis-aligned box of half size `h` about the origin, its faces turned inwards
    /// (`inwards`) or outwards, every vertex showing `light` in the one lamp layer.
    fn box_scene(h: f32, inwards: bool, light: f32) -> Scene {
        let mut mesh = Mesh::default();
        for axis in 0..3 {
            for sign in [-1.0f32, 1.0] {
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                let corner = |a: f32, b: f32| {
                    let mut p = [0.0; 3];
                    p[axis] = sign * h;
                    p[u] = a * h;
                    p[v] = b * h;
                    p
                };
                let base = mesh.vertices.len() as u32;
                for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                    mesh.vertices.push(Vertex {
                        position: corner(a, b),
                        uv: [0.0; 2],
                        color: [255; 4],
                        layer: 0,
                    });
                }
                // (u, v, axis) is right-handed, so this order is counter-clockwise seen from
                // the +axis side: outwards on the + face, and flipped for the − face or a room.
                let tri: [u32; 6] = match (sign > 0.0) ^ inwards {
                    true => [0, 1, 2, 0, 2, 3],
                    false => [0, 2, 1, 0, 3, 2],
                };
                mesh.indices.extend(tri.map(|i| base + i));
            }
        }
        let colours = vec![[light; 3]; mesh.vertices.len()];
        Scene {
            name: "box".into(),
            mesh,
            textures: vec![Texture::white()],
            default_trajectory: None,
            lights: Some(LightLayers {
                kinds: vec![LightKind::Lamp],
                colours,
            }),
            splats: None,
            floor: None,
        }
    }

    #[test]
    fn a_probe_in_a_room_sees_its_light_and_one_inside_furniture_sees_none() {
        let room = LightProbe::new(&box_scene(2.0, true, 0.6)).unwrap();
        let cube = room.cube(Vec3::new(0.3, -0.2, 0.1)).expect("open");
        for n in [Vec3::X, Vec3::NEG_Z, Vec3::new(0.6, 0.0, 0.8)] {
            let light = cube_light(&cube, n, 0);
            assert!(
                (light - Vec3::splat(0.6)).abs().max_element() < 0.02,
                "{n}: {light}"
            );
        }
        let furniture = LightProbe::new(&box_scene(0.5, false, 0.6)).unwrap();
        assert!(furniture.cube(Vec3::ZERO).is_none(), "inside a closed box");
        // Its four grid nodes have their lowest probe inside the box: none counts, and the
        // walker's own axis gives no light at that height.
        let cubes = furniture.cubes_at(Vec2::new(0.1, 0.1));
        assert!(cubes[0].iter().all(|axis| axis[0] == Vec3::ZERO));
        assert!(
            cubes[2].iter().any(|axis| axis[0] != Vec3::ZERO),
            "lit above it"
        );
    }

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
