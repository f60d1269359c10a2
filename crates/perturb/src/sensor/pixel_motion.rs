//! How far the image can move between two camera poses: the bound that sets how many sub-frames
//! an exposure and how many bands a rolling shutter need.

use rslam_core::se3::log;
use rslam_core::{Intrinsics, Pose};

/// The nearest surface assumed when bounding the image motion a translation causes, metres:
/// indoor handheld footage rarely sees closer than this.
pub const NEAREST_SURFACE_M: f64 = 0.5;

/// An upper bound on the distance in pixels any image point moves from the view at `from` to
/// the view at `to`: rotation by θ moves a point at radius r from the principal point about
/// θ·(f + r²/f) (the derivative of f·tan), translation t moves a point at depth z by f·t/z.
pub fn max_pixel_motion(camera: &Intrinsics, from: &Pose, to: &Pose) -> f64 {
    let relative = from.inverse().compose(to);
    let angle = log(&relative).rotation.length();
    let f = camera.fx.max(camera.fy);
    let corners = [(0.0, 0.0), (camera.width as f64, camera.height as f64)];
    let radius_sq = corners
        .iter()
        .flat_map(|&(x, _)| corners.iter().map(move |&(_, y)| (x, y)))
        .map(|(x, y)| (x - camera.cx).powi(2) + (y - camera.cy).powi(2))
        .fold(0.0, f64::max);
    angle * (f + radius_sq / f) + f * relative.translation.length() / NEAREST_SURFACE_M
}

#[cfg(test)]
mod tests {
    use glam::{DQuat, DVec3};

    use super::*;

    #[test]
    fn sideways_motion_and_roll_give_their_pixel_displacement() {
        let camera = Intrinsics {
            width: 100,
            height: 80,
            fx: 50.0,
            fy: 50.0,
            cx: 50.0,
            cy: 40.0,
        };
        let moved = Pose::new(DQuat::IDENTITY, DVec3::new(0.01, 0.0, 0.0));
        let px = max_pixel_motion(&camera, &Pose::IDENTITY, &moved);
        assert!((px - 50.0 * 0.01 / NEAREST_SURFACE_M).abs() < 1e-9, "{px}");
        let roll = Pose::new(DQuat::from_rotation_z(0.01), DVec3::ZERO);
        let px = max_pixel_motion(&camera, &roll, &Pose::IDENTITY);
        let corner_radius = (50.0f64 * 50.0 + 40.0 * 40.0).sqrt();
        assert!(px >= 0.01 * corner_radius, "a roll moves the corners {px}");
        assert_eq!(
            max_pixel_motion(&camera, &Pose::IDENTITY, &Pose::IDENTITY),
            0.0
        );
    }
}
