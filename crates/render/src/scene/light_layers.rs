//! A scene's light kept as layers, one per light: the linear colour each lamp (and the daylight
//! of the windows) gives every vertex at full strength, exposure included. A frame's light state
//! is one RGB weight per layer; the rasterizer mixes the layers with it on the GPU
//! (`shaders/render/mesh.wgsl`), and [`LightLayers::mixed`] is that mix on the CPU. With every
//! weight 1 the mix is the baked vertex colour up to its 8-bit rounding; scenes without layers
//! (user meshes) keep only their baked colours.

use serde::Serialize;

use super::srgb::linear_to_srgb;
use super::Mesh;

/// The most layers a scene may have: the rasterizer's uniform holds this many weights.
pub const MAX_LIGHT_LAYERS: usize = 8;

/// What a layer's light comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LightKind {
    /// A ceiling lamp (its light on the room and its own glowing fixture).
    Lamp,
    /// Daylight through every window (and the view outside them).
    Daylight,
}

#[derive(Clone, Debug, PartialEq)]
pub struct LightLayers {
    pub kinds: Vec<LightKind>,
    /// Linear RGB per vertex and layer, vertex-major: `colours[v * kinds.len() + l]`.
    pub colours: Vec<[f32; 3]>,
}

impl LightLayers {
    /// Names of the layers as the manifest and messages give them: `lamp0`, `lamp1`, …, `daylight`.
    pub fn names(&self) -> Vec<String> {
        let mut lamps = 0;
        self.kinds
            .iter()
            .map(|kind| match kind {
                LightKind::Lamp => {
                    lamps += 1;
                    format!("lamp{}", lamps - 1)
                }
                LightKind::Daylight => "daylight".to_string(),
            })
            .collect()
    }

    /// The linear colour of `vertex` under `weights` (one RGB weight per layer), clamped to
    /// [0, 1] as the baked 8-bit colours are.
    pub fn mixed(&self, vertex: usize, weights: &[[f32; 3]]) -> [f32; 3] {
        let count = self.kinds.len();
        let mut sum = [0.0f32; 3];
        for (colour, weight) in self.colours[vertex * count..(vertex + 1) * count]
            .iter()
            .zip(weights)
        {
            for c in 0..3 {
                sum[c] += colour[c] * weight[c];
            }
        }
        sum.map(|c| c.clamp(0.0, 1.0))
    }

    /// `mesh` with its vertex colours mixed on the CPU under `weights` (8-bit sRGB, as baked):
    /// what the GPU's mix draws, up to that rounding.
    pub fn lit_mesh(&self, mesh: &Mesh, weights: &[[f32; 3]]) -> Mesh {
        let mut lit = mesh.clone();
        for (i, v) in lit.vertices.iter_mut().enumerate() {
            let [r, g, b] = self.mixed(i, weights).map(linear_to_srgb);
            v.color = [r, g, b, 255];
        }
        lit
    }
}
