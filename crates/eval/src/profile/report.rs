//! `report.html` of a robustness profile: what breaking means, a chart per scene, the methods
//! side by side, and each method's breaking severities per family and scene.

use std::path::Path;

use super::chart::SceneChart;
use super::RobustnessProfile;
use crate::html_page::{escape, page, paragraph, Cell, Section, Table};
use crate::plot::svg_text;
use crate::EvalError;

pub(super) fn html(profile: &RobustnessProfile, path: &Path) -> Result<String, EvalError> {
    let (families, scenes) = profile.families_and_scenes();
    let methods: Vec<&str> = profile.methods.keys().map(String::as_str).collect();
    let mut charts = String::new();
    for scene in &scenes {
        let chart = SceneChart {
            profile,
            scene,
            families: families.clone(),
            methods: methods.clone(),
        };
        charts.push_str(&format!("<figure>{}</figure>\n", svg_text(path, &chart)?));
    }
    let mut side_by_side = Table::with_head(
        ["family", "scene"]
            .into_iter()
            .chain(methods.iter().copied()),
    );
    for family in &families {
        for scene in &scenes {
            let mut row = vec![Cell::text(family), Cell::text(scene)];
            for method in &methods {
                row.push(match profile.point(method, family, scene) {
                    Some(p) if p.breaking_severity.is_none() => Cell::text(&p.text()),
                    Some(p) => Cell::text(&p.text()).with_class("fail"),
                    None => Cell::text("—").with_class("none"),
                });
            }
            side_by_side.rows.push(row);
        }
    }
    let mut sections = vec![
        Section {
            id: "charts",
            title: "Breaking severity per scene".into(),
            body: format!("<div class=\"plots\">{charts}</div>\n"),
        },
        Section {
            id: "methods",
            title: "Methods side by side".into(),
            body: side_by_side.to_html(),
        },
    ];
    let mut per_method = String::new();
    for method in &methods {
        let mut table = Table::with_head(["family"].into_iter().chain(scenes.iter().copied()));
        for family in &families {
            let mut row = vec![Cell::text(family)];
            for scene in &scenes {
                let text = profile
                    .point(method, family, scene)
                    .map_or("—".to_string(), |p| p.text());
                row.push(Cell::text(&text));
            }
            table.rows.push(row);
        }
        per_method.push_str(&format!("<h3>{}</h3>\n{}", escape(method), table.to_html()));
    }
    sections.push(Section {
        id: "per-method",
        title: "Each method per family and scene".into(),
        body: per_method,
    });
    let title = format!(
        "rslam robustness profile: {} methods × {} families × {} scenes",
        methods.len(),
        families.len(),
        scenes.len()
    );
    let overview = paragraph(&format!(
        "The breaking severity is the lowest severity found at which the method breaks. \
         Breaking: {}, judged on the median of a method's runs at a severity (its repeats on \
         each of the {} sequence(s) made there). \
         The search bisects the severity between 0 and 5 down to a {} wide interval, shown as \
         (low–high]: low is the highest severity that did not break the method, high the lowest \
         that did. \"> 5\" marks a method that did not break at severity 5; \"0\" one that broke \
         on the clean sequences.",
        profile.criterion, profile.sequences_per_severity, profile.resolution
    ));
    Ok(page(&title, &overview, &sections))
}
