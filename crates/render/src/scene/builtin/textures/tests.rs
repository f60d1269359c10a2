use super::*;

const ALL: [Pattern; 25] = [
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
const TILING: usize = 15;

/// Least standard deviation of luma (0–1) for a texture to count as detailed, not blank.
const MIN_LUMA_STD: f32 = 0.04;

fn luma(t: &Texture, x: u32, y: u32) -> f32 {
    let i = 4 * (y * t.width + x) as usize;
    (0.299 * t.rgba[i] as f32 + 0.587 * t.rgba[i + 1] as f32 + 0.114 * t.rgba[i + 2] as f32) / 255.0
}

#[test]
fn every_pattern_has_detail_and_is_deterministic() {
    let mut failures = Vec::new();
    for (k, pattern) in ALL.into_iter().enumerate() {
        for seed in [1, 2] {
            let spec = TextureSpec { pattern, seed };
            let t = spec.generate();
            assert_eq!(t.rgba.len(), (TEXTURE_SIZE * TEXTURE_SIZE * 4) as usize);
            let values: Vec<f32> = (0..TEXTURE_SIZE * TEXTURE_SIZE)
                .map(|i| luma(&t, i % TEXTURE_SIZE, i / TEXTURE_SIZE))
                .collect();
            let mean = values.iter().sum::<f32>() / values.len() as f32;
            let std = (values.iter().map(|v| (v - mean).powi(2)).sum::<f32>()
                / values.len() as f32)
                .sqrt();
            if std <= MIN_LUMA_STD || !(0.1..0.95).contains(&mean) {
                failures.push(format!(
                    "{pattern:?} seed {seed}: luma mean {mean:.3}, std {std:.3}"
                ));
            }
            if k < 3 && seed == 1 {
                assert_eq!(t, spec.generate(), "{pattern:?} is not deterministic");
            }
        }
    }
    assert!(
        failures.is_empty(),
        "blank or badly exposed textures:\n{}",
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
