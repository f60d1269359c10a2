//! Mesh files as `rslam render --scene FILE` loads them: PLY, OBJ with its MTL, glTF and GLB;
//! and Gaussian-splat captures (3DGS PLY).

use std::path::Path;

use rslam_core::limits::{MAX_MESH_TRIANGLES, MAX_MESH_VERTICES};
use rslam_render::{load_scene, Scene};

use crate::Scratch;

pub const PLY: &str = "mesh.ply";
pub const CAPTURE: &str = "capture.ply";
pub const OBJ: &str = "mesh.obj";
pub const MTL: &str = "mesh.mtl";
pub const GLTF: &str = "mesh.gltf";
pub const GLB: &str = "mesh.glb";

/// The material library the `obj` target's seeds use, and the OBJ the `mtl` target's seeds
/// are used by.
const FIXED_MTL: &str = "newmtl red\nKd 0.8 0.1 0.1\nnewmtl tex\nKd 1 1 1\nmap_Kd tex.png\n";
const FIXED_OBJ: &str =
    "mtllib mesh.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n\
                         usemtl red\nf 1 2 3\nusemtl tex\nf 2/2 4/3 3/1\n";
/// A 1×1 PNG for `map_Kd`.
const TEX_PNG: &[u8] = include_bytes!("../../corpus/image/one_pixel.png");

pub fn prepare_obj(dir: &Path) -> std::io::Result<()> {
    std::fs::write(dir.join(MTL), FIXED_MTL)?;
    std::fs::write(dir.join("tex.png"), TEX_PNG)
}

pub fn prepare_mtl(dir: &Path) -> std::io::Result<()> {
    std::fs::write(dir.join(OBJ), FIXED_OBJ)?;
    std::fs::write(dir.join("tex.png"), TEX_PNG)
}

pub fn ply(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    load(scratch, PLY, input)
}

/// A capture, which the renderer can draw when accepted: finite values, a degree of 0 to 3 with
/// its coefficients, a rotation that is not zero, one of each per Gaussian.
pub fn capture(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    let path = scratch.write(CAPTURE, input)?;
    let scene = load_scene(&path.display().to_string()).map_err(|e| e.to_string())?;
    check_scene(&scene);
    let Some(cloud) = &scene.splats else {
        return Ok(()); // read as a mesh: checked above
    };
    let n = cloud.len();
    assert!(n > 0, "accepted a capture of no Gaussians");
    assert!(cloud.sh_degree <= 3, "accepted degree {}", cloud.sh_degree);
    assert_eq!(
        cloud.sh.len(),
        n * cloud.coefficients(),
        "coefficients per Gaussian"
    );
    let lengths = [
        cloud.opacity_logits.len(),
        cloud.log_scales.len(),
        cloud.rotations.len(),
    ];
    assert_eq!(lengths, [n; 3], "one of each per Gaussian");
    let values = (cloud.means.iter().flatten())
        .chain(cloud.sh.iter().flatten())
        .chain(&cloud.opacity_logits)
        .chain(cloud.log_scales.iter().flatten())
        .chain(cloud.rotations.iter().flatten());
    assert!(
        values.clone().all(|v| v.is_finite()),
        "accepted a value that is not finite"
    );
    let zero = cloud
        .rotations
        .iter()
        .position(|q| q.iter().all(|&c| c == 0.0));
    assert!(zero.is_none(), "accepted a zero rotation at {zero:?}");
    Ok(())
}

pub fn obj(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    load(scratch, OBJ, input)
}

/// The fixed OBJ with the input as its material library.
pub fn mtl(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    scratch.write(MTL, input)?;
    let scene =
        load_scene(&scratch.dir.join(OBJ).display().to_string()).map_err(|e| e.to_string())?;
    check_scene(&scene);
    Ok(())
}

pub fn gltf(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    load(scratch, GLTF, input)
}

pub fn glb(scratch: &Scratch, input: &[u8]) -> Result<(), String> {
    load(scratch, GLB, input)
}

fn load(scratch: &Scratch, file: &str, input: &[u8]) -> Result<(), String> {
    let path = scratch.write(file, input)?;
    let scene = load_scene(&path.display().to_string()).map_err(|e| e.to_string())?;
    check_scene(&scene);
    Ok(())
}

/// An accepted scene is one the renderer can draw: finite positions, indices and texture layers
/// in range, texture sizes that match their pixels, within the mesh limits.
fn check_scene(scene: &Scene) {
    let mesh = &scene.mesh;
    assert!(
        mesh.vertices.len() <= MAX_MESH_VERTICES,
        "accepted {} vertices",
        mesh.vertices.len()
    );
    assert!(
        mesh.triangle_count() <= MAX_MESH_TRIANGLES,
        "accepted {} triangles",
        mesh.triangle_count()
    );
    assert_eq!(mesh.indices.len() % 3, 0, "indices not in threes");
    if let Some(i) = mesh
        .indices
        .iter()
        .find(|&&i| i as usize >= mesh.vertices.len())
    {
        panic!("accepted index {i} of {} vertices", mesh.vertices.len());
    }
    for (i, v) in mesh.vertices.iter().enumerate() {
        assert!(
            v.position.iter().all(|c| c.is_finite()),
            "vertex {i}: accepted position {:?}",
            v.position
        );
        assert!(
            v.uv.iter().all(|c| c.is_finite()),
            "vertex {i}: accepted texture coordinates {:?}",
            v.uv
        );
        assert!(
            (v.layer as usize) < scene.textures.len(),
            "vertex {i}: layer {} of {} textures",
            v.layer,
            scene.textures.len()
        );
    }
    for (layer, t) in scene.textures.iter().enumerate() {
        assert_eq!(
            t.rgba.len(),
            t.width as usize * t.height as usize * 4,
            "texture {layer}: {}x{} with {} bytes",
            t.width,
            t.height,
            t.rgba.len()
        );
    }
}
