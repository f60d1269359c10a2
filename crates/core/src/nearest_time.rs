//! Nearest-timestamp matching, the one way rslam pairs streams captured at different times
//! (TUM colour with depth, frames with ground-truth poses).

/// The index of the time in `times` closest to `t` (the first of equals), if it lies within
/// `max_diff` seconds.
pub fn nearest_time(times: impl IntoIterator<Item = f64>, t: f64, max_diff: f64) -> Option<usize> {
    times
        .into_iter()
        .map(|time| (time - t).abs())
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .filter(|(_, gap)| *gap <= max_diff)
        .map(|(i, _)| i)
}

#[cfg(test)]
mod tests {
    use super::nearest_time;

    #[test]
    fn picks_the_closest_within_the_bound_and_the_first_of_equals() {
        let times = [0.0, 0.25, 0.5, 0.75];
        assert_eq!(nearest_time(times, 0.4, 0.125), Some(2));
        assert_eq!(
            nearest_time(times, 0.125, 0.125),
            Some(0),
            "tie: the earlier"
        );
        assert_eq!(nearest_time(times, 1.0, 0.125), None);
        assert_eq!(
            nearest_time(times, 0.875, 0.125),
            Some(3),
            "bound inclusive"
        );
        assert_eq!(nearest_time([], 0.0, 1.0), None);
    }
}
