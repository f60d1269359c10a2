//! Local contrast: the standard deviation of grey levels within 8 × 8-pixel blocks, the spread a
//! feature detector sees within a few pixels at the working resolution.

/// Side of the blocks, pixels.
pub const BLOCK: usize = 8;

/// The standard deviation of grey levels (0–255) in every whole [`BLOCK`] × [`BLOCK`] block of a
/// grey image, block row by block row.
pub fn block_contrasts(grey: &[u8], width: usize, height: usize) -> Vec<f32> {
    let mut out = Vec::with_capacity((width / BLOCK) * (height / BLOCK));
    for by in 0..height / BLOCK {
        for bx in 0..width / BLOCK {
            let (mut sum, mut squares) = (0u32, 0u32);
            for y in by * BLOCK..(by + 1) * BLOCK {
                for &g in &grey[y * width + bx * BLOCK..y * width + (bx + 1) * BLOCK] {
                    sum += g as u32;
                    squares += g as u32 * g as u32;
                }
            }
            let n = (BLOCK * BLOCK) as f32;
            let mean = sum as f32 / n;
            out.push((squares as f32 / n - mean * mean).max(0.0).sqrt());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_flat_block_has_none_and_a_half_split_block_half_its_step() {
        // 16 × 8: a flat block of 90, then a block whose left half is 40 and right half 140.
        let grey: Vec<u8> = (0..16 * 8)
            .map(|i| match i % 16 {
                0..8 => 90,
                8..12 => 40,
                _ => 140,
            })
            .collect();
        assert_eq!(block_contrasts(&grey, 16, 8), vec![0.0, 50.0]);
    }

    #[test]
    fn partial_blocks_at_the_edges_are_left_out() {
        assert_eq!(block_contrasts(&[7; 20 * 9], 20, 9).len(), 2);
    }
}
