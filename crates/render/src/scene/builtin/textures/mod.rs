//! Procedural textures: one function per pattern, each a pure function of (u, v) and a seed.
//! Patterns mapped in metres tile seamlessly; "fit" patterns (pictures, screens, doors) cover one
//! face. Colours are sRGB in [0, 1]; the scene's baked lighting multiplies them.

pub mod cache;
#[cfg(test)]
mod families;
mod garments;
mod noise;
mod prints;
mod surfaces;
mod textiles;
mod wood;

use rayon::prelude::*;

use crate::Texture;
pub use noise::{hsv, Rgb};

/// Side of every procedural texture, texels. At the Replica camera (f = 600) a texel of a 1.5 m
/// tile is one pixel at 2.6 m.
pub const TEXTURE_SIZE: u32 = 512;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Pattern {
    // Tiling, mapped in metres.
    FloorPlanks,
    WoodGrain,
    Fabric,
    Leather,
    OfficeCarpet,
    Stripes,
    Checks,
    GarmentPrint,
    FloorTiles,
    Wallpaper,
    Plaster,
    Brick,
    CeilingTiles,
    Marble,
    BrushedMetal,
    Leaves,
    Curtain,
    Pages,
    // Fitted to one face.
    Rug,
    Poster,
    Painting,
    BookSpine,
    Cardboard,
    Screen,
    Whiteboard,
    WindowView,
    Door,
    Keyboard,
}

impl Pattern {
    fn paint(self, seed: u64, u: f32, v: f32) -> Rgb {
        use Pattern::*;
        match self {
            FloorPlanks => wood::floor_planks(seed, u, v),
            WoodGrain => wood::grain(seed, u, v),
            Door => wood::door(seed, u, v),
            Fabric => textiles::fabric(seed, u, v),
            Leather => textiles::leather(seed, u, v),
            Stripes => garments::stripes(seed, u, v),
            Checks => garments::checks(seed, u, v),
            GarmentPrint => garments::print(seed, u, v),
            OfficeCarpet => textiles::office_carpet(seed, u, v),
            Curtain => textiles::curtain(seed, u, v),
            Rug => textiles::rug(seed, u, v),
            FloorTiles => surfaces::floor_tiles(seed, u, v),
            Wallpaper => surfaces::wallpaper(seed, u, v),
            Plaster => surfaces::plaster(seed, u, v),
            Brick => surfaces::brick(seed, u, v),
            CeilingTiles => surfaces::ceiling_tiles(seed, u, v),
            Marble => surfaces::marble(seed, u, v),
            BrushedMetal => surfaces::brushed_metal(seed, u, v),
            Leaves => surfaces::leaves(seed, u, v),
            Pages => prints::pages(seed, u, v),
            Poster => prints::poster(seed, u, v),
            Painting => prints::painting(seed, u, v),
            BookSpine => prints::book_spine(seed, u, v),
            Cardboard => prints::cardboard(seed, u, v),
            Screen => prints::screen(seed, u, v),
            Whiteboard => prints::whiteboard(seed, u, v),
            WindowView => prints::window_view(seed, u, v),
            Keyboard => prints::keyboard(seed, u, v),
        }
    }
}

/// A pattern and the seed that picks its palette and layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TextureSpec {
    pub pattern: Pattern,
    pub seed: u64,
}

impl TextureSpec {
    pub fn generate(&self) -> Texture {
        let n = TEXTURE_SIZE as usize;
        let mut rgba = vec![255u8; n * n * 4];
        rgba.par_chunks_mut(n * 4).enumerate().for_each(|(y, row)| {
            let v = (y as f32 + 0.5) / n as f32;
            for (x, px) in row.chunks_exact_mut(4).enumerate() {
                let u = (x as f32 + 0.5) / n as f32;
                let c = self.pattern.paint(self.seed, u, v);
                for (dst, src) in px.iter_mut().zip(c) {
                    *dst = (src.clamp(0.0, 1.0) * 255.0).round() as u8;
                }
            }
        });
        Texture {
            width: TEXTURE_SIZE,
            height: TEXTURE_SIZE,
            rgba,
        }
    }
}

#[cfg(test)]
use families::FAMILIES;
#[cfg(test)]
mod tests;
