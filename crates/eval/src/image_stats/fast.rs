//! FAST-9 corners (Rosten & Drummond 2006) as ORB-SLAM detects them: a pixel is a corner when 9
//! contiguous pixels of the 16 on a radius-3 Bresenham circle are all brighter than it by more
//! than the threshold, or all darker; corners are thinned by non-maximum suppression of their
//! strength over 3 × 3 neighbours, as OpenCV's detector that ORB-SLAM calls does. Hand-written
//! (80 lines) rather than imageproc, which would add a dozen crates for one function and has no
//! suppression.

/// ORB-SLAM's `iniThFAST`: the threshold on grey levels its extractor tries first.
pub const ORB_SLAM_THRESHOLD: u8 = 20;

const CIRCLE: [(i32, i32); 16] = [
    (0, -3),
    (1, -3),
    (2, -2),
    (3, -1),
    (3, 0),
    (3, 1),
    (2, 2),
    (1, 3),
    (0, 3),
    (-1, 3),
    (-2, 2),
    (-3, 1),
    (-3, 0),
    (-3, -1),
    (-2, -2),
    (-1, -3),
];

/// ORB-SLAM's `minThFAST`: the threshold its extractor falls back to in cells where
/// [`ORB_SLAM_THRESHOLD`] finds nothing.
pub const ORB_SLAM_MIN_THRESHOLD: u8 = 7;

/// A FAST-9 corner and its strength: the largest difference that every pixel of its best arc of
/// 9 contiguous circle pixels keeps to the centre, all brighter or all darker (OpenCV's corner
/// score). A pixel is a corner at threshold t when its strength exceeds t.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Corner {
    pub x: usize,
    pub y: usize,
    pub strength: u8,
}

/// The strength of pixel (x, y), or 0 when it is no corner at `threshold`.
fn strength(grey: &[u8], width: usize, x: usize, y: usize, threshold: u8) -> u8 {
    let centre = grey[y * width + x] as i32;
    let t = threshold as i32;
    let ring: [i32; 16] = std::array::from_fn(|k| {
        let (dx, dy) = CIRCLE[k];
        grey[(y as i32 + dy) as usize * width + (x as i32 + dx) as usize] as i32 - centre
    });
    // Any 9 contiguous circle pixels hold at least two of the four compass pixels.
    let compass = |sign: i32| {
        [0, 4, 8, 12]
            .iter()
            .filter(|&&k| sign * ring[k] > t)
            .count()
    };
    let mut best = 0;
    for sign in [1, -1] {
        if compass(sign) < 2 {
            continue;
        }
        for start in 0..16 {
            let weakest = (0..9).map(|k| sign * ring[(start + k) % 16]).min();
            best = best.max(weakest.unwrap_or(0));
        }
    }
    if best > t {
        best as u8
    } else {
        0
    }
}

/// FAST-9 corners of a grey image at `threshold` after 3 × 3 non-maximum suppression of their
/// strength, row by row.
pub fn corners(grey: &[u8], width: usize, height: usize, threshold: u8) -> Vec<Corner> {
    if width < 7 || height < 7 {
        return Vec::new();
    }
    let mut strengths = vec![0u8; width * height];
    for y in 3..height - 3 {
        for x in 3..width - 3 {
            strengths[y * width + x] = strength(grey, width, x, y, threshold);
        }
    }
    let mut found = Vec::new();
    for y in 3..height - 3 {
        for x in 3..width - 3 {
            let s = strengths[y * width + x];
            if s == 0 {
                continue;
            }
            let beaten = (-1i32..=1).any(|dy| {
                (-1i32..=1).any(|dx| {
                    let n = strengths[(y as i32 + dy) as usize * width + (x as i32 + dx) as usize];
                    (dx, dy) != (0, 0) && (n > s || (n == s && (dy, dx) < (0, 0)))
                })
            });
            if !beaten {
                found.push(Corner { x, y, strength: s });
            }
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 40 × 40 image of grey `ground` with a 20-pixel square of grey `square` in its middle.
    fn square(ground: u8, square: u8) -> Vec<u8> {
        (0..40 * 40)
            .map(|i| {
                let inside = |c: usize| (10..30).contains(&c);
                if inside(i % 40) && inside(i / 40) {
                    square
                } else {
                    ground
                }
            })
            .collect()
    }

    #[test]
    fn a_bright_square_on_dark_has_four_corners_and_a_flat_image_none() {
        assert_eq!(
            corners(&square(10, 200), 40, 40, ORB_SLAM_THRESHOLD).len(),
            4
        );
        assert_eq!(
            corners(&square(128, 128), 40, 40, ORB_SLAM_THRESHOLD).len(),
            0
        );
    }

    #[test]
    fn a_low_contrast_square_is_below_the_threshold() {
        let grey = square(100, 115);
        assert_eq!(corners(&grey, 40, 40, ORB_SLAM_THRESHOLD).len(), 0);
        assert_eq!(corners(&grey, 40, 40, 10).len(), 4);
    }

    #[test]
    fn a_square_corner_is_as_strong_as_the_square_is_bright() {
        let found = corners(&square(10, 110), 40, 40, ORB_SLAM_MIN_THRESHOLD);
        assert_eq!(found.len(), 4);
        assert!(found.iter().all(|c| c.strength == 100), "{found:?}");
        // One at each corner of the square (pixels 10 and 29 in each axis); FAST-9 also fires
        // two pixels along an edge from a corner, where 9 circle pixels still fall outside.
        let near = |v: usize| [10usize, 29].iter().any(|&edge| v.abs_diff(edge) <= 2);
        assert!(found.iter().all(|c| near(c.x) && near(c.y)), "{found:?}");
        // Strength 100 means a corner at every threshold below 100 and none at 100.
        assert_eq!(corners(&square(10, 110), 40, 40, 99).len(), 4);
        assert_eq!(corners(&square(10, 110), 40, 40, 100).len(), 0);
    }

    #[test]
    fn a_straight_edge_and_a_checkerboard_crossing_are_not_corners() {
        // FAST needs 9 contiguous pixels of the circle on one side: an edge gives 7, the X
        // junction of a checkerboard 4 per quadrant.
        let edge: Vec<u8> = (0..40 * 40)
            .map(|i| if i % 40 < 20 { 20 } else { 220 })
            .collect();
        assert_eq!(corners(&edge, 40, 40, ORB_SLAM_THRESHOLD).len(), 0);
        let checker: Vec<u8> = (0..40 * 40)
            .map(|i| {
                if (i % 40 < 20) == (i / 40 < 20) {
                    20
                } else {
                    220
                }
            })
            .collect();
        assert_eq!(corners(&checker, 40, 40, ORB_SLAM_THRESHOLD).len(), 0);
    }
}
