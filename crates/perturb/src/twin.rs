//! The CPU twin of each catalogue entry, reached through one signature: the oracle its GPU pass
//! is tested against (`catalogue_tests.rs`), and a CPU reference for callers without a GPU pass
//! at hand (the viewer's side-by-side view, the Python package).

use rslam_core::{DepthImage, RgbImage};

use crate::image_f32::RgbF32;
use crate::perturbation::FrameKey;

/// A perturbation's CPU twin, in the form its shader's arithmetic takes.
#[derive(Clone, Copy)]
pub enum Twin {
    /// Colour in [0, 1] as the shader reads the `Rgba8Unorm` frame, to colour as the shader
    /// writes it before the texture stores it (truncation to 8 bits, [`RgbF32::to_rgb8`]).
    Color(fn(&RgbF32, &FrameKey) -> RgbF32),
    /// 8-bit colour to 8-bit colour, for passes that compute on integer levels (PIL's
    /// fixed-point resampling in `pixelate`).
    Color8(fn(&RgbImage, &FrameKey) -> RgbImage),
    /// Depth in metres (0 = no measurement) to depth in metres.
    Depth(fn(&DepthImage, &FrameKey) -> DepthImage),
    /// Colour to colour (as [`Twin::Color`]) for a pass whose GPU state buffer carries over from
    /// frame to frame (auto_exposure's controller): `step` transforms one frame and updates
    /// `state` as the GPU pass updates its buffer; `initial` is the state when it is built.
    ColorSequence {
        initial: TwinState,
        /// The names of the state's four values, for the per-frame log of what each frame was
        /// made with.
        fields: [&'static str; 4],
        step: fn(&RgbF32, &FrameKey, &mut TwinState) -> RgbF32,
    },
}

/// The state a [`Twin::ColorSequence`] carries between frames (the GPU buffer's `vec4<f32>`).
pub type TwinState = [f32; 4];

impl Twin {
    /// The twin as it is when its entry is built, to be applied to frames in the order the GPU
    /// pass sees them.
    pub fn start(&self) -> TwinRun {
        let state = match self {
            Twin::ColorSequence { initial, .. } => *initial,
            _ => TwinState::default(),
        };
        TwinRun { twin: *self, state }
    }
}

/// A twin applied frame after frame, with the state a [`Twin::ColorSequence`] carries.
pub struct TwinRun {
    twin: Twin,
    state: TwinState,
}

impl TwinRun {
    /// Transforms the frame in place as the entry's GPU pass does: the colour for an image
    /// corruption, the depth for a depth corruption; the other is left as it is.
    pub fn apply(&mut self, color: &mut RgbImage, depth: &mut DepthImage, key: &FrameKey) {
        match self.twin {
            Twin::Color(twin) => *color = twin(&RgbF32::from_rgb8(color), key).to_rgb8(),
            Twin::Color8(twin) => *color = twin(color, key),
            Twin::Depth(twin) => *depth = twin(depth, key),
            Twin::ColorSequence { step, .. } => {
                *color = step(&RgbF32::from_rgb8(color), key, &mut self.state).to_rgb8()
            }
        }
    }
}

/// How far a GPU pass may be from its twin on the same frame and key.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// Largest difference of an 8-bit colour value.
    pub levels: u8,
    /// Fraction of colour values allowed to differ by more than `levels`.
    pub outliers: f64,
    /// Largest depth difference in metres. Which pixels are invalid (0) must always agree.
    pub metres: f32,
}

impl Tolerance {
    /// Bit for bit: integer arithmetic, or f32 steps that are exact on both sides.
    pub const EXACT: Self = Self {
        levels: 0,
        outliers: 0.0,
        metres: 0.0,
    };

    /// One level: the same f32 formula on the GPU (fused multiply-adds, approximate
    /// transcendentals, another summation order) and in Rust differs in the last bits, which
    /// truncation to 8 bits turns into one level where a value sits on a level boundary.
    pub const ONE_LEVEL: Self = Self {
        levels: 1,
        ..Self::EXACT
    };
}
