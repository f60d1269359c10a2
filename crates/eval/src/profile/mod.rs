//! A robustness profile: per method, perturbation family and scene, the lowest severity that
//! breaks the method (`rslam suite search` finds them), written as `profile.json` (method →
//! family → scene → breaking point), `profile.csv` and `report.html` with a chart per scene.

mod chart;
mod report;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::runs::csv_field;
use crate::EvalError;

/// The severity a method that never broke is shown at ("> 5"), and the top of the scale.
pub const TOP_SEVERITY: f64 = 5.0;

/// Where one method breaks under one family on one scene: the search narrowed it to
/// (`low`, `high`], `low` the highest severity seen not to break it and `high` the lowest seen to.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct BreakingPoint {
    /// `high`; `None` when the method did not break up to 5 (shown as "> 5", never as 5).
    pub breaking_severity: Option<f64>,
    pub low: f64,
    pub high: Option<f64>,
    /// Method runs the search made for it (sequences × repeats at every severity it tried).
    pub runs: usize,
}

impl BreakingPoint {
    /// "2.5 (2.44–2.5]", or "> 5".
    pub fn text(&self) -> String {
        match (self.breaking_severity, self.high) {
            (Some(s), Some(high)) if self.low < high => format!("{s} ({}–{high}]", self.low),
            (Some(s), _) => format!("{s}"),
            (None, _) => format!("> {TOP_SEVERITY}"),
        }
    }
}

/// method → family → scene → breaking point.
pub type ProfileTable = BTreeMap<String, BTreeMap<String, BTreeMap<String, BreakingPoint>>>;

#[derive(Clone, Debug, PartialEq)]
pub struct RobustnessProfile {
    /// What breaking means, as the search was told (`failed`, `sr<0.5`, `ate>3×clean`).
    pub criterion: String,
    /// The search stops when the interval is this narrow.
    pub resolution: f64,
    /// Sequences made at each severity (one per seed); each method runs its repeats on each.
    pub sequences_per_severity: usize,
    pub methods: ProfileTable,
}

impl RobustnessProfile {
    /// Every family, and every scene, of any method, sorted.
    fn families_and_scenes(&self) -> (Vec<&str>, Vec<&str>) {
        let mut families: Vec<&str> = Vec::new();
        let mut scenes: Vec<&str> = Vec::new();
        for by_family in self.methods.values() {
            for (family, by_scene) in by_family {
                families.push(family);
                scenes.extend(by_scene.keys().map(String::as_str));
            }
        }
        for list in [&mut families, &mut scenes] {
            list.sort_unstable();
            list.dedup();
        }
        (families, scenes)
    }

    fn point(&self, method: &str, family: &str, scene: &str) -> Option<&BreakingPoint> {
        self.methods.get(method)?.get(family)?.get(scene)
    }

    fn csv(&self) -> String {
        let mut out = String::from("method,family,scene,breaking_severity,low,high,runs\n");
        for (method, by_family) in &self.methods {
            for (family, by_scene) in by_family {
                for (scene, p) in by_scene {
                    let breaking = p
                        .breaking_severity
                        .map_or(format!(">{TOP_SEVERITY}"), |s| s.to_string());
                    let high = p.high.map_or(String::new(), |h| h.to_string());
                    out.push_str(&format!(
                        "{},{},{},{breaking},{},{high},{}\n",
                        csv_field(method),
                        csv_field(family),
                        csv_field(scene),
                        p.low,
                        p.runs
                    ));
                }
            }
        }
        out
    }
}

/// Writes `profile.json`, `profile.csv` and `report.html` into `dir`; returns their paths.
pub fn write_profile(profile: &RobustnessProfile, dir: &Path) -> Result<Vec<PathBuf>, EvalError> {
    std::fs::create_dir_all(dir).map_err(|e| EvalError::io(dir, e))?;
    let json = serde_json::to_string_pretty(&profile.methods).expect("a profile serialises");
    let files = [
        ("profile.json", json + "\n"),
        ("profile.csv", profile.csv()),
        (
            "report.html",
            report::html(profile, &dir.join("report.html"))?,
        ),
    ];
    let mut written = Vec::new();
    for (name, text) in files {
        let path = dir.join(name);
        let partial = dir.join(format!(".{name}.partial"));
        std::fs::write(&partial, text).map_err(|e| EvalError::io(&partial, e))?;
        std::fs::rename(&partial, &path).map_err(|e| EvalError::io(&path, e))?;
        written.push(path);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(super) fn profile() -> RobustnessProfile {
        let point = |s: Option<f64>, low: f64| BreakingPoint {
            breaking_severity: s,
            low,
            high: s,
            runs: 8,
        };
        let mut methods = ProfileTable::new();
        let fog = BTreeMap::from([
            ("room0".to_string(), point(Some(2.5), 2.44)),
            ("office1".to_string(), point(None, 5.0)),
        ]);
        let noise = BTreeMap::from([("room0".to_string(), point(Some(0.0), 0.0))]);
        methods.insert(
            "orb<slam>".into(),
            BTreeMap::from([("fog".into(), fog), ("gaussian_noise".into(), noise)]),
        );
        RobustnessProfile {
            criterion: "ate>3×clean".into(),
            resolution: 0.1,
            sequences_per_severity: 2,
            methods,
        }
    }

    #[test]
    fn a_method_that_never_breaks_is_shown_above_five_and_written_as_null() {
        let p = profile();
        let never = p.point("orb<slam>", "fog", "office1").unwrap();
        assert_eq!(never.text(), "> 5");
        let json = serde_json::to_value(&p.methods).unwrap();
        assert!(json["orb<slam>"]["fog"]["office1"]["breaking_severity"].is_null());
        assert_eq!(json["orb<slam>"]["fog"]["room0"]["breaking_severity"], 2.5);
        assert_eq!(json["orb<slam>"]["fog"]["room0"]["low"], 2.44);
        assert_eq!(json["orb<slam>"]["fog"]["room0"]["runs"], 8);
        let csv = p.csv();
        assert!(csv.contains("orb<slam>,fog,office1,>5,5,,8\n"), "{csv}");
        assert!(
            csv.contains("orb<slam>,fog,room0,2.5,2.44,2.5,8\n"),
            "{csv}"
        );
        assert_eq!(
            p.point("orb<slam>", "fog", "room0").unwrap().text(),
            "2.5 (2.44–2.5]"
        );
    }

    #[test]
    fn writes_the_three_files_and_the_page_escapes_names() {
        let dir = tempfile::tempdir().unwrap();
        let written = write_profile(&profile(), dir.path()).unwrap();
        assert_eq!(written.len(), 3);
        let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
        assert!(html.contains("orb&lt;slam&gt;") && !html.contains("orb<slam>"));
        assert!(html.contains("&gt; 5") && html.contains("<svg"));
        let back: ProfileTable =
            serde_json::from_str(&std::fs::read_to_string(&written[0]).unwrap()).unwrap();
        assert_eq!(back, profile().methods);
    }
}
