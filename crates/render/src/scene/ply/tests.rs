use super::*;
use crate::{load_scene, Texture};

/// Two triangles of a unit square, the first vertex red, with or without colour properties.
fn square(with_colours: bool) -> String {
    let (properties, colours) = if with_colours {
        (
            "property uchar red\nproperty uchar green\nproperty uchar blue\n",
            [" 255 0 0", " 0 0 0", " 0 0 0", " 0 0 0"],
        )
    } else {
        ("", [""; 4])
    };
    let corners = ["0 0 0", "1 0 0", "1 1 0", "0 1 0"];
    let mut text = format!(
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
         {properties}element face 1\nproperty list uchar int vertex_indices\nend_header\n"
    );
    for (corner, colour) in corners.iter().zip(colours) {
        text += &format!("{corner}{colour}\n");
    }
    text + "4 0 1 2 3\n"
}

#[test]
fn load_scene_reads_a_ply_file_with_its_colours_or_grey() {
    let dir = tempfile::tempdir().unwrap();
    for with_colours in [true, false] {
        let path = dir.path().join("Mesh.PLY");
        std::fs::write(&path, square(with_colours)).unwrap();
        let scene = load_scene(path.to_str().unwrap()).unwrap();
        assert_eq!(scene.mesh.triangle_count(), 2);
        assert_eq!(scene.mesh.vertices[2].position, [1.0, 1.0, 0.0]);
        let expected = if with_colours {
            [255, 0, 0, 255]
        } else {
            [200, 200, 200, 255]
        };
        assert_eq!(scene.mesh.vertices[0].color, expected);
        assert_eq!(scene.textures, vec![Texture::white()]);
        assert!(scene.default_trajectory.is_none());
    }
}

#[test]
fn load_scene_names_the_file_in_every_error() {
    let dir = tempfile::tempdir().unwrap();
    let truncated = dir.path().join("cut.ply");
    let full = square(true);
    std::fs::write(&truncated, &full[..full.len() - 3]).unwrap();
    let err = load_scene(truncated.to_str().unwrap()).unwrap_err();
    assert!(matches!(err, RenderError::BadMesh { .. }));
    assert!(
        err.to_string().starts_with(truncated.to_str().unwrap())
            && err.to_string().contains("file ends early"),
        "{err}"
    );

    let missing = dir.path().join("missing.ply");
    let err = load_scene(missing.to_str().unwrap()).unwrap_err();
    assert!(matches!(err, RenderError::Io { .. }), "{err:?}");
    assert!(err.to_string().contains("missing.ply"), "{err}");

    let stl = dir.path().join("part.stl");
    std::fs::write(&stl, "solid x\n").unwrap();
    let err = load_scene(stl.to_str().unwrap()).unwrap_err();
    assert!(
        err.to_string().contains("unsupported mesh format 'stl'"),
        "{err}"
    );

    let err = load_scene("room9").unwrap_err();
    assert!(
        err.to_string().contains("unknown scene 'room9'") && err.to_string().contains("office4"),
        "{err}"
    );

    let empty = dir.path().join("empty.ply");
    std::fs::write(
        &empty,
        "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
    )
    .unwrap();
    assert!(load_scene(empty.to_str().unwrap())
        .unwrap_err()
        .to_string()
        .contains("no triangles"));
}
