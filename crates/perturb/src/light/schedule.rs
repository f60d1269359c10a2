//! A job's light over time: from the spec's light items, the seed and the scene's layers, the
//! RGB weight of every layer for the interval a render exposes. Lamps: the lit part of the
//! interval (switching), weighted by the flicker, both integrated exactly; daylight: its drift
//! at the interval's middle. A pure function of time, so every camera of a rig sees the same
//! light at the same instant, and a resumed run the same as a whole one.

use super::switching::Outage;
use super::{Flicker, LightSpec};

/// What a scene layer's light comes from, as the schedule needs it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LayerKind {
    Lamp,
    Daylight,
}

/// The light state of a job's layers over time.
#[derive(Clone, Debug)]
pub struct LightSchedule {
    spec: LightSpec,
    seed: u64,
    layers: Vec<LayerKind>,
    /// Per lamp (in layer order), its dark intervals, sorted and merged.
    dark: Vec<Vec<(f64, f64)>>,
    flicker_phase: f64,
}

impl LightSchedule {
    /// The schedule of `spec` over `[0, horizon]` seconds for a scene with `layers`.
    pub fn new(spec: &LightSpec, seed: u64, layers: &[LayerKind], horizon: f64) -> Self {
        let lamps = layers.iter().filter(|&&k| k == LayerKind::Lamp).count();
        let outages: Vec<Outage> = spec
            .lights
            .map(|s| s.outages(seed, lamps, horizon))
            .unwrap_or_default();
        let dark = (0..lamps)
            .map(|lamp| {
                merged(
                    outages
                        .iter()
                        .filter(|o| o.lamps.contains(&lamp))
                        .map(|o| (o.start, o.end)),
                )
            })
            .collect();
        Self {
            spec: *spec,
            seed,
            layers: layers.to_vec(),
            dark,
            flicker_phase: Flicker::phase(seed),
        }
    }

    /// One RGB weight per layer for a render exposing `[a, b]` seconds (a = b: one instant).
    pub fn weights(&self, a: f64, b: f64) -> Vec<[f32; 3]> {
        let mut lamp = 0;
        self.layers
            .iter()
            .map(|kind| match kind {
                LayerKind::Lamp => {
                    lamp += 1;
                    [self.lamp(lamp - 1, a, b) as f32; 3]
                }
                LayerKind::Daylight => match self.spec.daylight {
                    Some(d) => d.gain(self.seed, (a + b) / 2.0).map(|g| g as f32),
                    None => [1.0; 3],
                },
            })
            .collect()
    }

    /// Lamp `lamp`'s mean intensity over `[a, b]`.
    fn lamp(&self, lamp: usize, a: f64, b: f64) -> f64 {
        let lit = lit_intervals(&self.dark[lamp], a, b);
        if b <= a {
            let on = !lit.is_empty();
            let flicker = self
                .spec
                .flicker
                .map_or(1.0, |f| f.at(self.flicker_phase, a));
            return if on { flicker } else { 0.0 };
        }
        let integral: f64 = lit
            .iter()
            .map(|&(s, e)| match self.spec.flicker {
                Some(f) => f.integral(self.flicker_phase, s, e),
                None => e - s,
            })
            .sum();
        integral / (b - a)
    }
}

/// Intervals sorted and joined where they overlap.
fn merged(intervals: impl Iterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    let mut sorted: Vec<(f64, f64)> = intervals.collect();
    sorted.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut out: Vec<(f64, f64)> = Vec::new();
    for (s, e) in sorted {
        match out.last_mut() {
            Some(last) if s <= last.1 => last.1 = last.1.max(e),
            _ => out.push((s, e)),
        }
    }
    out
}

/// The parts of `[a, b]` outside every dark interval (for a = b: `[(a, a)]` when lit, else none).
fn lit_intervals(dark: &[(f64, f64)], a: f64, b: f64) -> Vec<(f64, f64)> {
    if b <= a {
        let is_dark = dark.iter().any(|&(s, e)| s <= a && a < e);
        return if is_dark { Vec::new() } else { vec![(a, a)] };
    }
    let mut lit = Vec::new();
    let mut from = a;
    for &(s, e) in dark.iter().filter(|&&(s, e)| e > a && s < b) {
        if s > from {
            lit.push((from, s));
        }
        from = from.max(e);
    }
    if from < b {
        lit.push((from, b));
    }
    lit
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PerturbSpec;

    fn schedule(text: &str, layers: &[LayerKind]) -> LightSchedule {
        let spec = PerturbSpec::parse(text).unwrap();
        LightSchedule::new(&spec.light, 3, layers, 200.0)
    }

    #[test]
    fn a_frame_exposed_across_a_switch_sees_the_lit_part_of_its_exposure() {
        let s = schedule("lights:0.5/8/4", &[LayerKind::Lamp, LayerKind::Daylight]);
        let (start, end) = s.dark[0][0];
        assert_eq!(s.weights(start + 1.0, start + 1.0)[0], [0.0; 3]);
        assert_eq!(s.weights(start - 1.0, start - 1.0)[0], [1.0; 3]);
        let across = s.weights(start - 0.010, start + 0.030)[0][0];
        assert!((across - 0.25).abs() < 1e-6, "{across}");
        let back = s.weights(end - 0.010, end + 0.010)[0][0];
        assert!((back - 0.5).abs() < 1e-6, "{back}");
        assert_eq!(
            s.weights(start + 1.0, start + 1.0)[1],
            [1.0; 3],
            "daylight stays"
        );
    }

    #[test]
    fn lit_intervals_cut_out_the_dark() {
        let dark = merged([(1.0, 2.0), (1.5, 3.0), (5.0, 6.0)].into_iter());
        assert_eq!(dark, vec![(1.0, 3.0), (5.0, 6.0)]);
        assert_eq!(
            lit_intervals(&dark, 0.0, 7.0),
            vec![(0.0, 1.0), (3.0, 5.0), (6.0, 7.0)]
        );
        assert!(lit_intervals(&dark, 1.2, 2.8).is_empty());
        assert!(lit_intervals(&dark, 2.0, 2.0).is_empty());
        assert_eq!(lit_intervals(&dark, 3.0, 3.0), vec![(3.0, 3.0)]);
    }

    #[test]
    fn flicker_is_integrated_over_the_exposure_and_sampled_without_one() {
        let s = schedule("flicker:100/1", &[LayerKind::Lamp]);
        // A whole period (10 ms) averages to 1, whatever the phase.
        assert!((s.weights(0.1234, 0.1334)[0][0] - 1.0).abs() < 1e-6);
        let f = Flicker::parse("100/1").unwrap();
        let at = s.weights(0.2, 0.2)[0][0];
        assert!((at as f64 - f.at(s.flicker_phase, 0.2)).abs() < 1e-6);
    }
}
