//! FAST-9 corners (Rosten & Drummond 2006) as ORB-SLAM detects them: a pixel is a corner when 9
//! contiguous pixels of the 16 on a radius-3 Bresenham circle are all brighter than it by more
//! than the threshold, or all darker; corners are thinned by non-maximum suppression of their
//! score over 3 × 3 neighbours. Hand-written (60 lines) rather than imageproc, which would add a
//! dozen crates for one function and has no suppression.

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

/// Score of a corner: the summed margins over the threshold along its best arc of 9 or more
/// pixels; 0 when it is no corner.
fn score(grey: &[u8], width: usize, x: usize, y: usize, threshold: u8) -> u32 {
    let centre = grey[y * width + x] as i32;
    let t = threshold as i32;
    let ring: [i32; 16] = std::array::from_fn(|k| {
        let (dx, dy) = CIRCLE[k];
        grey[(y as i32 + dy) as usize * width + (x as i32 + dx) as usize] as i32 - centre
    });
    let mut best = 0;
    for sign in [1, -1] {
        let mut run = 0;
        let mut margin_sum = 0u32;
        for k in 0..16 + 8 {
            let d = sign * ring[k % 16];
            if d > t {
                run += 1;
                margin_sum += (d - t) as u32;
                if run >= 9 {
                    best = best.max(margin_sum);
                }
            } else {
                run = 0;
                margin_sum = 0;
            }
        }
    }
    best
}

/// FAST-9 corners of a grey image after 3 × 3 non-maximum suppression.
pub fn fast9_count(grey: &[u8], width: usize, height: usize, threshold: u8) -> usize {
    if width < 7 || height < 7 {
        return 0;
    }
    let mut scores = vec![0u32; width * height];
    for y in 3..height - 3 {
        for x in 3..width - 3 {
            scores[y * width + x] = score(grey, width, x, y, threshold);
        }
    }
    let mut count = 0;
    for y in 3..height - 3 {
        for x in 3..width - 3 {
            let s = scores[y * width + x];
            if s == 0 {
                continue;
            }
            let beaten = (-1i32..=1).any(|dy| {
                (-1i32..=1).any(|dx| {
                    let n = scores[(y as i32 + dy) as usize * width + (x as i32 + dx) as usize];
                    (dx, dy) != (0, 0) && (n > s || (n == s && (dy, dx) < (0, 0)))
                })
            });
            if !beaten {
                count += 1;
            }
        }
    }
    count
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
        assert_eq!(fast9_count(&square(10, 200), 40, 40, ORB_SLAM_THRESHOLD), 4);
        assert_eq!(
            fast9_count(&square(128, 128), 40, 40, ORB_SLAM_THRESHOLD),
            0
        );
    }

    #[test]
    fn a_low_contrast_square_is_below_the_threshold() {
        let grey = square(100, 115);
        assert_eq!(fast9_count(&grey, 40, 40, ORB_SLAM_THRESHOLD), 0);
        assert_eq!(fast9_count(&grey, 40, 40, 10), 4);
    }

    #[test]
    fn a_straight_edge_and_a_checkerboard_crossing_are_not_corners() {
        // FAST needs 9 contiguous pixels of the circle on one side: an edge gives 7, the X
        // junction of a checkerboard 4 per quadrant.
        let edge: Vec<u8> = (0..40 * 40)
            .map(|i| if i % 40 < 20 { 20 } else { 220 })
            .collect();
        assert_eq!(fast9_count(&edge, 40, 40, ORB_SLAM_THRESHOLD), 0);
        let checker: Vec<u8> = (0..40 * 40)
            .map(|i| {
                if (i % 40 < 20) == (i / 40 < 20) {
                    20
                } else {
                    220
                }
            })
            .collect();
        assert_eq!(fast9_count(&checker, 40, 40, ORB_SLAM_THRESHOLD), 0);
    }
}
