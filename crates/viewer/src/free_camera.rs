//! The free camera of a scene: a pose flown by keys and mouse in the camera's own frame
//! (x right, y down, z forward), snapped back to the path, and poses recorded into a new camera
//! path saved as a Replica `traj.txt`.

use std::path::Path;

use glam::{DQuat, DVec3};
use rslam_core::trajectory_io::write_replica;
use rslam_core::{Pose, Trajectory};

use crate::ViewerError;

/// One step of flight, in the camera frame: metres along x (right), y (down), z (forward), then
/// radians of yaw (about the camera's y) and pitch (about its x).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct CameraStep {
    pub right: f64,
    pub down: f64,
    pub forward: f64,
    pub yaw: f64,
    pub pitch: f64,
}

impl CameraStep {
    pub fn is_still(&self) -> bool {
        *self == CameraStep::default()
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct FreeCamera {
    /// Flying instead of following the path.
    pub active: bool,
    pub world_from_camera: Pose,
    /// Metres per second of held key.
    pub speed: f64,
    /// Poses added to the new path.
    pub recorded: Vec<Pose>,
}

impl Default for FreeCamera {
    fn default() -> Self {
        Self {
            active: false,
            world_from_camera: Pose::new(DQuat::IDENTITY, DVec3::ZERO),
            speed: 1.0,
            recorded: Vec::new(),
        }
    }
}

impl FreeCamera {
    /// Moves and turns the camera by `step`, in its own frame.
    pub fn fly(&mut self, step: CameraStep) {
        let turn = DQuat::from_rotation_y(step.yaw) * DQuat::from_rotation_x(step.pitch);
        let local = Pose::new(turn, DVec3::new(step.right, step.down, step.forward));
        self.world_from_camera = self.world_from_camera.compose(&local);
    }

    /// Back onto the path: the camera takes `pose`.
    pub fn snap_to(&mut self, pose: Pose) {
        self.world_from_camera = pose;
    }

    pub fn record(&mut self) {
        self.recorded.push(self.world_from_camera);
    }

    /// Writes the recorded poses as a Replica `traj.txt` (camera-to-world, one 4×4 per line),
    /// which `rslam render --traj` and `rslam view --traj` read.
    pub fn save(&self, path: &Path, rate_hz: f64) -> Result<(), ViewerError> {
        if self.recorded.is_empty() {
            return Err(ViewerError::File {
                path: path.to_path_buf(),
                message: "no poses recorded yet: press 'add pose' first".into(),
            });
        }
        let path_of_poses = Trajectory::from_poses_at_rate(self.recorded.clone(), rate_hz);
        write_replica(path, &path_of_poses)?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn forward_is_the_camera_z_axis_and_turns_compose() {
        let mut camera = FreeCamera {
            world_from_camera: Pose::new(
                DQuat::from_rotation_y(std::f64::consts::FRAC_PI_2),
                DVec3::new(1.0, 0.0, 0.0),
            ),
            ..FreeCamera::default()
        };
        camera.fly(CameraStep {
            forward: 2.0,
            ..Default::default()
        });
        // Turned 90° about y, the camera's z points along world +x.
        let t = camera.world_from_camera.translation;
        assert!((t - DVec3::new(3.0, 0.0, 0.0)).length() < 1e-12, "{t}");
        camera.fly(CameraStep {
            yaw: -std::f64::consts::FRAC_PI_2,
            ..Default::default()
        });
        let forward = camera.world_from_camera.rotation * DVec3::Z;
        assert!((forward - DVec3::Z).length() < 1e-12, "{forward}");
    }

    #[test]
    fn recorded_poses_save_and_read_back() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("traj.txt");
        let mut camera = FreeCamera::default();
        assert!(camera.save(&path, 20.0).is_err(), "nothing recorded");
        camera.record();
        camera.fly(CameraStep {
            forward: 0.5,
            yaw: 0.1,
            ..Default::default()
        });
        camera.record();
        camera.save(&path, 20.0).unwrap();
        let back = rslam_core::trajectory_io::read_trajectory(&path, None).unwrap();
        assert_eq!(back.trajectory.len(), 2);
        let d = back.trajectory.poses[1].translation - camera.recorded[1].translation;
        assert!(d.length() < 1e-9);
    }
}
