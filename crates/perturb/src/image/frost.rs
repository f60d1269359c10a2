//! frost: imagecorruptions' `frost` blends a·x + b·F with a randomly cropped frost photo. We ship
//! no photos: F is a procedural texture of ice crystals (six-armed dendrites with side branches,
//! three scales, over mist), generated on the GPU once per seed at 1.25× the frame and cropped at
//! a random offset every frame, as they crop theirs.

use std::f32::consts::{FRAC_PI_3, TAU};

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use super::color_pass::ColorPass;
use super::textures::storage_texture;
use crate::image_f32::RgbF32;
use crate::perturbation::{view, Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::rng::{uniform, RngKey};
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "frost";
const TEXTURE_SHADER: &str = "perturb/image/frost_texture.wgsl";
const SHADER: &str = "perturb/image/frost.wgsl";

/// (image weight, frost weight) per severity (docs/src/perturbations.md §3, imagecorruptions `frost`).
pub const WEIGHTS: [(f32, f32); 5] = [(1.0, 0.4), (0.8, 0.6), (0.7, 0.7), (0.65, 0.7), (0.6, 0.75)];

/// Large crystals' cell size as a fraction of the frame height.
const CELL_FRACTION: f32 = 0.2;

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "frost: blends a procedural ice-crystal texture (per seed, random crop per frame)",
    parameters: |s| {
        let (a, b) = WEIGHTS[s as usize - 1];
        format!("{a}·image + {b}·frost")
    },
    build: |kit| Ok(Box::new(Frost::new(kit)?)),
    between: Between::Interpolated("both weights linear from (1, 0)"),
    explicit: None,
    twin: Twin::Color(twin),
    // The texture's f32 trigonometry (crystal arms) and the blend, each rounded to 8 bits.
    twin_tolerance: Tolerance::ONE_LEVEL,
    uniforms: &[
        UniformLayout {
            rust: rust_layout!(TextureParams { key, cell }),
            wgsl: "Texture",
            shader: TEXTURE_SHADER,
        },
        UniformLayout {
            rust: rust_layout!(FrostParams {
                offset,
                image_weight,
                frost_weight
            }),
            wgsl: "Frost",
            shader: SHADER,
        },
    ],
};

/// (image, frost) weights at the frame's severity, linear between the table's rows from (1, 0).
fn weights(key: &FrameKey) -> (f32, f32) {
    let image = key.interpolate(1.0, &WEIGHTS.map(|(a, _)| a));
    let frost = key.interpolate(0.0, &WEIGHTS.map(|(_, b)| b));
    (image as f32, frost as f32)
}

/// The texture's size for a frame: a quarter larger each way, room for the per-frame crop.
fn texture_size(width: u32, height: u32) -> (u32, u32) {
    (width + width / 4, height + height / 4)
}

fn cell_size(height: u32) -> f32 {
    (CELL_FRACTION * height as f32).max(4.0)
}

/// The frame's crop offset, uniform over the margin.
fn crop_offset(seed: u64, frame: u32, width: u32, height: u32) -> (u32, u32) {
    let rng = RngKey::new(seed, NAME, frame, 1);
    let pick = |margin: u32, i: u32| (rng.uniform_f64([i, 0, 0, 0]) * (margin + 1) as f64) as u32;
    (
        pick(width / 4, 0).min(width / 4),
        pick(height / 4, 1).min(height / 4),
    )
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct TextureParams {
    key: [u32; 4],
    cell: f32,
    _pad: [f32; 3],
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct FrostParams {
    offset: [i32; 2],
    image_weight: f32,
    frost_weight: f32,
}

struct Frost {
    generate: wgpu::ComputePipeline,
    texture_params: wgpu::Buffer,
    texture: wgpu::Texture,
    /// The seed the texture was last generated for.
    generated_for: Option<u64>,
    pass: ColorPass,
}

impl Frost {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        let (w, h) = texture_size(kit.width, kit.height);
        Ok(Self {
            generate: kit.pipeline(TEXTURE_SHADER)?,
            texture_params: kit.uniform_buffer::<TextureParams>("frost texture"),
            texture: storage_texture(kit, "frost texture", wgpu::TextureFormat::Rgba8Unorm, w, h),
            generated_for: None,
            pass: ColorPass::runs::<FrostParams>(kit, SHADER)?,
        })
    }
}

impl GpuPerturbation for Frost {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let texture = view(&self.texture);
        if self.generated_for != Some(key.seed) {
            let params = TextureParams {
                key: RngKey::new(key.seed, NAME, 0, 0).0,
                cell: cell_size(kit.height),
                _pad: [0.0; 3],
            };
            kit.write_uniform(&self.texture_params, &params);
            let bind_group = kit.bind_group(
                &self.generate,
                "frost texture",
                &[
                    wgpu::BindingResource::TextureView(&texture),
                    self.texture_params.as_entire_binding(),
                ],
            );
            let (w, h) = texture_size(kit.width, kit.height);
            kit.dispatch_grid(encoder, &self.generate, &bind_group, "frost texture", w, h);
            self.generated_for = Some(key.seed);
        }
        let (a, b) = weights(key);
        let (ox, oy) = crop_offset(key.seed, key.frame, kit.width, kit.height);
        let params = FrostParams {
            offset: [ox as i32, oy as i32],
            image_weight: a,
            frost_weight: b,
        };
        let extra = [wgpu::BindingResource::TextureView(&texture)];
        self.pass.encode(kit, encoder, frame, &params, &extra);
        Ok(())
    }
}

const SIN60: f32 = 0.866_025_4;
const COT60: f32 = 0.577_350_26;

fn uniform4(key: &RngKey, cell: (i32, i32), layer: u32, index: u32) -> [f32; 4] {
    key.draw([cell.0 as u32, cell.1 as u32, layer, index])
        .map(uniform)
}

/// One dendrite arm (the twin of `arm` in `frost_texture.wgsl`).
fn arm(t: f32, n: f32, length: f32, width: f32, spacing: f32) -> f32 {
    if !(0.0..=length).contains(&t) {
        return 0.0;
    }
    let fade = (1.0 - t / length).sqrt();
    let stem = (-(n * n) / (width * width)).exp();
    let start = t - n.abs() * COT60;
    let nearest = (start / spacing).round_ties_even() * spacing;
    let reach = n.abs() / SIN60;
    let branch_length = 0.45 * (length - nearest);
    let mut branch = 0.0;
    if nearest > 0.0 && reach < branch_length {
        let across = (start - nearest) * SIN60;
        let w = 0.7 * width;
        branch = (-(across * across) / (w * w)).exp() * (1.0 - reach / branch_length).sqrt();
    }
    fade * stem.max(0.8 * branch)
}

fn crystals(key: &RngKey, p: [f32; 2], cell: f32, layer: u32) -> f32 {
    let home = ((p[0] / cell).floor() as i32, (p[1] / cell).floor() as i32);
    let mut best = 0.0f32;
    for dy in -1..=1 {
        for dx in -1..=1 {
            let c = (home.0 + dx, home.1 + dy);
            let r = uniform4(key, c, layer, 0);
            let nucleus = [
                (c.0 as f32 + 0.15 + 0.7 * r[0]) * cell,
                (c.1 as f32 + 0.15 + 0.7 * r[1]) * cell,
            ];
            let d = [p[0] - nucleus[0], p[1] - nucleus[1]];
            let length = cell * (0.55 + 0.6 * r[3]);
            if d[0] * d[0] + d[1] * d[1] > length * length {
                continue;
            }
            let width = (0.018 * cell).max(0.9);
            let spacing = 0.12 * length;
            for k in 0..6u32 {
                let a = uniform4(key, c, layer, k + 1);
                let angle = TAU * r[2] + k as f32 * FRAC_PI_3 + 0.35 * (a[0] - 0.5);
                let u = [angle.cos(), angle.sin()];
                let t = d[0] * u[0] + d[1] * u[1];
                let n = u[0] * d[1] - u[1] * d[0];
                best = best.max(arm(t, n, length * (0.25 + 0.75 * a[1]), width, spacing));
            }
        }
    }
    best
}

fn mist(key: &RngKey, p: [f32; 2], cell: f32) -> f32 {
    let (mut sum, mut scale, mut weight) = (0.0f32, 2.0 * cell, 0.5f32);
    for octave in 0..4u32 {
        let q = [p[0] / scale, p[1] / scale];
        let i = (q[0].floor() as i32, q[1].floor() as i32);
        let f = [q[0] - q[0].floor(), q[1] - q[1].floor()];
        let s = f.map(|f| f * f * (3.0 - 2.0 * f));
        let v = |dx, dy| uniform4(key, (i.0 + dx, i.1 + dy), 10 + octave, 0)[0];
        let mix = |a: f32, b: f32, t: f32| a * (1.0 - t) + b * t;
        sum += weight
            * mix(
                mix(v(0, 0), v(1, 0), s[0]),
                mix(v(0, 1), v(1, 1), s[0]),
                s[1],
            );
        scale *= 0.5;
        weight *= 0.5;
    }
    sum / 0.9375
}

/// The frost texture for `seed` (the twin of `frost_texture.wgsl`, stored as 8 bits).
pub fn frost_texture(seed: u64, width: u32, height: u32) -> RgbF32 {
    let key = RngKey::new(seed, NAME, 0, 0);
    let (w, h) = texture_size(width, height);
    let cell = cell_size(height);
    let mut out = RgbF32::new(w, h);
    for y in 0..h {
        for x in 0..w {
            let p = [x as f32 + 0.5, y as f32 + 0.5];
            let large = crystals(&key, p, cell, 0);
            let small = crystals(&key, p, cell / 3.0, 1);
            let tiny = crystals(&key, p, cell / 8.0, 2);
            let haze = mist(&key, p, cell);
            let ice = (large.max(0.75 * small).max(0.5 * tiny) + 0.35 * haze - 0.1).clamp(0.0, 1.0);
            let glass = [0.42f32, 0.52, 0.60].map(|c| c * (0.75 + 0.5 * haze));
            let white = [0.93f32, 0.96, 1.0];
            let i = out.index(x, y);
            out.data[i] = std::array::from_fn(|c| {
                let v = glass[c] * (1.0 - ice) + white[c] * ice;
                (v.clamp(0.0, 1.0) * 255.0).round() / 255.0
            });
        }
    }
    out
}

/// CPU twin of frost.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let (a, b) = weights(key);
    let ice = frost_texture(key.seed, image.width, image.height);
    let (ox, oy) = crop_offset(key.seed, key.frame, image.width, image.height);
    let mut out = image.clone();
    for y in 0..image.height {
        for x in 0..image.width {
            let f = ice.at(x + ox, y + oy);
            let i = out.index(x, y);
            let c = image.data[i];
            out.data[i] = std::array::from_fn(|k| {
                crate::image_f32::truncate8(a * c[k] + b * f[k]) as f32 / 255.0
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn texture_is_pale_blue_ice_with_structure() {
        // Mostly white-blue (blue ≥ green ≥ red on average, bright), with crisp crystal lines:
        // a good share of pixels far brighter than the mist around them.
        let ice = frost_texture(4, 160, 120);
        let n = ice.data.len() as f32;
        let mean: [f32; 3] =
            std::array::from_fn(|c| ice.data.iter().map(|p| p[c]).sum::<f32>() / n);
        assert!(mean[2] >= mean[1] && mean[1] >= mean[0], "{mean:?}");
        assert!((0.45..0.9).contains(&mean[1]), "{mean:?}");
        let bright = ice.data.iter().filter(|p| p[1] > 0.85).count() as f32 / n;
        assert!((0.03..0.6).contains(&bright), "crystal share {bright}");
        // Another seed grows other crystals.
        assert_ne!(frost_texture(5, 160, 120).data, ice.data);
    }

    #[test]
    fn crop_moves_per_frame_within_the_margin() {
        let offsets: Vec<_> = (0..8).map(|f| crop_offset(1, f, 160, 120)).collect();
        assert!(offsets.iter().all(|&(x, y)| x <= 40 && y <= 30));
        assert!(offsets.windows(2).any(|w| w[0] != w[1]));
    }
}
