//! glTF 2.0 / GLB reader: every triangle primitive of the default scene, node transforms applied,
//! colour = base-colour factor × COLOR_0 (linear in glTF, stored as sRGB here) × base-colour texture.
//! Only the images a base-colour texture uses are decoded; one that is missing or does not decode
//! is an error naming it, never a stand-in.

use std::collections::HashMap;
use std::path::Path;

use ::gltf::image::{Format, Source};
use ::gltf::mesh::Mode;
use glam::{Mat4, Vec3};
use rslam_core::mesh_io::read_mesh_bytes;
use rslam_core::printable;

use super::srgb::linear_to_srgb;
use super::{Mesh, Texture, Vertex};
use crate::RenderError;

/// Reads the meshes and base-colour textures of a .gltf or .glb file.
pub fn read_gltf(path: &Path) -> Result<(Mesh, Vec<Texture>), RenderError> {
    let bytes = read_mesh_bytes(path)?;
    check_glb_length(path, &bytes)?;
    check_attribute_accessors(path, &bytes)?;
    // The gltf crate (1.4) still panics on some inconsistent files, e.g. a buffer view whose
    // offset + length overflows (found by fuzzing); such a file is refused like any other.
    std::panic::catch_unwind(|| read_document(path, &bytes)).unwrap_or_else(|_| {
        Err(RenderError::bad_mesh(
            path,
            "inconsistent offsets, lengths or indices (the glTF reader failed on them)",
        ))
    })
}

fn read_document(path: &Path, bytes: &[u8]) -> Result<(Mesh, Vec<Texture>), RenderError> {
    let bad = |e: ::gltf::Error| RenderError::bad_mesh(path, e.to_string());
    let ::gltf::Gltf { document, blob } = ::gltf::Gltf::from_slice(bytes).map_err(bad)?;
    let base = path.parent().unwrap_or(Path::new("."));
    // gltf panics on a relative URI whose %-escapes do not decode to UTF-8.
    for buffer in document.buffers() {
        if let ::gltf::buffer::Source::Uri(uri) = buffer.source() {
            check_uri(path, uri)?;
        }
    }
    let buffers = ::gltf::import_buffers(&document, Some(base), blob).map_err(bad)?;
    let mut out = Collector {
        path,
        base,
        mesh: Mesh::default(),
        textures: vec![Texture::white()],
        layer_of_image: HashMap::new(),
        buffers: &buffers,
    };
    let roots: Vec<::gltf::Node> = match document
        .default_scene()
        .or_else(|| document.scenes().next())
    {
        Some(scene) => scene.nodes().collect(),
        // No scene: every node that is nobody's child.
        None => {
            let mut is_child = vec![false; document.nodes().len()];
            for child in document.nodes().flat_map(|n| n.children()) {
                is_child[child.index()] = true;
            }
            document.nodes().filter(|n| !is_child[n.index()]).collect()
        }
    };
    let mut visited = vec![false; document.nodes().len()];
    for node in roots {
        out.node(&node, Mat4::IDENTITY, &mut visited)?;
    }
    Ok((out.mesh, out.textures))
}

/// Bytes of a GLB header: magic, version, total length.
const GLB_HEADER_BYTES: u32 = 12;

/// gltf 1.4's `Glb::from_slice` subtracts the header's size from the total length a GLB states,
/// unchecked (found by fuzzing): a GLB stating less than its own header is refused first.
fn check_glb_length(path: &Path, bytes: &[u8]) -> Result<(), RenderError> {
    let Some(length) = bytes
        .strip_prefix(b"glTF")
        .and_then(|rest| rest.get(4..8))
        .map(|field| u32::from_le_bytes([field[0], field[1], field[2], field[3]]))
    else {
        return Ok(());
    };
    if length < GLB_HEADER_BYTES {
        return Err(RenderError::bad_mesh(
            path,
            format!("GLB header states a length of {length} bytes; expected at least its own {GLB_HEADER_BYTES}"),
        ));
    }
    Ok(())
}

/// gltf-json 1.4's validation indexes the accessor list with a primitive's POSITION accessor
/// unchecked and panics when it is out of range (found by fuzzing), so attribute accessors are
/// checked first on the unvalidated JSON.
fn check_attribute_accessors(path: &Path, bytes: &[u8]) -> Result<(), RenderError> {
    let json = if bytes.starts_with(b"glTF") {
        match ::gltf::Glb::from_slice(bytes) {
            Ok(glb) => glb.json.into_owned(),
            Err(_) => return Ok(()), // the full parse reports it
        }
    } else {
        bytes.to_vec()
    };
    let Ok(root) = ::gltf::json::Root::from_slice(&json) else {
        return Ok(()); // the full parse reports it
    };
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, primitive) in mesh.primitives.iter().enumerate() {
            for index in primitive.attributes.values() {
                if index.value() >= root.accessors.len() {
                    return Err(RenderError::bad_mesh(
                        path,
                        format!(
                            "mesh {m} primitive {p}: accessor {} out of range ({} accessors)",
                            index.value(),
                            root.accessors.len()
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

struct Collector<'a> {
    path: &'a Path,
    /// Where relative URIs point from.
    base: &'a Path,
    mesh: Mesh,
    textures: Vec<Texture>,
    layer_of_image: HashMap<usize, u32>,
    buffers: &'a [::gltf::buffer::Data],
}

impl Collector<'_> {
    /// Walks the node tree; a node met twice (a cycle, or a node with two parents, which glTF
    /// forbids) is an error rather than endless or exponential recursion.
    fn node(
        &mut self,
        node: &::gltf::Node,
        parent: Mat4,
        visited: &mut [bool],
    ) -> Result<(), RenderError> {
        if std::mem::replace(&mut visited[node.index()], true) {
            return Err(RenderError::bad_mesh(
                self.path,
                format!(
                    "node {} is reached twice (the node hierarchy must be a tree)",
                    node.index()
                ),
            ));
        }
        let world = parent * Mat4::from_cols_array_2d(&node.transform().matrix());
        if let Some(mesh) = node.mesh() {
            for primitive in mesh.primitives() {
                self.primitive(&primitive, &world)?;
            }
        }
        for child in node.children() {
            self.node(&child, world, visited)?;
        }
        Ok(())
    }

    fn primitive(
        &mut self,
        primitive: &::gltf::Primitive,
        world: &Mat4,
    ) -> Result<(), RenderError> {
        let mode = primitive.mode();
        if !matches!(
            mode,
            Mode::Triangles | Mode::TriangleStrip | Mode::TriangleFan
        ) {
            return Ok(()); // points and lines have no surface to render
        }
        let reader = primitive.reader(|b| self.buffers.get(b.index()).map(|d| &d.0[..]));
        let positions: Vec<[f32; 3]> = reader
            .read_positions()
            .ok_or_else(|| {
                RenderError::bad_mesh(self.path, "a triangle primitive has no POSITION attribute")
            })?
            .collect();
        let pbr = primitive.material().pbr_metallic_roughness();
        let texture = pbr.base_color_texture();
        let uvs: Vec<[f32; 2]> = match &texture {
            Some(info) => reader
                .read_tex_coords(info.tex_coord())
                .ok_or_else(|| {
                    RenderError::bad_mesh(
                        self.path,
                        format!(
                            "a primitive with a base colour texture has no TEXCOORD_{} attribute",
                            info.tex_coord()
                        ),
                    )
                })?
                .into_f32()
                .collect(),
            None => Vec::new(),
        };
        if texture.is_some() && uvs.len() != positions.len() {
            return Err(RenderError::bad_mesh(
                self.path,
                format!(
                    "{} texture coordinates for {} positions",
                    uvs.len(),
                    positions.len()
                ),
            ));
        }
        let colors: Vec<[f32; 4]> = reader
            .read_colors(0)
            .map(|c| c.into_rgba_f32().collect())
            .unwrap_or_default();
        let factor = pbr.base_color_factor();
        let layer = match &texture {
            Some(info) => self.layer(&info.texture().source())?,
            None => 0,
        };
        let base = self.mesh.vertices.len() as u32;
        for (i, p) in positions.iter().enumerate() {
            let c = colors.get(i).copied().unwrap_or([1.0; 4]);
            let rgb: [u8; 3] = std::array::from_fn(|k| linear_to_srgb(c[k] * factor[k]));
            self.mesh.vertices.push(Vertex {
                position: world.transform_point3(Vec3::from(*p)).into(),
                uv: uvs.get(i).copied().unwrap_or([0.0; 2]),
                color: [rgb[0], rgb[1], rgb[2], 255],
                layer,
            });
        }
        let indices: Vec<u32> = match reader.read_indices() {
            Some(idx) => idx.into_u32().collect(),
            None => (0..positions.len() as u32).collect(),
        };
        if let Some(&bad) = indices.iter().find(|&&i| i as usize >= positions.len()) {
            return Err(RenderError::bad_mesh(
                self.path,
                format!("index {bad} out of range for {} vertices", positions.len()),
            ));
        }
        let flip = world.determinant() < 0.0;
        let mut push = |a: u32, b: u32, c: u32| {
            let (b, c) = if flip { (c, b) } else { (b, c) };
            self.mesh
                .indices
                .extend_from_slice(&[base + a, base + b, base + c]);
        };
        match mode {
            Mode::Triangles => indices.chunks_exact(3).for_each(|t| push(t[0], t[1], t[2])),
            Mode::TriangleStrip => {
                for k in 0..indices.len().saturating_sub(2) {
                    let (a, b, c) = (indices[k], indices[k + 1], indices[k + 2]);
                    if k % 2 == 0 {
                        push(a, b, c)
                    } else {
                        push(b, a, c)
                    }
                }
            }
            _ => {
                for k in 1..indices.len().saturating_sub(1) {
                    push(indices[0], indices[k], indices[k + 1]);
                }
            }
        }
        Ok(())
    }

    /// The texture layer of an image, decoding it on first use.
    fn layer(&mut self, image: &::gltf::Image) -> Result<u32, RenderError> {
        if let Some(&layer) = self.layer_of_image.get(&image.index()) {
            return Ok(layer);
        }
        let bad = |message: String| RenderError::BadTexture {
            path: self.path.to_path_buf(),
            texture: printable(&self.describe(image)),
            message,
        };
        if let Source::Uri { uri, .. } = image.source() {
            check_uri(self.path, uri)?;
        }
        let data = ::gltf::image::Data::from_source(image.source(), Some(self.base), self.buffers)
            .map_err(|e| bad(e.to_string()))?;
        let texture = to_rgba8(&data)
            .ok_or_else(|| bad(format!("unsupported pixel format {:?}", data.format)))?;
        if texture.width == 0 || texture.height == 0 {
            return Err(bad(format!(
                "empty image ({}×{})",
                texture.width, texture.height
            )));
        }
        self.textures.push(texture);
        let layer = self.textures.len() as u32 - 1;
        self.layer_of_image.insert(image.index(), layer);
        Ok(layer)
    }

    /// The image file an error is about: its path, or where in the glTF it is embedded.
    fn describe(&self, image: &::gltf::Image) -> String {
        match image.source() {
            Source::Uri { uri, .. } if uri.starts_with("data:") => {
                format!("image {} (data URI)", image.index())
            }
            Source::Uri { uri, .. } => self.base.join(uri).display().to_string(),
            Source::View { view, mime_type } => format!(
                "image {} (buffer view {}, {mime_type})",
                image.index(),
                view.index()
            ),
        }
    }
}

/// A relative URI is %-decoded by gltf, which panics unless the result is UTF-8: an error here.
fn check_uri(path: &Path, uri: &str) -> Result<(), RenderError> {
    if uri.contains(':') {
        return Ok(()); // data: and file: URIs are not %-decoded
    }
    let bytes = uri.as_bytes();
    let hex = |b: u8| (b as char).to_digit(16);
    let mut decoded = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        match (
            bytes[i],
            bytes.get(i + 1).copied().and_then(hex),
            bytes.get(i + 2).copied().and_then(hex),
        ) {
            (b'%', Some(hi), Some(lo)) => {
                decoded.push((hi * 16 + lo) as u8);
                i += 3;
            }
            (b, _, _) => {
                decoded.push(b);
                i += 1;
            }
        }
    }
    match std::str::from_utf8(&decoded) {
        Ok(_) => Ok(()),
        Err(_) => Err(RenderError::bad_mesh(
            path,
            format!("URI '{uri}' does not %-decode to UTF-8"),
        )),
    }
}

fn to_rgba8(data: &::gltf::image::Data) -> Option<Texture> {
    let (channels, bytes_per_channel) = match data.format {
        Format::R8 => (1, 1),
        Format::R8G8 => (2, 1),
        Format::R8G8B8 => (3, 1),
        Format::R8G8B8A8 => (4, 1),
        Format::R16 => (1, 2),
        Format::R16G16 => (2, 2),
        Format::R16G16B16 => (3, 2),
        Format::R16G16B16A16 => (4, 2),
        _ => return None,
    };
    let stride = channels * bytes_per_channel;
    // 16-bit channels: keep the high byte (little-endian storage).
    let channel = |px: &[u8], c: usize| px[c * bytes_per_channel + bytes_per_channel - 1];
    let rgba = data
        .pixels
        .chunks_exact(stride)
        .flat_map(|px| match channels {
            1 | 2 => [channel(px, 0); 3].into_iter().chain([if channels == 2 {
                channel(px, 1)
            } else {
                255
            }]),
            _ => [channel(px, 0), channel(px, 1), channel(px, 2)]
                .into_iter()
                .chain([if channels == 4 { channel(px, 3) } else { 255 }]),
        })
        .collect();
    Some(Texture {
        width: data.width,
        height: data.height,
        rgba,
    })
}

#[cfg(test)]
mod tests;
