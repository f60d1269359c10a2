//! How a sequence name splits into scene and setting, and a setting into its category.

/// The setting of an unperturbed sequence.
pub const CLEAN: &str = "clean";

/// `room0__fog-3` → (`room0`, `fog-3`); a name without `__` is the clean sequence of its scene.
pub fn scene_and_setting(sequence: &str) -> (String, String) {
    match sequence.split_once("__") {
        Some((scene, setting)) if !setting.is_empty() => (scene.to_string(), setting.to_string()),
        _ => (
            sequence.trim_end_matches("__").to_string(),
            CLEAN.to_string(),
        ),
    }
}

/// The perturbation a setting belongs to: its leading run of letters and underscores
/// (`fog-3-dynamic` → `fog`, `depth_missing-5` → `depth_missing`, `rot1_trans0.025` → `rot`).
pub fn category(setting: &str) -> String {
    let end = setting
        .find(|c: char| !(c.is_ascii_alphabetic() || c == '_'))
        .unwrap_or(setting.len());
    let name = setting[..end].trim_end_matches('_');
    if name.is_empty() { setting } else { name }.to_string()
}

/// Settings in report order: clean first, then by name.
pub fn sort_settings(settings: &mut [String]) {
    settings.sort_by(|a, b| (a != CLEAN, a).cmp(&(b != CLEAN, b)));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sequence_names_split_at_the_double_underscore() {
        assert_eq!(
            scene_and_setting("room0__fog-3"),
            ("room0".into(), "fog-3".into())
        );
        assert_eq!(
            scene_and_setting("office_2"),
            ("office_2".into(), CLEAN.into())
        );
        assert_eq!(
            scene_and_setting("room0__rot-1__x"),
            ("room0".into(), "rot-1__x".into())
        );
    }

    #[test]
    fn categories_drop_severities_and_modes() {
        assert_eq!(category("fog-3-dynamic"), "fog");
        assert_eq!(category("depth_missing-5"), "depth_missing");
        assert_eq!(category("rot1_trans0.025"), "rot");
        assert_eq!(category("clean"), "clean");
        assert_eq!(category("3d"), "3d");
    }

    #[test]
    fn clean_sorts_first() {
        let mut s = vec!["fog-1".to_string(), "blur-1".into(), CLEAN.into()];
        sort_settings(&mut s);
        assert_eq!(s, vec!["clean", "blur-1", "fog-1"]);
    }
}
