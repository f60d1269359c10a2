use super::*;
use crate::load_scene;

/// One triangle (positions, uvs, indices) in a little-endian buffer.
fn triangle_buffer() -> Vec<u8> {
    let mut b = Vec::new();
    for p in [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        p.iter().for_each(|c| b.extend(c.to_le_bytes()));
    }
    for uv in [[0.0f32, 0.0], [1.0, 0.0], [0.0, 1.0]] {
        uv.iter().for_each(|c| b.extend(c.to_le_bytes()));
    }
    for i in [0u16, 1, 2] {
        b.extend(i.to_le_bytes());
    }
    b.extend([0, 0]); // pad to 4 bytes
    b
}

fn document(buffer: &str, image: &str) -> String {
    format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [0]}}],
  "nodes": [{{"children": [1], "translation": [10, 0, 0]}}, {{"mesh": 0, "scale": [2, 2, 2]}}],
  "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}, "indices": 2, "material": 0}}]}}],
  "materials": [{{"pbrMetallicRoughness": {{"baseColorFactor": [1.0, 0.2158, 0.0, 1.0], "baseColorTexture": {{"index": 0}}}}}}],
  "textures": [{{"source": 0}}],
  "images": [{image}],
  "buffers": [{buffer}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 36}},
    {{"buffer": 0, "byteOffset": 36, "byteLength": 24}},
    {{"buffer": 0, "byteOffset": 60, "byteLength": 6}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
    {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}},
    {{"bufferView": 2, "componentType": 5123, "count": 3, "type": "SCALAR"}}
  ]
}}"#
    )
}

fn png_2x1() -> Vec<u8> {
    let img = image::RgbImage::from_raw(2, 1, vec![255, 0, 0, 0, 0, 255]).unwrap();
    let mut bytes = std::io::Cursor::new(Vec::new());
    img.write_to(&mut bytes, image::ImageFormat::Png).unwrap();
    bytes.into_inner()
}

fn check(mesh: &Mesh, textures: &[Texture]) {
    assert_eq!(mesh.indices, vec![0, 1, 2]);
    // Node transforms compose: scale 2, then translate 10 along x.
    assert_eq!(mesh.vertices[1].position, [12.0, 0.0, 0.0]);
    assert_eq!(mesh.vertices[2].position, [10.0, 2.0, 0.0]);
    assert_eq!(mesh.vertices[1].uv, [1.0, 0.0]);
    // Linear factor (1, 0.2158, 0) is sRGB (255, 128, 0).
    assert_eq!(mesh.vertices[0].color, [255, 128, 0, 255]);
    assert_eq!(mesh.vertices[0].layer, 1);
    assert_eq!(textures.len(), 2);
    assert_eq!(textures[1].rgba, vec![255, 0, 0, 255, 0, 0, 255, 255]);
}

#[test]
fn reads_gltf_with_external_buffer_and_texture() {
    let dir = tempfile::tempdir().unwrap();
    let buffer = triangle_buffer();
    std::fs::write(dir.path().join("tri.bin"), &buffer).unwrap();
    std::fs::write(dir.path().join("tex.png"), png_2x1()).unwrap();
    let json = document(
        &format!(r#"{{"uri": "tri.bin", "byteLength": {}}}"#, buffer.len()),
        r#"{"uri": "tex.png"}"#,
    );
    let path = dir.path().join("scene.gltf");
    std::fs::write(&path, json).unwrap();
    let (mesh, textures) = read_gltf(&path).unwrap();
    check(&mesh, &textures);
}

#[test]
fn reads_glb_with_embedded_buffer_and_texture() {
    let mut bin = triangle_buffer();
    let png = png_2x1();
    let image_offset = bin.len();
    bin.extend(&png);
    bin.resize(bin.len() + (4 - bin.len() % 4) % 4, 0);
    let mut json = document(
        &format!(r#"{{"byteLength": {}}}"#, bin.len()),
        r#"{"bufferView": 3, "mimeType": "image/png"}"#,
    );
    json = json.replace(
        r#"{"buffer": 0, "byteOffset": 60, "byteLength": 6}"#,
        &format!(r#"{{"buffer": 0, "byteOffset": 60, "byteLength": 6}}, {{"buffer": 0, "byteOffset": {image_offset}, "byteLength": {}}}"#, png.len()),
    );
    let mut json = json.into_bytes();
    json.resize(json.len() + (4 - json.len() % 4) % 4, b' ');
    let mut glb = Vec::new();
    glb.extend(b"glTF");
    glb.extend(2u32.to_le_bytes());
    glb.extend(((12 + 8 + json.len() + 8 + bin.len()) as u32).to_le_bytes());
    glb.extend((json.len() as u32).to_le_bytes());
    glb.extend(0x4E4F_534Au32.to_le_bytes());
    glb.extend(&json);
    glb.extend((bin.len() as u32).to_le_bytes());
    glb.extend(0x004E_4942u32.to_le_bytes());
    glb.extend(&bin);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.glb");
    std::fs::write(&path, &glb).unwrap();
    let scene = load_scene(path.to_str().unwrap()).unwrap();
    check(&scene.mesh, &scene.textures);

    let cut = dir.path().join("cut.glb");
    std::fs::write(&cut, &glb[..glb.len() / 2]).unwrap();
    let err = load_scene(cut.to_str().unwrap()).unwrap_err().to_string();
    assert!(
        err.starts_with(cut.to_str().unwrap()) && !err.contains('\n'),
        "{err}"
    );

    // Found by fuzzing: a stated length under the header's 12 bytes panicked in the gltf crate.
    let short = dir.path().join("short.glb");
    let mut stated_short = glb.clone();
    stated_short[8..12].copy_from_slice(&4u32.to_le_bytes());
    std::fs::write(&short, &stated_short).unwrap();
    let err = load_scene(short.to_str().unwrap()).unwrap_err().to_string();
    assert!(
        err.starts_with(short.to_str().unwrap()) && err.contains("length of 4 bytes"),
        "{err}"
    );
}

#[test]
fn broken_gltf_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("broken.gltf");
    std::fs::write(&path, "{ not json").unwrap();
    let err = load_scene(path.to_str().unwrap()).unwrap_err().to_string();
    assert!(err.starts_with(path.to_str().unwrap()), "{err}");
    let missing_buffer = dir.path().join("nobin.gltf");
    std::fs::write(
        &missing_buffer,
        document(
            r#"{"uri": "gone.bin", "byteLength": 68}"#,
            r#"{"uri": "tex.png"}"#,
        ),
    )
    .unwrap();
    let err = load_scene(missing_buffer.to_str().unwrap())
        .unwrap_err()
        .to_string();
    assert!(err.starts_with(missing_buffer.to_str().unwrap()), "{err}");
}

/// A base-colour texture that is missing or does not decode is an error naming the texture file
/// and the glTF file, never a white stand-in.
#[test]
fn unreadable_texture_is_an_error_naming_texture_and_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let buffer = triangle_buffer();
    std::fs::write(dir.path().join("tri.bin"), &buffer).unwrap();
    let buffer_json = format!(r#"{{"uri": "tri.bin", "byteLength": {}}}"#, buffer.len());
    let path = dir.path().join("scene.gltf");
    std::fs::write(&path, document(&buffer_json, r#"{"uri": "tex.png"}"#)).unwrap();
    let texture = dir.path().join("tex.png");
    let expect_error = |what: &str| {
        let err = load_scene(path.to_str().unwrap()).unwrap_err();
        assert!(
            matches!(err, RenderError::BadTexture { .. }),
            "{what}: {err:?}"
        );
        let err = err.to_string();
        assert!(
            err.starts_with(path.to_str().unwrap())
                && err.contains(texture.to_str().unwrap())
                && !err.contains('\n'),
            "{what}: {err}"
        );
    };
    expect_error("missing");
    std::fs::write(&texture, b"\x89PNG\r\n\x1a\nnot really a png").unwrap();
    expect_error("corrupt");
    let mut cut = png_2x1();
    cut.truncate(cut.len() - 20);
    std::fs::write(&texture, cut).unwrap();
    expect_error("truncated");
    std::fs::write(&texture, png_2x1()).unwrap();
    assert!(
        load_scene(path.to_str().unwrap()).is_ok(),
        "the fixture itself loads"
    );
}

#[test]
fn corrupt_embedded_image_names_its_buffer_view() {
    let mut bin = triangle_buffer();
    bin.extend(b"garbage!");
    let json = document(
        &format!(r#"{{"uri": "tri.bin", "byteLength": {}}}"#, bin.len()),
        r#"{"bufferView": 3, "mimeType": "image/png"}"#,
    )
    .replace(
        r#"{"buffer": 0, "byteOffset": 60, "byteLength": 6}"#,
        r#"{"buffer": 0, "byteOffset": 60, "byteLength": 6}, {"buffer": 0, "byteOffset": 68, "byteLength": 8}"#,
    );
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("tri.bin"), &bin).unwrap();
    let path = dir.path().join("embedded.gltf");
    std::fs::write(&path, json).unwrap();
    let err = load_scene(path.to_str().unwrap()).unwrap_err().to_string();
    assert!(
        err.starts_with(path.to_str().unwrap()) && err.contains("image 0 (buffer view 3"),
        "{err}"
    );
}

/// Untextured primitives keep loading with no image at all; a texture needs its TEXCOORD set.
#[test]
fn texture_coordinates_follow_the_textures_set() {
    let dir = tempfile::tempdir().unwrap();
    let buffer = triangle_buffer();
    std::fs::write(dir.path().join("tri.bin"), &buffer).unwrap();
    std::fs::write(dir.path().join("tex.png"), png_2x1()).unwrap();
    let buffer_json = format!(r#"{{"uri": "tri.bin", "byteLength": {}}}"#, buffer.len());
    let json = document(&buffer_json, r#"{"uri": "tex.png"}"#);
    let second_set = json.replace(r#""TEXCOORD_0": 1"#, r#""TEXCOORD_1": 1"#);
    let second_set = second_set.replace(
        r#""baseColorTexture": {"index": 0}"#,
        r#""baseColorTexture": {"index": 0, "texCoord": 1}"#,
    );
    let path = dir.path().join("set1.gltf");
    std::fs::write(&path, &second_set).unwrap();
    let (mesh, _) = read_gltf(&path).unwrap();
    assert_eq!(
        mesh.vertices[1].uv,
        [1.0, 0.0],
        "uv from TEXCOORD_1, not _0"
    );

    let missing_set = json.replace(r#", "TEXCOORD_0": 1"#, "");
    let path = dir.path().join("nouv.gltf");
    std::fs::write(&path, &missing_set).unwrap();
    let err = read_gltf(&path).unwrap_err().to_string();
    assert!(err.contains("TEXCOORD_0"), "{err}");

    let untextured = missing_set.replace(r#", "baseColorTexture": {"index": 0}"#, "");
    let path = dir.path().join("plain.gltf");
    std::fs::write(&path, &untextured).unwrap();
    std::fs::remove_file(dir.path().join("tex.png")).unwrap();
    let (mesh, textures) = read_gltf(&path).unwrap();
    assert_eq!(textures.len(), 1, "only the white layer");
    assert!(mesh.vertices.iter().all(|v| v.layer == 0));
}

/// gltf's URI decoding panics on %-escapes that are not UTF-8; that must come back as an error.
#[test]
fn undecodable_uri_is_an_error_not_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let buffer = triangle_buffer();
    std::fs::write(dir.path().join("tri.bin"), &buffer).unwrap();
    let buffer_json = format!(r#"{{"uri": "tri.bin", "byteLength": {}}}"#, buffer.len());
    let path = dir.path().join("uri.gltf");
    std::fs::write(&path, document(&buffer_json, r#"{"uri": "tex%FF.png"}"#)).unwrap();
    let err = read_gltf(&path).unwrap_err().to_string();
    assert!(
        err.starts_with(path.to_str().unwrap()) && err.contains("tex%FF.png"),
        "{err}"
    );
    let bad_buffer = dir.path().join("buf.gltf");
    std::fs::write(
        &bad_buffer,
        document(
            r#"{"uri": "tri%C3.bin", "byteLength": 68}"#,
            r#"{"uri": "tex.png"}"#,
        ),
    )
    .unwrap();
    let err = read_gltf(&bad_buffer).unwrap_err().to_string();
    assert!(err.contains("tri%C3.bin"), "{err}");
}

/// The triangle document with an external buffer, edited by `edit`; read back.
fn read_edited(edit: impl Fn(String) -> String) -> Result<(Mesh, Vec<Texture>), RenderError> {
    let dir = tempfile::tempdir().unwrap();
    let buffer = triangle_buffer();
    std::fs::write(dir.path().join("tri.bin"), &buffer).unwrap();
    std::fs::write(dir.path().join("tex.png"), png_2x1()).unwrap();
    let buffer_json = format!(r#"{{"uri": "tri.bin", "byteLength": {}}}"#, buffer.len());
    let path = dir.path().join("edited.gltf");
    std::fs::write(&path, edit(document(&buffer_json, r#"{"uri": "tex.png"}"#))).unwrap();
    read_gltf(&path)
}

/// Found by fuzzing: gltf-json's validation indexed the accessors with POSITION unchecked.
#[test]
fn a_position_accessor_out_of_range_is_an_error_not_a_panic() {
    let err = read_edited(|d| d.replace(r#""POSITION": 0"#, r#""POSITION": 7"#)).unwrap_err();
    assert!(err.to_string().contains("accessor 7 out of range"), "{err}");
}

/// Found by fuzzing: a node that is its own descendant recursed until the stack overflowed.
#[test]
fn a_cycle_in_the_node_tree_is_an_error_not_a_stack_overflow() {
    let err = read_edited(|d| {
        d.replace(
            r#"{"mesh": 0, "scale""#,
            r#"{"mesh": 0, "children": [0], "scale""#,
        )
    })
    .unwrap_err();
    assert!(err.to_string().contains("reached twice"), "{err}");
}

/// Found by fuzzing: the gltf crate added a buffer view's offset and length unchecked.
#[test]
fn an_overflowing_buffer_view_is_an_error_not_a_panic() {
    let err = read_edited(|d| {
        d.replace(
            r#""byteOffset": 36, "byteLength": 24"#,
            r#""byteOffset": 18446744073709551615, "byteLength": 24"#,
        )
    })
    .unwrap_err();
    assert!(err.to_string().contains("edited.gltf"), "{err}");
}
