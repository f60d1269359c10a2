//! Surface colour at a hit: vertex colour × texture, the texture filtered the way the rasterizer's
//! sampler does (repeat wrap, bilinear within a level, linear between mip levels, the level chosen
//! from the uv derivatives across the pixel), on a mip chain box-filtered in linear light.

use super::Hit;
use crate::scene::srgb::{linear_to_srgb, srgb_to_linear};
use crate::{Mesh, Texture, Vertex};

/// How uv changes from one pixel to the next, in texture repeats per pixel: what a fragment
/// shader's implicit derivatives `dpdx(uv)`, `dpdy(uv)` give, and what picks the mip level.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct UvDerivatives {
    /// uv one pixel to the right minus uv here.
    pub dx: [f32; 2],
    /// uv one pixel down minus uv here.
    pub dy: [f32; 2],
}

impl UvDerivatives {
    /// No change across the pixel: the full-resolution level (magnification).
    pub const ZERO: Self = Self {
        dx: [0.0; 2],
        dy: [0.0; 2],
    };
}

pub(super) struct Shading {
    vertices: Vec<Vertex>,
    indices: Vec<u32>,
    textures: Vec<MipChain>,
}

struct Level {
    width: usize,
    height: usize,
    /// sRGB, as the rasterizer's texture stores every level; filtered in linear light.
    rgb: Vec<[u8; 3]>,
}

struct MipChain {
    levels: Vec<Level>,
}

impl Shading {
    pub(super) fn new(mesh: &Mesh, textures: &[Texture]) -> Self {
        Self {
            vertices: mesh.vertices.clone(),
            indices: mesh.indices.clone(),
            textures: textures.iter().map(MipChain::new).collect(),
        }
    }

    fn corners(&self, triangle: u32) -> [Vertex; 3] {
        let t = triangle as usize;
        [0, 1, 2].map(|i| self.vertices[self.indices[3 * t + i] as usize])
    }

    /// Texture layer of a triangle (the first vertex's, as the rasterizer's flat interpolation).
    pub(super) fn layer(&self, triangle: u32) -> u32 {
        self.corners(triangle)[0].layer
    }

    /// uv at barycentric weights `b` of `triangle`; `b` may lie outside the triangle
    /// (extrapolation, as a GPU does for the helper pixels of a 2×2 quad).
    pub(super) fn uv(&self, triangle: u32, b: [f32; 3]) -> [f32; 2] {
        let v = self.corners(triangle);
        std::array::from_fn(|c| b[0] * v[0].uv[c] + b[1] * v[1].uv[c] + b[2] * v[2].uv[c])
    }

    pub(super) fn color_at(&self, hit: &Hit, d: &UvDerivatives) -> [u8; 3] {
        let v = self.corners(hit.triangle);
        let b = hit.barycentrics;
        let uv = self.uv(hit.triangle, b);
        // Vertex colours are decoded per vertex, then interpolated (as the vertex shader does).
        let vertex_rgb: [f32; 3] = std::array::from_fn(|c| {
            (0..3)
                .map(|k| b[k] * srgb_to_linear(v[k].color[c]))
                .sum::<f32>()
        });
        let texel = match self.textures.get(v[0].layer as usize) {
            Some(chain) => chain.sample(uv, d),
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

    /// Level of detail λ = log2 ρ, ρ the longer of the two pixel steps measured in level-0
    /// texels (Vulkan spec, "Scale Factor Operation, Level-of-Detail Operation"); −∞ for no change.
    fn lod(&self, d: &UvDerivatives) -> f32 {
        let (w, h) = (self.levels[0].width as f32, self.levels[0].height as f32);
        let rho = |s: [f32; 2]| (s[0] * w).hypot(s[1] * h);
        rho(d.dx).max(rho(d.dy)).log2()
    }

    /// Trilinear: bilinear in the two levels around λ, blended linearly by its fraction; level 0
    /// when magnified (λ ≤ 0), the last level beyond it.
    fn sample(&self, uv: [f32; 2], d: &UvDerivatives) -> [f32; 3] {
        let lod = self.lod(d);
        let last = self.levels.len() - 1;
        if lod.is_nan() || lod <= 0.0 {
            return self.levels[0].bilinear(uv);
        }
        if lod >= last as f32 {
            return self.levels[last].bilinear(uv);
        }
        let fine = lod.floor();
        let a = self.levels[fine as usize].bilinear(uv);
        let b = self.levels[fine as usize + 1].bilinear(uv);
        let t = lod - fine;
        std::array::from_fn(|c| a[c] + (b[c] - a[c]) * t)
    }
}

impl Level {
    /// 2×2 box filter in linear light, stored as sRGB; `None` once 1×1.
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
