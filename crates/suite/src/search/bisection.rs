//! The search for one method, family and scene: is it broken on the clean sequences, at 5, and
//! then bisection between the highest severity seen not to break it and the lowest seen to,
//! until they are one resolution apart. Each probe's verdict is the median of its runs, so a
//! method whose runs spread needs more repeats, not another rule (see [`super::Criterion`]).

use rslam_perturb::Severity;

/// The severities a family can take.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Grid {
    /// Any severity in steps of 0.01; bisection stops at `resolution` (in hundredths).
    Real { resolution: u16 },
    /// Whole severities only (the item has no parameters between its rows).
    Whole,
}

impl Grid {
    /// The severity between `low` and `high` to try next; `None` once they are adjacent on
    /// the grid (or one resolution apart).
    fn midpoint(self, low: Severity, high: Severity) -> Option<Severity> {
        let (low, high) = (low.hundredths(), high.hundredths());
        let step = match self {
            Grid::Real { resolution } => resolution.max(1),
            Grid::Whole => 100,
        };
        if high - low <= step {
            return None;
        }
        let middle = match self {
            Grid::Real { .. } => (low + high) / 2,
            Grid::Whole => (low / 100 + high / 100) / 2 * 100,
        };
        Severity::from_hundredths(middle)
    }
}

/// Where the search ended.
#[derive(Clone, Debug, PartialEq)]
pub struct Finding {
    /// The lowest severity seen to break the method; `None`: not broken at 5.
    pub breaking: Option<Severity>,
    /// The highest severity seen not to break it (0 when even the clean sequences did).
    pub low: Severity,
    /// Every severity tried, in order, with whether it broke the method.
    pub probes: Vec<(Severity, bool)>,
}

/// Searches with `breaks(severity)`: whether the method breaks there. Monotone `breaks` give
/// the exact threshold to within the grid's step.
pub fn bisect<E>(
    grid: Grid,
    mut breaks: impl FnMut(Severity) -> Result<bool, E>,
) -> Result<Finding, E> {
    let mut probes = Vec::new();
    let mut probe = |severity: Severity| -> Result<bool, E> {
        let broke = breaks(severity)?;
        probes.push((severity, broke));
        Ok(broke)
    };
    if probe(Severity::CLEAN)? {
        return Ok(Finding {
            breaking: Some(Severity::CLEAN),
            low: Severity::CLEAN,
            probes,
        });
    }
    if !probe(Severity::MAX)? {
        return Ok(Finding {
            breaking: None,
            low: Severity::MAX,
            probes,
        });
    }
    let (mut low, mut high) = (Severity::CLEAN, Severity::MAX);
    while let Some(middle) = grid.midpoint(low, high) {
        match probe(middle)? {
            true => high = middle,
            false => low = middle,
        }
    }
    Ok(Finding {
        breaking: Some(high),
        low,
        probes,
    })
}

#[cfg(test)]
mod tests {
    use std::convert::Infallible;

    use super::*;

    fn at(hundredths: u16) -> Severity {
        Severity::from_hundredths(hundredths).unwrap()
    }

    fn search(grid: Grid, threshold: f64) -> Finding {
        bisect::<Infallible>(grid, |s| Ok(s.value() >= threshold)).unwrap()
    }

    #[test]
    fn finds_every_threshold_to_within_the_resolution() {
        for t in 1..500u16 {
            let threshold = t as f64 / 100.0 + 0.003;
            let found = search(Grid::Real { resolution: 10 }, threshold);
            let breaking = found.breaking.unwrap().value();
            assert!(
                breaking >= threshold && breaking - found.low.value() <= 0.1,
                "{threshold}: {found:?}"
            );
            assert!(found.low.value() < threshold);
            // 0 and 5, then ⌈log2(500 / 10)⌉ = 6 bisections.
            assert!(found.probes.len() <= 8, "{threshold}: {found:?}");
        }
    }

    #[test]
    fn clean_breakage_and_never_breaking_end_the_search_at_once() {
        let clean = search(Grid::Real { resolution: 10 }, -1.0);
        assert_eq!(
            (clean.breaking, clean.probes.len()),
            (Some(Severity::CLEAN), 1)
        );
        let never = search(Grid::Real { resolution: 10 }, 7.0);
        assert_eq!((never.breaking, never.low), (None, Severity::MAX));
        assert_eq!(
            never.probes,
            [(Severity::CLEAN, false), (Severity::MAX, false)]
        );
    }

    #[test]
    fn whole_grids_try_whole_severities_only() {
        let found = search(Grid::Whole, 3.5);
        assert_eq!(found.breaking, Some(at(400)));
        assert_eq!(found.low, at(300));
        assert!(found.probes.iter().all(|(s, _)| s.as_whole().is_some()));
    }
}
