//! Surface colour at a hit: vertex colour × texture, with a box-filtered mip chain per texture so
//! low-resolution views see the average of the texels a pixel covers rather than aliasing.

use obvhs::triangle::Triangle;

use super::Hit;
use crate::scene::srgb::{linear_to_srgb, srgb_to_linear};
use crate::{Mesh, Texture, Vertex};

pub(super) struct Shading {
    vertices: Vec<Vertex>,
    indices: Vec<u32>,
    textures: Vec<MipChain>,
    /// Per triangle: texels per metre of level 0 of its texture, for the mip choice.
    texel_density: Vec<f32>,
}

struct Level {
    width: usize,
    height: usize,
    /// sRGB; filtered in linear light.
    rgb: Vec<[u8; 3]>,
}

struct MipChain {
    levels: Vec<Level>,
}

impl Shading {
    pub(super) fn new(mesh: &Mesh, textures: &[Texture], triangles: &[Triangle]) -> Self {
        let textures: Vec<MipChain> = textures.iter().map(MipChain::new).collect();
        let texel_density = mesh
            .indices
            .chunks_exact(3)
            .zip(triangles)
            .map(|(idx, tri)| {
                let v = [0, 1, 2].map(|k| mesh.vertices[idx[k] as usize]);
                let base = textures
                    .get(v[0].layer as usize)
                    .map_or((1, 1), |t| (t.levels[0].width, t.levels[0].height));
                let (d1, d2) = (
                    [v[1].uv[0] - v[0].uv[0], v[1].uv[1] - v[0].uv[1]],
                    [v[2].uv[0] - v[0].uv[0], v[2].uv[1] - v[0].uv[1]],
                );
                let uv_area = (d1[0] * d2[1] - d1[1] * d2[0]).abs() * 0.5;
                let world_area = (tri.v1 - tri.v0).cross(tri.v2 - tri.v0).length() * 0.5;
                if world_area > 0.0 {
                    (uv_area * (base.0 * base.1) as f32 / world_area).sqrt()
                } else {
                    0.0
                }
            })
            .collect();
        Self {
            vertices: mesh.vertices.clone(),
            indices: mesh.indices.clone(),
            textures,
            texel_density,
        }
    }

    pub(super) fn color_at(&self, hit: &Hit, footprint: f32) -> [u8; 3] {
        let t = hit.triangle as usize;
        let v = [0, 1, 2].map(|i| self.vertices[self.indices[3 * t + i] as usize]);
        let b = hit.barycentrics;
        let lerp = |f: &dyn Fn(&Vertex) -> f32| b[0] * f(&v[0]) + b[1] * f(&v[1]) + b[2] * f(&v[2]);
        let uv = [lerp(&|v| v.uv[0]), lerp(&|v| v.uv[1])];
        let vertex_rgb: [f32; 3] = std::array::from_fn(|c| lerp(&|v| srgb_to_linear(v.color[c])));
        let texel = match self.textures.get(v[0].layer as usize) {
            Some(chain) => {
                let texels = footprint * self.texel_density[t];
                let lod = if texels > 1.0 {
                    texels.log2().round() as usize
                } else {
                    0
                };
                chain.sample(lod, uv)
            }
            None => [1.0; 3],
        };
        std::array::from_fn(|c| linear_to_srgb(vertex_rgb[c] * texel[c]))
    }
}

impl MipChain {
    fn new(texture: &Texture) -> Self {
        let mut levels = vec![Level {
            width: texture.width as usize,
            height: texture.height as usize,
            rgb: texture
                .rgba
                .chunks_exact(4)
                .map(|p| [p[0], p[1], p[2]])
                .collect(),
        }];
        while let Some(next) = levels.last().and_then(Level::halved) {
            levels.push(next);
        }
        Self { levels }
    }

    fn sample(&self, lod: usize, uv: [f32; 2]) -> [f32; 3] {
        self.levels[lod.min(self.levels.len() - 1)].bilinear(uv)
    }
}

impl Level {
    /// 2×2 box filter; `None` once 1×1.
    fn halved(&self) -> Option<Level> {
        if self.width == 1 && self.height == 1 {
            return None;
        }
        let (width, height) = ((self.width / 2).max(1), (self.height / 2).max(1));
        let at = |x: usize, y: usize| {
            self.rgb[y.min(self.height - 1) * self.width + x.min(self.width - 1)]
        };
        let rgb = (0..width * height)
            .map(|i| {
                let (x, y) = (2 * (i % width), 2 * (i / width));
                let q = [at(x, y), at(x + 1, y), at(x, y + 1), at(x + 1, y + 1)];
                std::array::from_fn(|c| {
                    linear_to_srgb(q.iter().map(|p| srgb_to_linear(p[c])).sum::<f32>() * 0.25)
                })
            })
            .collect();
        Some(Level { width, height, rgb })
    }

    /// Repeat wrap, texel centres at half-integer texel coordinates.
    fn bilinear(&self, uv: [f32; 2]) -> [f32; 3] {
        let fx = uv[0] * self.width as f32 - 0.5;
        let fy = uv[1] * self.height as f32 - 0.5;
        let (x0, y0) = (fx.floor(), fy.floor());
        let (ax, ay) = (fx - x0, fy - y0);
        let wrap = |i: f32, n: usize| (i as i64).rem_euclid(n as i64) as usize;
        let (xa, xb) = (wrap(x0, self.width), wrap(x0 + 1.0, self.width));
        let (ya, yb) = (wrap(y0, self.height), wrap(y0 + 1.0, self.height));
        let p = |x: usize, y: usize| self.rgb[y * self.width + x].map(srgb_to_linear);
        let (p00, p10, p01, p11) = (p(xa, ya), p(xb, ya), p(xa, yb), p(xb, yb));
        std::array::from_fn(|c| {
            let top = p00[c] + (p10[c] - p00[c]) * ax;
            let bottom = p01[c] + (p11[c] - p01[c]) * ax;
            top + (bottom - top) * ay
        })
    }
}
