//! The bake: direct light from lamps and windows through shadow rays, then the light reflected by
//! the room's surfaces, gathered with cosine-weighted rays from every vertex. One gather is the
//! first bounce; the later bounces of a closed room are a geometric series in its mean albedo ρ̄
//! (each bounce returns about ρ̄ of the previous one), so the gathered light is scaled by
//! 1 / (1 − ρ̄) instead of being traced again.
//!
//! Irradiance is linear in the lights, so the bake also keeps each light's share as a layer of
//! its own ([`Baked::layers`]: each lamp, then the daylight of all windows), for light items
//! that switch lamps or drift the daylight per frame. The total is summed exactly as without
//! layers, so the built-in scenes' colours do not change.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::sampling::{cosine_hemisphere, disc, square};
use super::{cache, Lighting, LAMP_RADIUS};
use crate::raycast::RayCaster;
use crate::scene::builtin::rng::{hash3, unit};
use crate::Mesh;

/// Shadow-ray samples per lamp disc and per window pane, and gather rays per vertex.
const LAMP_SAMPLES: u32 = 8;
const WINDOW_SAMPLES: u32 = 16;
const GATHER_RAYS: u32 = 64;
/// Radiant intensity of a lamp (per steradian) and radiance of a window pane, in one arbitrary
/// unit; their ratio and colours are what matters: warm bulbs, cool daylight.
const LAMP_INTENSITY: Vec3 = Vec3::new(1.05, 0.96, 0.82);
const WINDOW_RADIANCE: Vec3 = Vec3::new(0.55, 0.6, 0.68);
/// A lamp's irradiance stops growing closer than this (metres): no surface is brighter than the
/// bulb's own diffuser.
const LAMP_NEAR: f32 = 0.3;
/// Shadow and gather rays start this far off the surface (metres), clear of the vertex's own faces.
const RAY_OFFSET: f32 = 2e-3;
/// Seed of the per-vertex sample rotations ("light" in ASCII).
const SAMPLING_SEED: u64 = 0x006c_6967_6874;
/// Bumped whenever the bake's result would change for the same input: it names the cache entry.
const BAKE_VERSION: u32 = 2;

/// What the bake reads, one entry per vertex of `mesh`.
pub struct BakeInput<'a> {
    pub mesh: &'a Mesh,
    /// Unit shading normals.
    pub normals: &'a [Vec3],
    /// Linear albedo (tint × the mean of the texture).
    pub albedo: &'a [Vec3],
    /// Vertices that glow (lamp shades, the view through windows): not lit, and they reflect
    /// nothing back (their light is the lamps' and windows' own).
    pub emissive: &'a [bool],
    pub lighting: &'a Lighting,
}

/// The irradiance at every vertex (linear, arbitrary unit) and each light's share of it.
#[derive(Clone, Debug, PartialEq)]
pub struct Baked {
    pub total: Vec<Vec3>,
    /// One per light, [`Lighting::layer_count`] of them: each lamp's, then the windows'
    /// together. Their sum is `total` up to rounding.
    pub layers: Vec<Vec<Vec3>>,
}

/// The bake of `input`, from the cache or baked now.
pub fn bake(input: &BakeInput) -> Baked {
    let Some(folder) = cache::folder() else {
        return bake_now(input);
    };
    let key = cache_key(input);
    let (count, layers) = (input.mesh.vertices.len(), input.lighting.layer_count());
    if let Some(baked) = cache::load(&folder, &key, count, layers) {
        return baked;
    }
    let baked = bake_now(input);
    cache::store(&folder, &key, &baked);
    baked
}

/// Light of every layer at one vertex, and their total.
struct Shares {
    total: Vec3,
    layers: Vec<Vec3>,
}

fn bake_now(input: &BakeInput) -> Baked {
    let caster = RayCaster::from_mesh(input.mesh);
    let positions: Vec<Vec3> = input
        .mesh
        .vertices
        .iter()
        .map(|v| Vec3::from(v.position))
        .collect();
    let layer_count = input.lighting.layer_count();
    let dark = || Shares {
        total: Vec3::ZERO,
        layers: vec![Vec3::ZERO; layer_count],
    };
    let direct: Vec<Shares> = (0..positions.len())
        .into_par_iter()
        .map(|i| {
            if input.emissive[i] {
                return dark();
            }
            let origin = positions[i] + input.normals[i] * RAY_OFFSET;
            direct_light(&caster, input.lighting, origin, input.normals[i], i as u32)
        })
        .collect();
    let reflected: Vec<Shares> = direct
        .iter()
        .zip(input.albedo)
        .zip(input.emissive)
        .map(|((e, &a), &glows)| match glows {
            true => dark(),
            false => Shares {
                total: e.total * a,
                layers: e.layers.iter().map(|&l| l * a).collect(),
            },
        })
        .collect();
    let bounces = 1.0 / (1.0 - mean_albedo(input)).max(0.2);
    let shares: Vec<Shares> = (0..positions.len())
        .into_par_iter()
        .map(|i| {
            if input.emissive[i] {
                return dark();
            }
            let origin = positions[i] + input.normals[i] * RAY_OFFSET;
            let gathered = gather(&caster, input.mesh, &reflected, origin, input.normals[i], i);
            Shares {
                total: direct[i].total + gathered.total * bounces,
                layers: (direct[i].layers.iter().zip(&gathered.layers))
                    .map(|(&d, &g)| d + g * bounces)
                    .collect(),
            }
        })
        .collect();
    Baked {
        total: shares.iter().map(|s| s.total).collect(),
        layers: (0..layer_count)
            .map(|l| shares.iter().map(|s| s.layers[l]).collect())
            .collect(),
    }
}

/// Per-vertex rotation of the sample patterns, one per purpose.
fn rotation(vertex: u32, purpose: i64) -> Vec2 {
    let h = |k| unit(hash3(SAMPLING_SEED, vertex as i64, purpose, k));
    Vec2::new(h(0), h(1))
}

fn visible(caster: &RayCaster, from: Vec3, to: Vec3) -> bool {
    let d = to - from;
    let dist = d.length();
    caster
        .cast_within(from, d / dist, dist - RAY_OFFSET)
        .is_none()
}

fn direct_light(caster: &RayCaster, l: &Lighting, p: Vec3, n: Vec3, vertex: u32) -> Shares {
    let mut e = Vec3::ZERO;
    let mut layers = vec![Vec3::ZERO; l.layer_count()];
    for (li, lamp) in l.lamps.iter().enumerate() {
        let rot = rotation(vertex, 2 * li as i64);
        let mut sum = 0.0;
        for k in 0..LAMP_SAMPLES {
            let q = *lamp + (disc(square(k, LAMP_SAMPLES, rot)) * LAMP_RADIUS).extend(0.0);
            let d = q - p;
            let cos = n.dot(d.normalize());
            if cos > 0.0 && visible(caster, p, q) {
                sum += cos / d.length_squared().max(LAMP_NEAR * LAMP_NEAR);
            }
        }
        let share = LAMP_INTENSITY * sum / LAMP_SAMPLES as f32;
        e += share;
        layers[li] = share;
    }
    for (wi, w) in l.windows.iter().enumerate() {
        let rot = rotation(vertex, 2 * wi as i64 + 1);
        let wn = w.normal();
        let mut sum = 0.0;
        for k in 0..WINDOW_SAMPLES {
            let s = square(k, WINDOW_SAMPLES, rot);
            let q = w.corner + w.right * s.x + w.down * s.y;
            let d = q - p;
            let dir = d.normalize();
            let (cos_p, cos_w) = (n.dot(dir), wn.dot(-dir));
            if cos_p > 0.0 && cos_w > 0.0 && visible(caster, p, q) {
                sum += cos_p * cos_w / d.length_squared().max(0.01);
            }
        }
        let share = WINDOW_RADIANCE * sum * w.area() / WINDOW_SAMPLES as f32;
        e += share;
        layers[l.lamps.len()] += share;
    }
    Shares { total: e, layers }
}

/// Irradiance from the surfaces around: with cosine-weighted rays it is the mean outgoing
/// radiance × π, i.e. the mean of albedo × irradiance at the hit points.
fn gather(
    caster: &RayCaster,
    mesh: &Mesh,
    reflected: &[Shares],
    p: Vec3,
    n: Vec3,
    vertex: usize,
) -> Shares {
    let rot = rotation(vertex as u32, -1);
    let mut sum = Vec3::ZERO;
    let mut layers = vec![Vec3::ZERO; reflected.first().map_or(0, |r| r.layers.len())];
    for k in 0..GATHER_RAYS {
        let dir = cosine_hemisphere(n, square(k, GATHER_RAYS, rot));
        let Some(hit) = caster.cast(p, dir) else {
            continue;
        };
        if caster.triangle_normal(hit.triangle).dot(dir) > 0.0 {
            continue; // the back of a face: the inside of something closed
        }
        let t = hit.triangle as usize * 3;
        for (c, &b) in hit.barycentrics.iter().enumerate() {
            let corner = &reflected[mesh.indices[t + c] as usize];
            sum += corner.total * b;
            for (layer, &r) in layers.iter_mut().zip(&corner.layers) {
                *layer += r * b;
            }
        }
    }
    let rays = GATHER_RAYS as f32;
    Shares {
        total: sum / rays,
        layers: layers.into_iter().map(|l| l / rays).collect(),
    }
}

/// Mean albedo (luminance) of the lit vertices.
fn mean_albedo(input: &BakeInput) -> f32 {
    let lum = |a: Vec3| a.dot(Vec3::new(0.2126, 0.7152, 0.0722));
    let (sum, count) = input
        .albedo
        .iter()
        .zip(input.emissive)
        .filter(|(_, &g)| !g)
        .fold((0.0, 0usize), |(s, c), (&a, _)| (s + lum(a), c + 1));
    if count == 0 {
        0.0
    } else {
        sum / count as f32
    }
}

fn cache_key(input: &BakeInput) -> blake3::Hash {
    let mut h = blake3::Hasher::new();
    h.update(&BAKE_VERSION.to_le_bytes());
    let f = |h: &mut blake3::Hasher, v: Vec3| {
        for c in v.to_array() {
            h.update(&c.to_le_bytes());
        }
    };
    for v in &input.mesh.vertices {
        f(&mut h, Vec3::from(v.position));
    }
    for &i in &input.mesh.indices {
        h.update(&i.to_le_bytes());
    }
    for ((&n, &a), &g) in input.normals.iter().zip(input.albedo).zip(input.emissive) {
        f(&mut h, n);
        f(&mut h, a);
        h.update(&[g as u8]);
    }
    for &lamp in &input.lighting.lamps {
        f(&mut h, lamp);
    }
    for w in &input.lighting.windows {
        f(&mut h, w.corner);
        f(&mut h, w.right);
        f(&mut h, w.down);
    }
    h.finalize()
}

#[cfg(test)]
mod tests;
