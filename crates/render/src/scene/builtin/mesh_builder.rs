//! Geometry primitives for the procedural scenes: subdivided quads, cuboids, cylinders and
//! ellipsoids placed by a [`Frame`], with UVs in metres (or fitted to a face). Vertices keep their
//! normal and tint until [`MeshBuilder::finish`] bakes the lighting into their colours.
//!
//! Winding: every triangle is counter-clockwise seen from the side its normal points to, and
//! normals point out of solids and into the room, so a ray from free space always meets a front face.

use glam::{Vec2, Vec3};

use super::exposure::exposure;
use super::lighting::{bake, glowing_layer, BakeInput, Lighting, Window};
use super::textures::Rgb;
use crate::scene::srgb::{linear_to_srgb, unit_srgb_to_linear};
use crate::{LightKind, LightLayers, Mesh, Vertex};

/// Largest edge of one quad cell, metres; bounds the spacing of the baked lighting samples.
const MAX_CELL: f32 = 0.25;

#[derive(Clone, Copy, Debug)]
pub enum UvMap {
    /// One texture repeat per this many metres, anchored to the object's local axes.
    Metres(f32),
    /// The texture spans the face once.
    Fit,
}

#[derive(Clone, Copy, Debug)]
pub struct Material {
    /// Texture layer (0 = white).
    pub layer: u32,
    pub tint: Rgb,
    pub uv: UvMap,
    /// Glows (a lamp shade, the view through a window): shown at its own colour, never shaded.
    pub emissive: bool,
}

impl Material {
    pub fn glowing(self) -> Self {
        Self {
            emissive: true,
            ..self
        }
    }
}

/// Placement: local x right (seen from the front), local y away from the viewer (front face at
/// −y), z up; rotated by `yaw` about z, then moved to `origin`.
#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub origin: Vec3,
    pub yaw: f32,
}

impl Frame {
    pub fn new(origin: Vec3, yaw: f32) -> Self {
        Self { origin, yaw }
    }

    pub fn vector(&self, v: Vec3) -> Vec3 {
        let (s, c) = self.yaw.sin_cos();
        Vec3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z)
    }

    pub fn point(&self, p: Vec3) -> Vec3 {
        self.origin + self.vector(p)
    }

    /// A frame inside this one: offset in local coordinates, turned by `yaw` more.
    pub fn then(&self, offset: Vec3, yaw: f32) -> Frame {
        Frame::new(self.point(offset), self.yaw + yaw)
    }
}

/// Which faces of a cuboid to build, and with what; `None` leaves a face out (e.g. a bottom
/// resting on the floor).
#[derive(Clone, Copy, Debug)]
pub struct Faces {
    /// Top, bottom, front (−y), back (+y), right (+x), left (−x).
    pub sides: [Option<Material>; 6],
}

impl Faces {
    pub const TOP: usize = 0;
    pub const BOTTOM: usize = 1;
    pub const FRONT: usize = 2;
    pub const BACK: usize = 3;

    pub fn all(m: Material) -> Self {
        Self {
            sides: [Some(m); 6],
        }
    }

    pub fn with(mut self, side: usize, m: Material) -> Self {
        self.sides[side] = Some(m);
        self
    }

    pub fn without(mut self, side: usize) -> Self {
        self.sides[side] = None;
        self
    }
}

impl From<Material> for Faces {
    fn from(m: Material) -> Self {
        Faces::all(m)
    }
}

pub struct MeshBuilder {
    mesh: Mesh,
    normals: Vec<Vec3>,
    tints: Vec<Rgb>,
    emissive: Vec<bool>,
    lighting: Lighting,
}

impl MeshBuilder {
    pub fn new(lighting: Lighting) -> Self {
        Self {
            mesh: Mesh::default(),
            normals: Vec::new(),
            tints: Vec::new(),
            emissive: Vec::new(),
            lighting,
        }
    }

    /// A window pane that lets daylight in (its quad is built separately).
    pub fn window_light(&mut self, frame: &Frame, top_left: Vec3, right: Vec3, down: Vec3) {
        self.lighting.windows.push(Window {
            corner: frame.point(top_left),
            right: frame.vector(right),
            down: frame.vector(down),
        });
    }

    /// The unlit mesh with its normals, linear tints and glow flags, for the bake's tests.
    #[cfg(test)]
    pub fn into_bake_parts(self) -> (Mesh, Vec<Vec3>, Vec<Vec3>, Vec<bool>) {
        let tints = self.tints.iter().map(|&t| linear(t)).collect();
        (self.mesh, self.normals, tints, self.emissive)
    }

    /// The mesh with its lighting baked into the vertex colours, and each light's share of them
    /// ([`LightLayers`]); `layer_albedo[l]` is the mean linear colour of texture layer `l`.
    /// Indices so far: where the next piece's triangles start in the finished mesh.
    pub fn index_count(&self) -> u32 {
        self.mesh.indices.len() as u32
    }

    pub fn finish(mut self, layer_albedo: &[Vec3]) -> (Mesh, LightLayers) {
        let tints: Vec<Vec3> = self.tints.iter().map(|&t| linear(t)).collect();
        let albedo: Vec<Vec3> = tints
            .iter()
            .zip(&self.mesh.vertices)
            .map(|(&t, v)| t * layer_albedo[v.layer as usize])
            .collect();
        let baked = bake(&BakeInput {
            mesh: &self.mesh,
            normals: &self.normals,
            albedo: &albedo,
            emissive: &self.emissive,
            lighting: &self.lighting,
        });
        let radiance: Vec<Vec3> = baked
            .total
            .iter()
            .zip(&albedo)
            .map(|(&e, &a)| e * a)
            .collect();
        let exposure = exposure(&self.mesh, &radiance, &self.emissive);
        let layer_count = self.lighting.layer_count();
        let mut colours = Vec::with_capacity(self.mesh.vertices.len() * layer_count);
        for (i, v) in self.mesh.vertices.iter_mut().enumerate() {
            let shade = if self.emissive[i] {
                Vec3::ONE
            } else {
                baked.total[i] * exposure
            };
            let c = tints[i] * shade;
            v.color = [
                linear_to_srgb(c.x),
                linear_to_srgb(c.y),
                linear_to_srgb(c.z),
                255,
            ];
            let glows_with = self.emissive[i].then(|| glowing_layer(&self.lighting, v.position));
            colours.extend((0..layer_count).map(|l| {
                let share = match glows_with {
                    Some(layer) if layer == l => tints[i],
                    Some(_) => Vec3::ZERO,
                    None => tints[i] * baked.layers[l][i] * exposure,
                };
                share.to_array()
            }));
        }
        let lamps = self.lighting.lamps.len();
        let kinds = (0..layer_count)
            .map(|l| match l < lamps {
                true => LightKind::Lamp,
                false => LightKind::Daylight,
            })
            .collect();
        (self.mesh, LightLayers { kinds, colours })
    }

    /// A rectangle seen from its front: `top_left` corner, `right` and `down` edges (local
    /// coordinates of `frame`). Its normal is `down × right`, towards the viewer.
    pub fn quad(&mut self, frame: &Frame, top_left: Vec3, right: Vec3, down: Vec3, m: &Material) {
        let (la, lb) = (right.length(), down.length());
        if la <= 0.0 || lb <= 0.0 {
            return;
        }
        let (na, nb) = ((la / MAX_CELL).ceil() as u32, (lb / MAX_CELL).ceil() as u32);
        let normal = frame.vector(down.cross(right).normalize());
        let (ua, ub) = (right / la, down / lb);
        let base = self.mesh.vertices.len() as u32;
        for j in 0..=nb {
            for i in 0..=na {
                let (s, t) = (i as f32 / na as f32, j as f32 / nb as f32);
                let local = top_left + right * s + down * t;
                let uv = match m.uv {
                    UvMap::Metres(size) => Vec2::new(local.dot(ua), local.dot(ub)) / size,
                    UvMap::Fit => Vec2::new(s, t),
                };
                self.push_vertex(frame.point(local), normal, uv, m);
            }
        }
        let row = na + 1;
        for j in 0..nb {
            for i in 0..na {
                let tl = base + j * row + i;
                let (tr, bl, br) = (tl + 1, tl + row, tl + row + 1);
                self.mesh
                    .indices
                    .extend_from_slice(&[tl, bl, br, tl, br, tr]);
            }
        }
    }

    /// An axis-aligned box in the frame's local coordinates.
    pub fn cuboid(&mut self, frame: &Frame, min: Vec3, max: Vec3, faces: impl Into<Faces>) {
        let faces = faces.into();
        let s = max - min;
        let (x, y, z) = (Vec3::X * s.x, Vec3::Y * s.y, Vec3::Z * s.z);
        let (x0, y0, z0, x1, y1, z1) = (min.x, min.y, min.z, max.x, max.y, max.z);
        let sides = [
            (Vec3::new(x0, y1, z1), x, -y),  // top: seen from above, "down" is −y
            (Vec3::new(x0, y0, z0), x, y),   // bottom
            (Vec3::new(x0, y0, z1), x, -z),  // front
            (Vec3::new(x1, y1, z1), -x, -z), // back
            (Vec3::new(x1, y0, z1), y, -z),  // right
            (Vec3::new(x0, y1, z1), -y, -z), // left
        ];
        for (m, (tl, right, down)) in faces.sides.iter().zip(sides) {
            if let Some(m) = m {
                self.quad(frame, tl, right, down, m);
            }
        }
    }

    /// A vertical cylinder standing on `base` (local), with a top cap.
    pub fn cylinder(&mut self, frame: &Frame, base: Vec3, radius: f32, height: f32, m: &Material) {
        let segments = ((radius * 100.0).ceil() as u32).clamp(12, 40);
        let first = self.mesh.vertices.len() as u32;
        for k in 0..=segments {
            let a = k as f32 / segments as f32 * std::f32::consts::TAU;
            let n = Vec3::new(a.cos(), a.sin(), 0.0);
            for (zi, z) in [height, 0.0].into_iter().enumerate() {
                let uv = match m.uv {
                    UvMap::Metres(size) => Vec2::new(a * radius, height - z) / size,
                    UvMap::Fit => Vec2::new(k as f32 / segments as f32, zi as f32),
                };
                self.push_vertex(
                    frame.point(base + n * radius + Vec3::Z * z),
                    frame.vector(n),
                    uv,
                    m,
                );
            }
        }
        for k in 0..segments {
            let (t0, b0, t1, b1) = (
                first + 2 * k,
                first + 2 * k + 1,
                first + 2 * k + 2,
                first + 2 * k + 3,
            );
            self.mesh
                .indices
                .extend_from_slice(&[t0, b0, b1, t0, b1, t1]);
        }
        let centre = self.mesh.vertices.len() as u32;
        let top = base + Vec3::Z * height;
        let uv_of = |p: Vec3| match m.uv {
            UvMap::Metres(size) => Vec2::new(p.x, -p.y) / size,
            UvMap::Fit => Vec2::new(0.5 + p.x / (2.0 * radius), 0.5 - p.y / (2.0 * radius)),
        };
        self.push_vertex(
            frame.point(top),
            frame.vector(Vec3::Z),
            uv_of(Vec3::ZERO),
            m,
        );
        for k in 0..=segments {
            let a = k as f32 / segments as f32 * std::f32::consts::TAU;
            let rim = Vec3::new(a.cos(), a.sin(), 0.0) * radius;
            self.push_vertex(frame.point(top + rim), frame.vector(Vec3::Z), uv_of(rim), m);
        }
        for k in 0..segments {
            self.mesh
                .indices
                .extend_from_slice(&[centre, centre + 1 + k, centre + 2 + k]);
        }
    }

    /// An ellipsoid around `centre` (local) with semi-axes `radii`.
    pub fn ellipsoid(&mut self, frame: &Frame, centre: Vec3, radii: Vec3, m: &Material) {
        const RINGS: u32 = 10;
        const SEGMENTS: u32 = 18;
        let first = self.mesh.vertices.len() as u32;
        for j in 0..=RINGS {
            let lat = std::f32::consts::PI * (j as f32 / RINGS as f32 - 0.5);
            for k in 0..=SEGMENTS {
                let lon = std::f32::consts::TAU * k as f32 / SEGMENTS as f32;
                let unit = Vec3::new(lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin());
                let normal = (unit / radii).normalize();
                let uv = match m.uv {
                    UvMap::Metres(size) => Vec2::new(lon * radii.x, -lat * radii.z) / size,
                    UvMap::Fit => {
                        Vec2::new(k as f32 / SEGMENTS as f32, 1.0 - j as f32 / RINGS as f32)
                    }
                };
                self.push_vertex(
                    frame.point(centre + unit * radii),
                    frame.vector(normal),
                    uv,
                    m,
                );
            }
        }
        let row = SEGMENTS + 1;
        for j in 0..RINGS {
            for k in 0..SEGMENTS {
                let a = first + j * row + k;
                let (b, c, d) = (a + 1, a + row, a + row + 1);
                self.mesh.indices.extend_from_slice(&[a, b, d, a, d, c]);
            }
        }
    }

    fn push_vertex(&mut self, position: Vec3, normal: Vec3, uv: Vec2, m: &Material) {
        self.mesh.vertices.push(Vertex {
            position: position.into(),
            uv: uv.into(),
            color: [255; 4],
            layer: m.layer,
        });
        self.normals.push(normal);
        self.tints.push(m.tint);
        self.emissive.push(m.emissive);
    }
}

/// An sRGB tint in [0, 1] as linear light.
fn linear(t: Rgb) -> Vec3 {
    Vec3::from(t.map(unit_srgb_to_linear))
}
