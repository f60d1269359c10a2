//! distortion:radtan(k1,k2,p1,p2) | distortion:equidistant(k1,k2,k3,k4) — the frame seen through
//! a lens: OpenCV's radial-tangential model or the Kannala-Brandt equidistant (fisheye) one
//! ([`Distortion`]). It is rendered, not warped from the pinhole frame: the scene is drawn by a
//! wider pinhole with the same focal length that covers every ray the lens image sees
//! ([`LensView`](super::LensView)), and each output pixel then takes the colour and depth its ray
//! lands on ([`LensPass`](super::LensPass)). The camera files of the dataset carry the model and
//! its coefficients; poses and timestamps are unchanged.

use rslam_core::Distortion;

pub const NAME: &str = "distortion";

/// Parses the `MODEL(c1,c2,c3,c4)` of `distortion:MODEL(c1,c2,c3,c4)`.
pub fn parse(value: &str, mode: Option<&str>) -> Result<Distortion, String> {
    if let Some(m) = mode {
        return Err(format!("{NAME} takes no mode, got '@{m}'"));
    }
    Distortion::parse(value)
}

/// The item as a spec writes it, e.g. `distortion:radtan(-0.28,0.07,0.0002,0.00002)`.
pub fn item(lens: &Distortion) -> String {
    format!("{NAME}:{lens}")
}
