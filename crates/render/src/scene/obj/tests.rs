use crate::load_scene;

const QUAD_OBJ: &str =
    "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
                        usemtl painted\nf 1/1 2/2 3/3 4/4\n";

#[test]
fn reads_obj_with_material_colour_and_texture() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("quad.obj"), QUAD_OBJ).unwrap();
    std::fs::write(
        dir.path().join("quad.mtl"),
        "newmtl painted\nKd 1.0 0.5 0.0\nmap_Kd tex/wood.png\n",
    )
    .unwrap();
    std::fs::create_dir(dir.path().join("tex")).unwrap();
    image::RgbImage::from_raw(1, 2, vec![10, 20, 30, 40, 50, 60])
        .unwrap()
        .save(dir.path().join("tex/wood.png"))
        .unwrap();
    let scene = load_scene(dir.path().join("quad.obj").to_str().unwrap()).unwrap();
    assert_eq!(scene.mesh.triangle_count(), 2, "the quad is triangulated");
    assert_eq!(scene.textures.len(), 2);
    assert_eq!(
        scene.textures[1].rgba,
        vec![10, 20, 30, 255, 40, 50, 60, 255]
    );
    let v = &scene.mesh.vertices;
    assert!(v
        .iter()
        .all(|v| v.layer == 1 && v.color == [255, 128, 0, 255]));
    let corner = v.iter().find(|v| v.position == [0.0, 1.0, 0.0]).unwrap();
    assert_eq!(corner.uv, [0.0, 0.0], "OBJ v = 1 is the top row");
}

#[test]
fn obj_problems_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("quad.obj");
    std::fs::write(&obj, QUAD_OBJ).unwrap();
    // Material library missing.
    let err = load_scene(obj.to_str().unwrap()).unwrap_err().to_string();
    assert!(
        err.contains("quad.obj") && err.contains("material library"),
        "{err}"
    );
    // Texture missing.
    std::fs::write(
        dir.path().join("quad.mtl"),
        "newmtl painted\nmap_Kd nowhere.png\n",
    )
    .unwrap();
    let err = load_scene(obj.to_str().unwrap()).unwrap_err().to_string();
    assert!(
        err.contains("quad.obj") && err.contains("nowhere.png"),
        "{err}"
    );
    // Garbage geometry.
    let bad = dir.path().join("bad.obj");
    std::fs::write(&bad, "v 0 0 zero\nf 1 2 3\n").unwrap();
    let err = load_scene(bad.to_str().unwrap()).unwrap_err().to_string();
    assert!(
        err.starts_with(bad.to_str().unwrap()) && !err.contains('\n'),
        "{err}"
    );
}

/// A texture file that exists but does not decode is an error naming it and the OBJ, like a
/// missing one; a material without `map_Kd` still loads untextured.
#[test]
fn undecodable_texture_is_an_error_naming_texture_and_obj() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("quad.obj");
    std::fs::write(&obj, QUAD_OBJ).unwrap();
    std::fs::write(
        dir.path().join("quad.mtl"),
        "newmtl painted\nKd 1 1 1\nmap_Kd broken.png\n",
    )
    .unwrap();
    let texture = dir.path().join("broken.png");
    for (what, bytes) in [
        ("garbage", b"this is not an image".to_vec()),
        ("bad png", b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR broken".to_vec()),
        ("empty", Vec::new()),
    ] {
        std::fs::write(&texture, bytes).unwrap();
        let err = load_scene(obj.to_str().unwrap()).unwrap_err();
        assert!(
            matches!(err, crate::RenderError::BadTexture { .. }),
            "{what}: {err:?}"
        );
        let err = err.to_string();
        assert!(
            err.starts_with(obj.to_str().unwrap()) && err.contains(texture.to_str().unwrap()),
            "{what}: {err}"
        );
    }
    std::fs::write(dir.path().join("quad.mtl"), "newmtl painted\nKd 1 1 1\n").unwrap();
    let scene = load_scene(obj.to_str().unwrap()).unwrap();
    assert_eq!(scene.textures.len(), 1);
    assert!(scene.mesh.vertices.iter().all(|v| v.layer == 0));
}

/// tobj 4.0.5 panicked (`parse_float3` unwraps) on a colour with fewer than three numbers; found
/// by fuzzing the material library.
#[test]
fn a_short_colour_in_the_material_library_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("quad.obj");
    std::fs::write(&obj, QUAD_OBJ).unwrap();
    for short in ["Kd 1.0", "Ka", "Ks 0.1 0.1", "Ke -1"] {
        std::fs::write(
            dir.path().join("quad.mtl"),
            format!("newmtl painted\n{short}\n"),
        )
        .unwrap();
        let err = load_scene(obj.to_str().unwrap()).unwrap_err().to_string();
        assert!(
            err.contains("quad.obj: cannot read its material library")
                && err.contains("quad.mtl: material parse error"),
            "{short}: {err}"
        );
    }
}

#[test]
fn non_finite_coordinates_are_an_error_naming_the_object() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("tri.obj");
    for (text, bad) in [
        ("o tri\nv 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", "NaN"),
        (
            "o tri\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 inf\nf 1/1 2/1 3/1\n",
            "inf",
        ),
    ] {
        std::fs::write(&obj, text).unwrap();
        let err = load_scene(obj.to_str().unwrap()).unwrap_err().to_string();
        assert!(
            err.ends_with(&format!(
                "tri.obj: object 'tri': coordinate {bad} is not a finite number"
            )),
            "{err}"
        );
    }
}

/// Found by fuzzing: a texture name holding a carriage return was quoted as is.
#[test]
fn a_texture_name_with_a_line_break_is_quoted_on_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("quad.obj");
    std::fs::write(&obj, QUAD_OBJ).unwrap();
    std::fs::write(
        dir.path().join("quad.mtl"),
        "newmtl painted\nmap_Kd wo\rod.png\n",
    )
    .unwrap();
    let err = load_scene(obj.to_str().unwrap()).unwrap_err().to_string();
    assert!(
        err.contains("wo\\rod.png") && !err.contains('\r'),
        "{err:?}"
    );
}
