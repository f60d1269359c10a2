//! Scenes: one triangle mesh with baked, view-independent colour, plus the textures it samples,
//! or a Gaussian-splat capture. Built-in procedural scenes (`room0` … `office4`), user meshes
//! (PLY, glTF/GLB, OBJ) and captures (3DGS PLY) all load into the same [`Scene`]: [`load_scene`]
//! picks the source from the name, the file extension and a PLY's header; [`export`] writes the
//! ground-truth mesh as PLY.

pub(crate) mod builtin;
mod content_hash;
pub mod export;
mod gltf;
mod light_layers;
mod load;
mod obj;
mod ply;
pub(crate) mod srgb;

pub use builtin::{agent_trajectory, builtin_path_length, BUILTIN_SCENES};
pub use light_layers::{LightKind, LightLayers, MAX_LIGHT_LAYERS};
pub use load::{load_scene, load_scene_scaled};

use std::sync::Arc;

use rslam_core::splat_io::SplatCloud;
use rslam_core::Trajectory;

/// One mesh vertex. Final surface colour = `color` (sRGB, baked lighting) × `textures[layer]` at `uv`
/// (textures repeat outside [0,1]); both are decoded to linear light before the product.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Vertex {
    /// World coordinates, metres.
    pub position: [f32; 3],
    pub uv: [f32; 2],
    /// sRGB, alpha ignored.
    pub color: [u8; 4],
    /// Index into [`Scene::textures`]; 0 is the 1×1 white texture.
    pub layer: u32,
}

/// Indexed triangle list.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub vertices: Vec<Vertex>,
    /// Three indices per triangle.
    pub indices: Vec<u32>,
}

/// An RGBA8 sRGB texture, rows top to bottom (v = 0 at the top row).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Texture {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
}

impl Texture {
    pub fn white() -> Self {
        Self {
            width: 1,
            height: 1,
            rgba: vec![255; 4],
        }
    }
}

#[derive(Clone, Debug)]
pub struct Scene {
    /// Built-in name or the path it was loaded from.
    pub name: String,
    pub mesh: Mesh,
    /// `textures[0]` is always [`Texture::white`].
    pub textures: Vec<Texture>,
    /// The built-in scenes' default camera path; `None` for user meshes.
    pub default_trajectory: Option<Trajectory>,
    /// Each light's share of the vertex colours, for the light items; `None` for user meshes,
    /// whose light is baked in.
    pub lights: Option<LightLayers>,
    /// A Gaussian-splat capture: the scene is its Gaussians, and `mesh` is empty.
    pub splats: Option<Arc<SplatCloud>>,
    /// Where people can walk: the built-in scenes' floor; `None` for files.
    pub floor: Option<FreeFloor>,
}

/// A built-in room's floor, metres, z = 0: the room spans ±`room_half` about the origin, and the
/// rectangle `free_centre` ± `free_half` is kept clear of anything taller than a table (the
/// default paths walk it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FreeFloor {
    pub room_half: [f32; 2],
    pub free_centre: [f32; 2],
    pub free_half: [f32; 2],
    pub ceiling: f32,
    /// The room's closed door, which `objects` can swing open.
    pub door: Option<Door>,
}

/// A built-in room's door leaf, closed: world metres, z = 0 at its foot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Door {
    /// The foot of the hinge edge on the leaf's room side.
    pub hinge: [f32; 3],
    /// Unit vector along the wall from the hinge to the leaf's free edge.
    pub along: [f32; 2],
    /// Unit vector from the wall into the room: the leaf opens this way.
    pub into_room: [f32; 2],
    pub width: f32,
    pub height: f32,
    /// From the leaf's room side back to the wall.
    pub thickness: f32,
    /// The leaf's and its handle's triangles: `(start, end)` in the scene's index buffer.
    pub indices: [(u32, u32); 2],
}

impl Door {
    /// Whether the scene's index buffer entry `index` is one of the leaf's or handle's.
    pub fn owns(&self, index: usize) -> bool {
        (self.indices.iter()).any(|&(start, end)| (start as usize..end as usize).contains(&index))
    }
}

impl Mesh {
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }
}
