//! The parameter table of the material families: the mean albedo (linear luminance) and the
//! texture contrast (standard deviation of luma) each family's patterns must stay within.
//!
//! Albedo ranges follow the reflectances of interior surfaces in the IES Lighting Handbook (10th
//! ed., "reflectances of building materials" and the recommended room-surface reflectances:
//! ceilings 0.7–0.9, walls 0.5–0.7, floors 0.2–0.4, furniture 0.25–0.45), and paint makers'
//! light-reflectance values (LRV: whites and off-whites 0.7–0.9). The contrast ranges say how
//! much a surface varies across itself: painted walls and ceilings are nearly uniform (a per cent
//! or two), wood and textiles show their grain or weave, prints are anything. Patterned clothes
//! (the tops walkers wear, `actors`) are two colours of everyday clothes, navy and white to tan
//! and brown: their luma varies as much as a print's, and black cloth reflects a per cent or
//! two.

use super::Pattern::{self, *};

pub struct Family {
    pub name: &'static str,
    pub patterns: &'static [Pattern],
    /// Mean linear luminance, least and most.
    pub albedo: (f32, f32),
    /// Standard deviation of luma (sRGB, 0–1), least and most.
    pub contrast: (f32, f32),
}

pub const FAMILIES: [Family; 10] = [
    Family {
        name: "painted walls and ceilings",
        patterns: &[Plaster, Wallpaper],
        albedo: (0.55, 0.85),
        contrast: (0.002, 0.03),
    },
    Family {
        name: "acoustic ceiling tiles",
        patterns: &[CeilingTiles],
        albedo: (0.6, 0.85),
        contrast: (0.005, 0.05),
    },
    Family {
        name: "wood (floors, furniture, doors)",
        patterns: &[FloorPlanks, WoodGrain, Door],
        albedo: (0.08, 0.5),
        contrast: (0.02, 0.12),
    },
    Family {
        name: "carpet and rugs",
        patterns: &[OfficeCarpet, Rug],
        albedo: (0.04, 0.35),
        contrast: (0.01, 0.2),
    },
    Family {
        name: "upholstery, leather, curtains",
        patterns: &[Fabric, Leather, Curtain],
        albedo: (0.03, 0.5),
        contrast: (0.01, 0.15),
    },
    Family {
        name: "patterned clothes",
        patterns: &[Stripes, Checks, GarmentPrint],
        albedo: (0.01, 0.75),
        contrast: (0.05, 0.45),
    },
    Family {
        name: "tiles and stone",
        patterns: &[FloorTiles, Marble],
        albedo: (0.05, 0.75),
        contrast: (0.02, 0.2),
    },
    Family {
        name: "brick",
        patterns: &[Brick],
        albedo: (0.08, 0.3),
        contrast: (0.03, 0.18),
    },
    Family {
        name: "metal and plants",
        patterns: &[BrushedMetal, Leaves],
        albedo: (0.02, 0.6),
        contrast: (0.01, 0.25),
    },
    Family {
        name: "prints, screens, books, windows",
        patterns: &[
            Pages, Poster, Painting, BookSpine, Cardboard, Screen, Whiteboard, WindowView, Keyboard,
        ],
        albedo: (0.02, 0.9),
        contrast: (0.02, 0.45),
    },
];
