//! What `rslam list` shows: every item a spec takes, with its syntax, what it does, what it
//! needs of a job, and its parameters at each severity.

use serde::Serialize;

use crate::{Between, Group, CATALOGUE, ITEM_TABLES};

/// One row of `rslam list`.
#[derive(Clone, Debug, Serialize)]
pub struct ListEntry {
    pub name: &'static str,
    /// "image", "depth", "trajectory", "stream", "sensor", "calibration" or "imu".
    pub group: &'static str,
    /// How to write it in a spec.
    pub syntax: String,
    pub description: String,
    /// What it needs of a job ([`crate::Need::words`]), e.g. "a scene"; empty: any job.
    pub needs: Vec<&'static str>,
    /// Parameters at severities 1..=5; empty for items without severities.
    pub parameters: Vec<String>,
    /// How a real severity between two whole ones is made (`interpolated: …`, or `whole
    /// severities only: …`); empty for items without severities.
    #[serde(skip_serializing_if = "String::is_empty")]
    pub between: String,
}

/// Every item: image, then depth corruptions (catalogue order), then the items of
/// [`ITEM_TABLES`] (trajectory, stream, sensor, calibration, IMU).
pub fn listing() -> Vec<ListEntry> {
    let mut entries: Vec<ListEntry> = CATALOGUE
        .iter()
        .map(|e| {
            let mut syntax = format!("{}:0-5[@dynamic]", e.name);
            if let Some(form) = &e.explicit {
                syntax.push_str(&format!(" | {}", form.syntax));
            }
            ListEntry {
                name: e.name,
                group: match e.group {
                    Group::Image => "image",
                    Group::Depth => "depth",
                },
                syntax,
                description: e.description.to_string(),
                needs: e.needs().into_iter().map(|n| n.words()).collect(),
                parameters: e.parameter_table().to_vec(),
                between: match e.between {
                    Between::Interpolated(how) => format!("interpolated: {how}"),
                    Between::WholeOnly(why) => format!("whole severities only: {why}"),
                },
            }
        })
        .collect();
    entries.sort_by_key(|e| e.group != "image");
    for (group, table) in ITEM_TABLES {
        entries.extend(table.iter().map(|e| ListEntry {
            name: e.name,
            group,
            syntax: e.syntax.to_string(),
            description: e.description.to_string(),
            needs: e.needs.iter().map(|n| n.words()).collect(),
            parameters: Vec::new(),
            between: String::new(),
        }));
    }
    entries
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lists_every_spec_name_once() {
        let names: Vec<&str> = listing().iter().map(|e| e.name).collect();
        assert_eq!(names.len(), crate::all_names().len());
        for name in crate::all_names() {
            assert_eq!(names.iter().filter(|&&n| n == name).count(), 1, "{name}");
        }
        assert!(listing()
            .iter()
            .filter(|e| e.group == "image" || e.group == "depth")
            .all(|e| e.parameters.len() == 5));
    }
}
