//! sRGB ⇄ linear-light conversions (IEC 61966-2-1) through lookup tables.

use std::sync::LazyLock;

/// Entries of the linear → sRGB table; fine enough that a round trip of every u8 is exact.
const ENCODE_STEPS: usize = 4096;

static DECODE: LazyLock<[f32; 256]> = LazyLock::new(|| {
    std::array::from_fn(|v| {
        let c = v as f32 / 255.0;
        if c <= 0.04045 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    })
});

static ENCODE: LazyLock<Vec<u8>> = LazyLock::new(|| {
    (0..=ENCODE_STEPS)
        .map(|i| {
            let c = i as f32 / ENCODE_STEPS as f32;
            let s = if c <= 0.003_130_8 {
                c * 12.92
            } else {
                1.055 * c.powf(1.0 / 2.4) - 0.055
            };
            (s * 255.0).round() as u8
        })
        .collect()
});

pub fn srgb_to_linear(v: u8) -> f32 {
    DECODE[v as usize]
}

/// An sRGB value in [0, 1] (clamped) as linear light, through its nearest byte.
pub fn unit_srgb_to_linear(c: f32) -> f32 {
    srgb_to_linear((c.clamp(0.0, 1.0) * 255.0).round() as u8)
}

pub fn linear_to_srgb(c: f32) -> u8 {
    ENCODE[(c.clamp(0.0, 1.0) * ENCODE_STEPS as f32).round() as usize]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_byte_survives_a_round_trip() {
        for v in 0..=255u8 {
            assert_eq!(linear_to_srgb(srgb_to_linear(v)), v);
        }
        assert_eq!(srgb_to_linear(255), 1.0);
        assert!(
            (srgb_to_linear(128) - 0.2158).abs() < 1e-3,
            "mid grey is ~21.6 % linear"
        );
    }
}
