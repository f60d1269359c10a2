//! Actors: people who walk through a scene while it is filmed, or a user's rigid meshes moved
//! along path files ([`RigidActor`]). Each walker is an articulated body ([`WalkerBody`]) on a
//! closed path over the scene's free floor ([`WalkPath`]), planned so that no walker ever touches
//! the scene, another walker or the camera ([`plan`]); a user's path is checked to keep clear of
//! the scene and the camera. At any instant [`Actors::mesh_at`] gives their posed triangles, lit
//! by the scene's light layers ([`light_probe`]), for the rasterizer and the ray-cast oracle
//! alike.

mod ahead;
mod floor_map;
mod footprint;
mod light_probe;
mod objects;
mod plan;
mod rigid;
mod walk_path;
mod walker;

pub use floor_map::FloorMap;
pub use footprint::Footprint;
pub use objects::ObjectParams;
pub use plan::{CameraTrack, WalkerParams, CAMERA_CLEARANCE, SEEN_DISTANCE, SEEN_HALF_ANGLE};
pub use rigid::{MovedObject, RigidActor, RigidLight, RigidOrigin};
pub use walk_path::{Route, Stride, WalkPath};
pub use walker::{BodyMaterial, PosedMesh, WalkerBody, MAX_STRIDE};

use glam::{Quat, Vec2, Vec3};

use crate::scene::srgb::{linear_to_srgb, unit_srgb_to_linear};
use crate::{Door, FreeFloor, Mesh, RenderError, Scene, Texture, Vertex};
use light_probe::{cube_light, AmbientCube, LightProbe, PROBE_HEIGHTS};
use plan::Walking;

/// Metres of cloth per texture repeat.
const CLOTH_REPEAT_M: f32 = 0.5;

/// One walker: its body, its path and what it wears.
#[derive(Clone, Debug)]
pub struct Walker {
    pub body: WalkerBody,
    /// What it covers of the floor at its stride.
    pub footprint: Footprint,
    pub path: WalkPath,
    /// Step length, metres.
    pub stride: f32,
    /// Colour of each [`BodyMaterial`], sRGB in [0, 1] (white on a patterned top: its texture
    /// has the colours).
    pub colours: [[f32; 3]; 6],
    /// What its top is made of: 0 plain cloth (its colour), else a patterned top, the texture
    /// of that index among the clothes' (`scene::builtin::clothing_textures`).
    pub top: usize,
    /// The nearest its body comes to the camera centre, metres.
    pub closest_m: f32,
    /// The nearest it comes while in front of the camera (its centre within 40° of the camera's
    /// axis over the floor), metres; `None` when it never is. More than the severity's closest
    /// approach where the floor the camera looks over has no room that near.
    pub closest_in_view_m: Option<f32>,
    /// The share of the sequence it walks on, rather than waiting or stepping back to give way.
    pub walking_share: f32,
    /// The share of the sequence its centre is in front of the camera (within 40° of its axis
    /// over the floor, under 4 m away).
    pub in_view_share: f32,
    /// How far in front of the camera it keeps, metres, if it is the walker ahead of it: AHEAD,
    /// or nearer where the floor had no way for it that far.
    pub ahead_m: Option<f32>,
}

/// Where a walker is at an instant, for the manifest.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WalkerPose {
    /// The body's axis on the floor, metres.
    pub position: Vec2,
    /// Direction of travel, radians from +x towards +y.
    pub heading: f32,
    /// Gait phase, turns.
    pub phase: f32,
    /// Step length now, metres: the walker's stride, shorter as it slows, 0 standing.
    pub step: f32,
}

/// What moves through a scene, as a job asks for it.
#[derive(Clone, Debug, Default)]
pub struct World<'a> {
    pub walkers: Option<&'a WalkerParams>,
    pub objects: Option<&'a ObjectParams>,
    /// Rigid meshes along a user's path files: walkers and objects give way to them.
    pub user: Vec<RigidActor>,
}

/// The walkers, the user's actors and the moved objects of a job and what lights them.
pub struct Actors {
    walkers: Vec<Walker>,
    rigid: Vec<RigidActor>,
    /// Texture layer of each rigid actor's first texture (0 for one that uses the scene's).
    rigid_layers: Vec<u32>,
    /// The scene's door, when the actors swing it: its triangles are theirs, not the room's.
    swung_door: Option<Door>,
    probe: LightProbe,
    /// Texture layer of the first clothing texture: the scene's own come first.
    first_cloth: u32,
    textures: Vec<Texture>,
}

/// The actors' triangles at an instant: scene vertices (texture layers after the scene's), and
/// their light as layers like the scene's (`light[v * layers + l]`, linear RGB).
#[derive(Clone, Debug, Default)]
pub struct ActorMesh {
    pub mesh: Mesh,
    pub light: Vec<[f32; 3]>,
    /// The vertices of actor k (the walkers, then the user's actors); instance masks give them
    /// id k + 1.
    pub actor_vertices: Vec<std::ops::Range<usize>>,
}

impl ActorMesh {
    /// The instance-mask id of each vertex: k + 1 on actor k.
    pub fn vertex_ids(&self) -> Vec<u32> {
        let mut ids = vec![0; self.mesh.vertices.len()];
        for (k, range) in self.actor_vertices.iter().enumerate() {
            ids[range.clone()].fill(k as u32 + 1);
        }
        ids
    }
}

impl Actors {
    /// The world of `scene`: the user's actors, each path checked to keep clear of the scene and
    /// of the camera on `camera`; then walkers and moved objects as `world` says, drawn from
    /// `seed`, clear of the camera and of everything planned before them (walkers give way to
    /// the user's actors, objects to both).
    pub fn plan(
        scene: &Scene,
        world: World,
        seed: u64,
        camera: &CameraTrack,
    ) -> Result<Self, RenderError> {
        let (mut actors, floor) = Self::lit_by(scene)?;
        let map = FloorMap::new(&scene.mesh, &floor, plan::TALLEST);
        for actor in &world.user {
            actor.check(&map, camera)?;
            let first = actors.first_cloth + actors.textures.len() as u32;
            actors.rigid_layers.push(first);
            actors.textures.extend(actor.textures.iter().cloned());
        }
        actors.rigid = world.user;
        let refused = |message| refusal(scene, message);
        let given_way = (Vec::new(), &actors.rigid[..]);
        if let Some(walkers) = world.walkers {
            let freely = (walkers, Walking::Freely);
            actors.walkers =
                plan::walkers(&map, freely, seed, camera, given_way).map_err(refused)?;
        }
        if let Some(carriers) = world.objects.and_then(ObjectParams::box_carriers) {
            let carrying = (&carriers, Walking::Carrying);
            let given_way = (std::mem::take(&mut actors.walkers), &actors.rigid[..]);
            actors.walkers =
                plan::walkers(&map, carrying, seed, camera, given_way).map_err(refused)?;
        }
        if let Some(objects) = world.objects {
            let around = (camera, &actors.walkers[..], &actors.rigid[..]);
            let moved = objects::plan(scene, &map, objects, seed, around).map_err(refused)?;
            for object in moved {
                if let RigidOrigin::Object(MovedObject { kind: "door", .. }) = object.origin {
                    actors.swung_door = floor.door;
                }
                actors.rigid_layers.push(0);
                actors.rigid.push(object);
            }
        }
        Ok(actors)
    }

    /// No actors yet in `scene`, with the light that will light them, and its floor.
    fn lit_by(scene: &Scene) -> Result<(Self, FreeFloor), RenderError> {
        let (Some(floor), Some(probe)) = (scene.floor, LightProbe::new(scene)) else {
            return Err(refusal(
                scene,
                "people walk over a built-in scene's free floor; this scene has none".into(),
            ));
        };
        let actors = Self {
            walkers: Vec::new(),
            rigid: Vec::new(),
            rigid_layers: Vec::new(),
            swung_door: None,
            probe,
            first_cloth: scene.textures.len() as u32,
            textures: crate::scene::builtin::clothing_textures(),
        };
        Ok((actors, floor))
    }

    /// The scene's triangles less those the actors take over.
    pub fn scene_indices<'a>(&self, scene: &'a Scene) -> std::borrow::Cow<'a, [u32]> {
        let Some(door) = &self.swung_door else {
            return std::borrow::Cow::Borrowed(&scene.mesh.indices);
        };
        let kept = (scene.mesh.indices.chunks_exact(3).enumerate())
            .filter(|(t, _)| !door.owns(3 * t))
            .flat_map(|(_, corners)| corners.iter().copied());
        std::borrow::Cow::Owned(kept.collect())
    }

    pub fn rigid_actors(&self) -> &[RigidActor] {
        &self.rigid
    }

    pub fn walkers(&self) -> &[Walker] {
        &self.walkers
    }

    /// The textures the actors' vertices refer to, to be appended to the scene's.
    pub fn textures(&self) -> &[Texture] {
        &self.textures
    }

    pub fn layer_count(&self) -> usize {
        self.probe.layer_count()
    }

    /// Every walker's pose `t` seconds from the start.
    pub fn poses_at(&self, t: f64) -> Vec<WalkerPose> {
        self.walkers
            .iter()
            .map(|w| {
                let stride = w.path.at(t);
                WalkerPose {
                    position: stride.position,
                    heading: stride.heading,
                    phase: phase(stride.walked, w.stride),
                    step: w.stride * stride.pace,
                }
            })
            .collect()
    }

    /// The walkers and the user's actors posed `t` seconds from the start, in world
    /// coordinates, lit by the scene.
    pub fn mesh_at(&self, t: f64) -> ActorMesh {
        let mut out = ActorMesh::default();
        let mut posed = PosedMesh::default();
        for (walker, pose) in self.walkers.iter().zip(self.poses_at(t)) {
            posed.positions.clear();
            posed.normals.clear();
            posed.uvs.clear();
            posed.materials.clear();
            posed.indices.clear();
            walker.body.pose(pose.phase, pose.step, &mut posed);
            let turn = Quat::from_rotation_z(pose.heading);
            let origin = pose.position.extend(0.0);
            let cubes = self.probe.cubes_at(pose.position);
            let base = out.mesh.vertices.len() as u32;
            for i in 0..posed.positions.len() {
                let position = origin + turn * posed.positions[i];
                let normal = turn * posed.normals[i];
                let material = posed.materials[i];
                let tint = walker.colours[material as usize].map(unit_srgb_to_linear);
                let color = self.light(&cubes, position, normal, tint, &mut out.light);
                out.mesh.vertices.push(Vertex {
                    position: position.into(),
                    uv: (posed.uvs[i] / CLOTH_REPEAT_M).into(),
                    color,
                    layer: self.texture_of(walker, material),
                });
            }
            out.mesh
                .indices
                .extend(posed.indices.iter().map(|&i| base + i));
            (out.actor_vertices).push(base as usize..out.mesh.vertices.len());
        }
        for (actor, &first_layer) in self.rigid.iter().zip(&self.rigid_layers) {
            let (moving, still) = (actor.pose_at(t), actor.rest_pose());
            let cubes = self.probe.cubes_at(moving.1.truncate());
            let base = out.mesh.vertices.len() as u32;
            let vertices = actor.mesh.vertices.iter().zip(&actor.normals);
            for (i, (v, normal)) in vertices.enumerate() {
                let (turn, origin) = if i < actor.still_from { moving } else { still };
                let position = origin + turn * Vec3::from(v.position);
                let color = match &actor.light {
                    RigidLight::Probe => {
                        let tint =
                            [0, 1, 2].map(|c| unit_srgb_to_linear(f32::from(v.color[c]) / 255.0));
                        self.light(&cubes, position, turn * *normal, tint, &mut out.light)
                    }
                    RigidLight::Baked(layers) => {
                        let count = self.layer_count();
                        out.light
                            .extend_from_slice(&layers[i * count..(i + 1) * count]);
                        v.color
                    }
                };
                out.mesh.vertices.push(Vertex {
                    position: position.into(),
                    uv: v.uv,
                    color,
                    layer: first_layer + v.layer,
                });
            }
            (out.mesh.indices).extend(actor.mesh.indices.iter().map(|&i| base + i));
            (out.actor_vertices).push(base as usize..out.mesh.vertices.len());
        }
        out
    }

    /// A surface of linear colour `tint` at `position` facing `normal`: its light per layer
    /// (pushed onto `light`), and the sum as an sRGB vertex colour.
    fn light(
        &self,
        cubes: &[AmbientCube],
        position: Vec3,
        normal: Vec3,
        tint: [f32; 3],
        light: &mut Vec<[f32; 3]>,
    ) -> [u8; 4] {
        let mut total = Vec3::ZERO;
        for layer in 0..self.layer_count() {
            let lit = probe_light(cubes, position.z, normal, layer) * Vec3::from(tint);
            total += lit;
            light.push(lit.into());
        }
        let [r, g, b] = total.to_array().map(linear_to_srgb);
        [r, g, b, 255]
    }

    fn texture_of(&self, walker: &Walker, material: BodyMaterial) -> u32 {
        match material {
            BodyMaterial::Top => self.first_cloth + walker.top as u32,
            BodyMaterial::Trousers => self.first_cloth + 1,
            BodyMaterial::Shoes => self.first_cloth + 2,
            BodyMaterial::Skin | BodyMaterial::Hair | BodyMaterial::Carton => 0,
        }
    }
}

fn refusal(scene: &Scene, message: String) -> RenderError {
    RenderError::Actors {
        name: scene.name.clone(),
        message,
    }
}

/// Gait phase in turns after `walked` metres with steps of `stride` (a cycle is two steps).
fn phase(walked: f32, stride: f32) -> f32 {
    (walked / (2.0 * stride)).rem_euclid(1.0)
}

/// The light of `layer` on a surface at height `z` facing `normal`, between the probes.
fn probe_light(cubes: &[AmbientCube], z: f32, normal: Vec3, layer: usize) -> Vec3 {
    let last = PROBE_HEIGHTS.len() - 1;
    let k = PROBE_HEIGHTS.partition_point(|&h| h <= z).clamp(1, last);
    let (lo, hi) = (PROBE_HEIGHTS[k - 1], PROBE_HEIGHTS[k]);
    let f = ((z - lo) / (hi - lo)).clamp(0.0, 1.0);
    cube_light(&cubes[k - 1], normal, layer).lerp(cube_light(&cubes[k], normal, layer), f)
}
