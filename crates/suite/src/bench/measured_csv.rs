//! The CSV row tail of a run's measures in the suite's report tables: the measures and an empty
//! `failure` field, or empty measure fields and why the run could not be measured.

use rslam_eval::runs::csv_field;

/// `measures` (`fields` comma-separated values) then the failure field; with no measures,
/// `fields` empty fields then `failure`.
pub(super) fn measures_or_failure(
    measures: Option<String>,
    fields: usize,
    failure: Option<&str>,
) -> String {
    match measures {
        Some(values) => format!("{values},"),
        None => format!(
            "{}{}",
            ",".repeat(fields),
            csv_field(failure.unwrap_or_default())
        ),
    }
}
