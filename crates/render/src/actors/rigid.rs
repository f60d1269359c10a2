//! A rigid actor: a mesh moved along timed poses, linear in position and spherical in rotation
//! between them, at rest before the first and after the last. Either a user's: a mesh file (PLY,
//! OBJ or glTF, in its own frame, z up) along a path file in any trajectory format rslam reads,
//! whose footprint on the floor (the circle round its origin that holds every vertex) is checked
//! every few milliseconds to keep clear of walls, furniture and the camera, an error naming the
//! path file's line; or one of the things `objects` moves (a door, a pushed chair), planned
//! clear of everything by [`super::objects`].

use std::path::{Path, PathBuf};

use glam::{DQuat, Quat, Vec2, Vec3};
use rslam_core::trajectory_io::{read_trajectory_with, ReadOptions};
use rslam_core::{read_text_file, Pose, Trajectory};

use super::plan::{CameraTrack, CAMERA_CLEARANCE};
use super::FloorMap;
use crate::{load_scene, Mesh, RenderError, Texture};

/// A rigid mesh along its path.
#[derive(Clone, Debug)]
pub struct RigidActor {
    pub origin: RigidOrigin,
    /// In its own frame; texture layers index [`RigidActor::textures`], or the scene's when it
    /// has none of its own.
    pub mesh: Mesh,
    /// Per vertex, its own frame.
    pub normals: Vec<Vec3>,
    pub textures: Vec<Texture>,
    pub light: RigidLight,
    /// Vertices from this one on stay where the first pose puts them (the dark opening a door
    /// leaves as it swings).
    pub still_from: usize,
    /// The radius round its origin, over the floor, that holds every vertex, metres.
    pub radius: f32,
    times: Vec<f64>,
    /// The mesh's frame in the world at each time.
    poses: Vec<Pose>,
}

/// Where a rigid actor comes from.
#[derive(Clone, Debug)]
pub enum RigidOrigin {
    /// A user's mesh and path files, with the BLAKE3 (hex) of each as read and the path file's
    /// line of each pose.
    Files {
        mesh_file: PathBuf,
        path_file: PathBuf,
        mesh_blake3: String,
        path_blake3: String,
        lines: Vec<usize>,
    },
    /// A thing `objects` moves.
    Object(MovedObject),
}

/// What `objects` moved, for the manifest.
#[derive(Clone, Debug, PartialEq)]
pub struct MovedObject {
    /// `door` or `chair`.
    pub kind: &'static str,
    /// Seconds from the start at which it starts and stops moving (a door: opening, then
    /// closing).
    pub moves: Vec<[f64; 2]>,
    /// The nearest its footprint comes to the camera centre, metres.
    pub closest_m: f32,
}

/// How a rigid actor is lit.
#[derive(Clone, Debug)]
pub enum RigidLight {
    /// By the scene's light probe where it stands, its vertex colours as albedo.
    Probe,
    /// As the scene baked it in place (a door of the scene): its vertex colours and, per
    /// vertex and light layer, linear RGB (`layers[v * count + l]`).
    Baked(Vec<[f32; 3]>),
}

impl RigidActor {
    /// A planned object: `mesh` in its own frame at `path`'s poses.
    pub(super) fn object(
        object: MovedObject,
        (mesh, light, still_from): (Mesh, RigidLight, usize),
        path: Trajectory,
    ) -> Self {
        Self {
            origin: RigidOrigin::Object(object),
            normals: vertex_normals(&mesh),
            radius: footprint_radius(&mesh),
            mesh,
            textures: Vec::new(),
            light,
            still_from,
            times: path.timestamps,
            poses: path.poses,
        }
    }

    pub(super) fn set_closest(&mut self, closest_m: f32) {
        if let RigidOrigin::Object(object) = &mut self.origin {
            object.closest_m = closest_m;
        }
    }

    /// The fastest its origin moves over the floor, metres per second.
    pub fn top_speed(&self) -> f32 {
        (self.times.windows(2).zip(self.poses.windows(2)))
            .map(|(t, p)| {
                let d = (p[1].translation - p[0].translation).truncate().length();
                (d / (t[1] - t[0]).max(1e-9)) as f32
            })
            .fold(0.0, f32::max)
    }

    /// Where its first pose puts it: where its still vertices stay.
    pub fn rest_pose(&self) -> (Quat, Vec3) {
        self.pose_at(f64::NEG_INFINITY)
    }

    /// Reads `mesh_file` and `path_file`; an error names the file that cannot be read.
    pub fn load(mesh_file: &Path, path_file: &Path) -> Result<Self, RenderError> {
        let scene = load_scene(&mesh_file.to_string_lossy())?;
        if scene.mesh.indices.is_empty() {
            return Err(RenderError::BadMesh {
                path: mesh_file.into(),
                message: "an actor needs triangles; the file has none".into(),
            });
        }
        let path = read_trajectory_with(path_file, &ReadOptions::default())?.trajectory;
        // Each pose is on one line that is neither blank nor a comment or header.
        let text = read_text_file(path_file, "a path file")?;
        let mesh_bytes = std::fs::read(mesh_file).map_err(|source| RenderError::Io {
            path: mesh_file.into(),
            source,
        })?;
        let lines: Vec<usize> = (text.lines().enumerate())
            .filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'))
            .map(|(i, _)| i + 1)
            .collect();
        Ok(Self {
            origin: RigidOrigin::Files {
                mesh_file: mesh_file.into(),
                path_file: path_file.into(),
                mesh_blake3: blake3::hash(&mesh_bytes).to_hex().to_string(),
                path_blake3: blake3::hash(text.as_bytes()).to_hex().to_string(),
                lines: lines.into_iter().take(path.poses.len()).collect(),
            },
            normals: vertex_normals(&scene.mesh),
            radius: footprint_radius(&scene.mesh),
            still_from: scene.mesh.vertices.len(),
            mesh: scene.mesh,
            textures: scene.textures,
            light: RigidLight::Probe,
            times: path.timestamps,
            poses: path.poses,
        })
    }

    /// Its rotation and position in the world `t` seconds from the start.
    pub fn pose_at(&self, t: f64) -> (Quat, Vec3) {
        let i = self.times.partition_point(|&x| x <= t);
        let pose = match i {
            0 => self.poses[0],
            i if i == self.times.len() => self.poses[i - 1],
            i => {
                let (t0, t1) = (self.times[i - 1], self.times[i]);
                let f = (t - t0) / (t1 - t0);
                let (a, b) = (self.poses[i - 1], self.poses[i]);
                Pose::new(
                    a.rotation.slerp(b.rotation, f),
                    a.translation.lerp(b.translation, f),
                )
            }
        };
        (quat(pose.rotation), pose.translation.as_vec3())
    }

    /// The path file's lines of the poses `t` lies between ("lines 11-12"), or of the pose at
    /// it or that it rests at before the first and after the last ("line 11").
    fn lines_at(&self, lines: &[usize], t: f64) -> String {
        let i = self.times.partition_point(|&x| x <= t);
        let line = |k: usize| lines.get(k).copied().unwrap_or(0);
        match i {
            0 => format!("line {}", line(0)),
            i if i == self.times.len() || self.times[i - 1] == t => format!("line {}", line(i - 1)),
            i => format!("lines {}-{}", line(i - 1), line(i)),
        }
    }

    /// Whether a user's actor's footprint keeps clear of walls and furniture (`map`) and of the
    /// camera (`camera`) over the camera's time, checked every 5 ms ([`CameraTrack::instants`]);
    /// the error names the path file and line. A planned object is clear by its plan.
    pub fn check(&self, map: &FloorMap, camera: &CameraTrack) -> Result<(), RenderError> {
        let RigidOrigin::Files {
            path_file, lines, ..
        } = &self.origin
        else {
            return Ok(());
        };
        for t in camera.instants() {
            let at = self.pose_at(t).1.truncate();
            let clearance = map.clearance(at);
            let to_camera = at.distance(camera.at(t).truncate());
            let problem = if to_camera < self.radius + CAMERA_CLEARANCE {
                Some(format!(
                    "at {t:.3} s the actor (its footprint {:.2} m round its origin) is {to_camera:.2} m from the camera; expected at least {:.2} m",
                    self.radius,
                    self.radius + CAMERA_CLEARANCE
                ))
            } else if clearance < self.radius {
                Some(format!(
                    "at {t:.3} s the actor (its footprint {:.2} m round its origin) is {clearance:.2} m from a wall or furniture, or off the floor; expected a path over the free floor",
                    self.radius
                ))
            } else {
                None
            };
            if let Some(message) = problem {
                return Err(RenderError::BadMesh {
                    path: path_file.clone(),
                    message: format!("{}: {message}", self.lines_at(lines, t)),
                });
            }
        }
        Ok(())
    }
}

fn quat(q: DQuat) -> Quat {
    Quat::from_xyzw(q.x as f32, q.y as f32, q.z as f32, q.w as f32)
}

/// The radius round the origin, over the floor, that holds every vertex of `mesh`.
fn footprint_radius(mesh: &Mesh) -> f32 {
    (mesh.vertices.iter())
        .map(|v| Vec2::new(v.position[0], v.position[1]).length())
        .fold(0.0, f32::max)
}

/// Area-weighted vertex normals.
fn vertex_normals(mesh: &Mesh) -> Vec<Vec3> {
    let mut normals = vec![Vec3::ZERO; mesh.vertices.len()];
    for t in mesh.indices.chunks_exact(3) {
        let [a, b, c] = [t[0], t[1], t[2]].map(|i| Vec3::from(mesh.vertices[i as usize].position));
        let n = (b - a).cross(c - a);
        for &i in t {
            normals[i as usize] += n;
        }
    }
    normals.iter().map(|n| n.normalize_or(Vec3::Z)).collect()
}

#[cfg(test)]
mod tests {
    use std::f32::consts::FRAC_PI_2;

    use glam::{Quat, Vec3};

    use super::RigidActor;

    const TRIANGLE_PLY: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0.3 0 0\n0 0.4 0\n0 0 1\n3 0 1 2\n";

    /// Between poses a pose is linear in position and spherical in rotation; before the first
    /// and after the last the actor rests; lines are the file's, comments counted.
    #[test]
    fn poses_between_lines_and_at_rest_outside_them() {
        let dir = tempfile::tempdir().unwrap();
        let mesh = dir.path().join("tri.ply");
        let path = dir.path().join("path.txt");
        std::fs::write(&mesh, TRIANGLE_PLY).unwrap();
        let turn = Quat::from_rotation_z(FRAC_PI_2);
        std::fs::write(
            &path,
            format!(
                "# t x y z qx qy qz qw\n1 0 0 0 0 0 0 1\n\n3 2 4 0 {} {} {} {}\n",
                turn.x, turn.y, turn.z, turn.w
            ),
        )
        .unwrap();
        let actor = RigidActor::load(&mesh, &path).unwrap();
        assert!((actor.radius - 0.4).abs() < 1e-6);
        let (rotation, position) = actor.pose_at(2.0);
        assert!(position.distance(Vec3::new(1.0, 2.0, 0.0)) < 1e-5);
        assert!(rotation.angle_between(Quat::from_rotation_z(FRAC_PI_2 / 2.0)) < 1e-5);
        assert_eq!(actor.pose_at(0.0).1, Vec3::ZERO);
        assert!(actor.pose_at(9.0).1.distance(Vec3::new(2.0, 4.0, 0.0)) < 1e-5);
        let super::RigidOrigin::Files { lines, .. } = &actor.origin else {
            panic!("a user's actor comes from files");
        };
        assert_eq!(actor.lines_at(lines, 0.5), "line 2");
        assert_eq!(actor.lines_at(lines, 2.0), "lines 2-4");
        assert_eq!(actor.lines_at(lines, 3.0), "line 4");
        assert!(actor.normals[0].distance(Vec3::new(0.4, 0.3, 0.12).normalize()) < 1e-6);
    }
}
