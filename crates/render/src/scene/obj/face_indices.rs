//! Face indices that refer to no vertex, refused before tobj reads them: tobj 4.0.5 turns them
//! into indices it multiplies without overflow checks (`f 2/-13/1` with 4 texture coordinates
//! panicked in `add_vertex`; found by the OBJ fuzz property). The rules are tobj's: a negative
//! index counts back from the elements read so far, a positive one may point anywhere in the
//! file.

use std::path::Path;

use crate::RenderError;

/// The elements a face vertex `v/vt/vn` refers to, in the order of its parts.
const KINDS: [(&str, &str); 3] = [
    ("v", "vertex position"),
    ("vt", "texture coordinate"),
    ("vn", "normal"),
];

/// Refuses the first `f` or `l` index (1-based line) that is 0 or refers past the elements of
/// its kind; lines tobj cannot parse at all are left to its own error.
pub fn check_face_indices(path: &Path, text: &str) -> Result<(), RenderError> {
    let mut total = [0usize; 3];
    for line in text.lines() {
        if let Some(kind) = element_kind(line) {
            total[kind] += 1;
        }
    }
    let mut so_far = [0usize; 3];
    for (number, line) in text.lines().enumerate() {
        if let Some(kind) = element_kind(line) {
            so_far[kind] += 1;
            continue;
        }
        let mut words = line.split_whitespace();
        if !matches!(words.next(), Some("f" | "l")) {
            continue;
        }
        for word in words {
            for (kind, part) in word.split('/').enumerate().take(3) {
                let Ok(index) = part.parse::<isize>() else {
                    continue;
                };
                let (count, valid) = if index < 0 {
                    (so_far[kind], index.unsigned_abs() <= so_far[kind])
                } else {
                    (
                        total[kind],
                        index >= 1 && index.unsigned_abs() <= total[kind],
                    )
                };
                if !valid {
                    let (_, name) = KINDS[kind];
                    return Err(RenderError::bad_mesh(
                        path,
                        format!(
                            "line {}: index {index} refers to no {name} ({count} defined{}); expected 1 to {count}, or -1 to -{count} counting back",
                            number + 1,
                            if index < 0 { " above it" } else { "" }
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// Which of [`KINDS`] a line defines, if any.
fn element_kind(line: &str) -> Option<usize> {
    let first = line.split_whitespace().next()?;
    KINDS.iter().position(|(keyword, _)| *keyword == first)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str) -> Result<(), String> {
        check_face_indices(Path::new("m.obj"), text).map_err(|e| e.to_string())
    }

    const QUAD: &str =
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 1 1\nvn 0 0 1\n";

    #[test]
    fn indices_within_the_elements_pass_in_both_directions() {
        check(&format!(
            "{QUAD}f 1/1/1 2/2/1 3/3/1\nf -3/-3/-1 -1/-1/-1 -2/-2/-1\nl 1 4\n"
        ))
        .unwrap();
        check(&format!("{QUAD}f 1//1 2//1 3//1\n")).unwrap();
        // a positive index may point at a vertex defined further down, as tobj reads it
        check("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
    }

    #[test]
    fn an_index_past_its_elements_names_the_line_and_the_range() {
        let e = check(&format!("{QUAD}usemtl tex\nf 2/2/1 4/4/1 3/-13/1\n")).unwrap_err();
        assert!(e.contains("m.obj"), "{e}");
        assert!(
            e.contains("line 11: index -13 refers to no texture coordinate (4 defined above it)"),
            "{e}"
        );
        let e = check(&format!("{QUAD}f 1/1/1 2/2/2 3/3/1\n")).unwrap_err();
        assert!(e.contains("index 2 refers to no normal (1 defined)"), "{e}");
        let e = check(&format!("{QUAD}f 0 1 2\n")).unwrap_err();
        assert!(e.contains("index 0 refers to no vertex position"), "{e}");
        let e = check(&format!("{QUAD}f 1/9223372036854775807 2 3\n")).unwrap_err();
        assert!(e.contains("texture coordinate"), "{e}");
        // counting back uses the elements above the face, not the whole file
        let e = check("f -1 -1 -1\nv 0 0 0\n").unwrap_err();
        assert!(
            e.contains("line 1: index -1 refers to no vertex position (0 defined above it)"),
            "{e}"
        );
    }
}
