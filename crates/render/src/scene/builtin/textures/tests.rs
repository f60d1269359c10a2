use super::*;

const ALL: [Pattern; 28] = [
    Pattern::FloorPlanks,
    Pattern::WoodGrain,
    Pattern::Fabric,
    Pattern::Leather,
    Pattern::OfficeCarpet,
    Pattern::FloorTiles,
    Pattern::Wallpaper,
    Pattern::Plaster,
    Pattern::Brick,
    Pattern::CeilingTiles,
    Pattern::Marble,
    Pattern::BrushedMetal,
    Pattern::Leaves,
    Pattern::Curtain,
    Pattern::Stripes,
    Pattern::Checks,
    Pattern::GarmentPrint,
    Pattern::Pages,
    Pattern::Rug,
    Pattern::Poster,
    Pattern::Painting,
    Pattern::BookSpine,
    Pattern::Cardboard,
    Pattern::Screen,
    Pattern::Whiteboard,
    Pattern::WindowView,
    Pattern::Door,
    Pattern::Keyboard,
];

/// Patterns mapped in metres, which must repeat without a seam.
const TILING: usize = 18;

fn luma(t: &Texture, x: u32, y: u32) -> f32 {
    let i = 4 * (y * t.width + x) as usize;
    (0.299 * t.rgba[i] as f32 + 0.587 * t.rgba[i + 1] as f32 + 0.114 * t.rgba[i + 2] as f32) / 255.0
}

fn lumas(t: &Texture) -> Vec<f32> {
    (0..t.width * t.height)
        .map(|i| luma(t, i % t.width, i / t.width))
        .collect()
}

/// Standard deviation of luma values.
fn luma_spread(values: &[f32]) -> f32 {
    let mean = values.iter().sum::<f32>() / values.len() as f32;
    (values.iter().map(|v| (v - mean).powi(2)).sum::<f32>() / values.len() as f32).sqrt()
}

/// Mean linear luminance and standard deviation of luma.
fn albedo_and_contrast(t: &Texture) -> (f32, f32) {
    use crate::scene::srgb::srgb_to_linear;
    let n = (t.width * t.height) as usize;
    let std = luma_spread(&lumas(t));
    let albedo = t
        .rgba
        .chunks_exact(4)
        .map(|p| {
            0.2126 * srgb_to_linear(p[0])
                + 0.7152 * srgb_to_linear(p[1])
                + 0.0722 * srgb_to_linear(p[2])
        })
        .sum::<f32>()
        / n as f32;
    (albedo, std)
}

#[test]
fn every_pattern_is_in_one_family_of_the_table() {
    for pattern in ALL {
        let homes = FAMILIES
            .iter()
            .filter(|f| f.patterns.contains(&pattern))
            .count();
        assert_eq!(homes, 1, "{pattern:?} is in {homes} families");
    }
}

#[test]
fn every_pattern_keeps_the_albedo_and_contrast_of_its_family_and_is_deterministic() {
    let mut failures = Vec::new();
    for family in &FAMILIES {
        for (k, &pattern) in family.patterns.iter().enumerate() {
            for seed in [1, 2, 3, 4] {
                let spec = TextureSpec { pattern, seed };
                let t = spec.generate();
                assert_eq!(t.rgba.len(), (TEXTURE_SIZE * TEXTURE_SIZE * 4) as usize);
                let (albedo, contrast) = albedo_and_contrast(&t);
                let inside = |v: f32, (lo, hi): (f32, f32)| (lo..=hi).contains(&v);
                if !inside(albedo, family.albedo) || !inside(contrast, family.contrast) {
                    failures.push(format!(
                        "{pattern:?} seed {seed}: albedo {albedo:.3} (table {:?}), luma std {contrast:.3} (table {:?}) — {}",
                        family.albedo, family.contrast, family.name
                    ));
                }
                if k == 0 && seed == 1 {
                    assert_eq!(t, spec.generate(), "{pattern:?} is not deterministic");
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "outside the material table:\n{}",
        failures.join("\n")
    );
}

#[test]
fn tiling_patterns_have_no_seam() {
    let n = TEXTURE_SIZE;
    for pattern in &ALL[..TILING] {
        let t = TextureSpec {
            pattern: *pattern,
            seed: 5,
        }
        .generate();
        let step = |a: (u32, u32), b: (u32, u32)| (luma(&t, a.0, a.1) - luma(&t, b.0, b.1)).abs();
        // The step across the wrap against the mean step across every interior boundary.
        let across = |k: u32| -> f32 {
            (0..n)
                .map(|i| step((k, i), ((k + 1) % n, i)) + step((i, k), (i, (k + 1) % n)))
                .sum()
        };
        let interior = (0..n - 1).map(across).sum::<f32>() / (n - 1) as f32;
        let seam = across(n - 1);
        assert!(
            seam < 2.0 * interior + 0.02 * n as f32,
            "{pattern:?}: seam {seam} vs interior {interior}"
        );
    }
}

/// A camera metered for the room sees daylight three stops brighter: the sky and the sunlit
/// façades clip (without the gain only the clouds would), nothing outside is darker than the
/// room's mid-grey, and the glazing and trees still vary.
#[test]
fn the_view_through_a_window_is_exposed_for_the_room_clipped_sky_and_bright_texture() {
    let n = (TEXTURE_SIZE * TEXTURE_SIZE) as f32;
    for seed in [1, 2, 3, 4] {
        let t = TextureSpec {
            pattern: Pattern::WindowView,
            seed,
        }
        .generate();
        let white = t
            .rgba
            .chunks_exact(4)
            .filter(|p| p[..3] == [255; 3])
            .count() as f32
            / n;
        let unclipped: Vec<f32> = lumas(&t).into_iter().filter(|&l| l < 1.0).collect();
        let darkest = unclipped.iter().copied().fold(1.0, f32::min);
        let spread = luma_spread(&unclipped);
        assert!(
            white > 0.6,
            "seed {seed}: only {white:.2} of the view clips"
        );
        assert!(
            darkest > 0.45,
            "seed {seed}: a texel outside at luma {darkest:.2}"
        );
        assert!(
            spread > 0.03,
            "seed {seed}: what does not clip has a luma spread of {spread:.3}"
        );
    }
}

/// Standard deviation of luma about each `block`-texel square's own mean: the texture's detail
/// finer than the block, which a camera a few metres away averages into a pixel or two.
fn fine_contrast(t: &Texture, block: u32) -> f32 {
    let mut deviations = Vec::with_capacity((t.width * t.height) as usize);
    for by in (0..t.height / block).map(|k| k * block) {
        for bx in (0..t.width / block).map(|k| k * block) {
            let cell: Vec<f32> = (0..block * block)
                .map(|i| luma(t, bx + i % block, by + i / block))
                .collect();
            let mean = cell.iter().sum::<f32>() / cell.len() as f32;
            deviations.extend(cell.iter().map(|l| l - mean));
        }
    }
    luma_spread(&deviations)
}

/// Real leather's grain is a millimetre or so across and its relief shows faintly, so within a
/// centimetre the texture moves luma by a few grey levels (2.5–4.9 on seeds 1–4), not the 7.9–15.6
/// of the pitted, crinkled leather that once covered office1's chairs and office3's sofa with
/// strong corners.
#[test]
fn leather_grain_is_faint_within_a_centimetre() {
    // Leather repeats every half metre (`Style::leather`).
    let texels_per_cm = TEXTURE_SIZE / 50;
    for seed in [1, 2, 3, 4] {
        let t = TextureSpec {
            pattern: Pattern::Leather,
            seed,
        }
        .generate();
        let fine = fine_contrast(&t, texels_per_cm);
        assert!(
            fine < 0.025,
            "seed {seed}: leather varies by {:.1} grey levels within a centimetre",
            fine * 255.0
        );
    }
}
