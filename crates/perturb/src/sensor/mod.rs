//! Sensor effects formed from the camera's own motion and optics during capture, not filters on
//! a finished image: `exposure` (motion blur of the true motion), `rolling_shutter` (rows read out
//! at their own instants) and `distortion` (a lens). They need the renderer, so they run where
//! frames are drawn from a scene: the pipeline's scene source asks [`Shutter::schedule`] for the
//! renders of each frame, draws them, and sums them on the GPU with [`ShutterPass`]; under a lens
//! it draws them with the wider pinhole of a [`LensView`] and resamples the sum through the lens
//! with [`LensPass`]; then the image corruptions run.

pub mod distortion;
pub mod exposure;
mod lens_pass;
mod lens_view;
pub mod pixel_motion;
pub mod rolling_shutter;
mod schedule;
mod shutter_pass;

pub use exposure::Exposure;
pub use lens_pass::{mask_twin as lens_mask_twin, twin as lens_twin, LensPass};
pub use lens_view::{LensView, MAX_WIDE_SIDE};
pub use rolling_shutter::RollingShutter;
pub use schedule::{CameraPath, Shutter, SubRender, MAX_RENDERS};
pub use shutter_pass::{twin, ShutterPass, WeightedRows, UNIFORMS};

use crate::applies::{ItemEntry, Need};

/// A time in milliseconds ≥ 0; the error names `what` and shows `example`.
fn parse_milliseconds(value: &str, what: &str, example: &str) -> Result<f64, String> {
    value
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v >= 0.0)
        .ok_or_else(|| format!("'{value}': expected {what} in milliseconds ≥ 0, e.g. {example}"))
}

pub static SENSOR_ITEMS: &[ItemEntry] = &[
    ItemEntry {
        name: exposure::NAME,
        syntax: "exposure:MS[@K]",
        description: "motion blur of the camera's own motion: K renders from poses spread over an exposure of MS ms (SE(3)-interpolated path), averaged in linear light; K from the predicted pixel motion (≤ 1 px per sub-frame, at most 64) unless @K; timestamp and ground truth at mid-exposure",
        needs: &[Need::Scene],
    },
    ItemEntry {
        name: rolling_shutter::NAME,
        syntax: "rolling_shutter:MS",
        description: "rows read out top to bottom over MS ms, each from the pose at its read-out time (colour and depth; bands of ≤ 0.5 px motion); timestamp and ground truth at the middle row",
        needs: &[Need::Scene],
    },
    ItemEntry {
        name: distortion::NAME,
        syntax: "distortion:radtan(k1,k2,p1,p2) | distortion:equidistant(k1,k2,k3,k4)",
        description: "lens distortion, OpenCV radial-tangential or Kannala-Brandt equidistant (fisheye): rendered by a wider pinhole and resampled through the inverse model (colour bilinear, depth without mixing surfaces); written into cam_params.json and orbslam3.yaml; poses unchanged",
        needs: &[Need::Scene, Need::Lens],
    },
];
