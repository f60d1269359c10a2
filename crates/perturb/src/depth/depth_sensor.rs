//! depth_sensor: a structured-light (Kinect v1) or active-stereo (RealSense D435) depth sensor,
//! computed from the rendered geometry (metric depth and the camera), not from a 16-bit image.
//!
//! Per pixel, with the emitter (Kinect's projector, the D435's right imager) rectified with the
//! camera and offset by the baseline b along the camera's x axis:
//! - **Projector shadow.** A point at column x, depth z projects into the emitter at column
//!   x − f·b/z (f the frame camera's focal length in pixels, b signed). It is hidden from the
//!   emitter when nearer geometry lies on the same emitter ray; such geometry shows in the image
//!   on the emitter's side of the point. Mirroring so the emitter is at +x,
//!   q(x) = sign(b)·x − f·|b|/z decreases along a surface the emitter sees, scanned away from the
//!   emitter; so scanning the row from the emitter's side, a pixel is shadowed when q(x) is not
//!   below the running minimum of q over the pixels already scanned. Shadows therefore fall on
//!   the side of an occluder away from the emitter, Δd = f·|b|·(1/z_far − 1/z_near) columns wide
//!   (the difference of disparities). Invalid pixels neither shadow nor are shadowed.
//! - **Axial noise and quantisation**, in the sensor's native disparity d = F/z (F = native
//!   f·|b|): d' = round_step(d + N(0, σ_d)), z' = F/d'. To first order
//!   σ_z(z) = z²/F · √(σ_d² + step²/12) (Khoshelham & Elberink 2012, eq. 10, with the
//!   quantisation's uniform variance step²/12 added).
//! - **Range**: z' outside [z_min, z_max] becomes invalid (0).
//!
//! Spec: `depth_sensor:kinect`, `depth_sensor:realsense`; severities 1..=5 are the Kinect v1
//! with σ_d multiplied by the severity (1 = a real Kinect v1). Needs the camera: image-only
//! inputs (no camera, no depth) are refused when the perturber is built.
//!
//! Not modelled: lateral noise at edges (Nguyen et al. 2012, eq. 3), the angle dependence of the
//! axial noise, speckle-window effects.

use bytemuck::{Pod, Zeroable};
use rslam_core::DepthImage;
use rslam_gpu::FrameTextures;

use super::depth_pass::DepthPass;
use crate::perturbation::{CatalogueEntry, ExplicitForm, FrameKey, GpuPerturbation, Group, Kit};
use crate::rng::{self, RngKey};
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, RustLayout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "depth_sensor";
const SHADER: &str = "perturb/depth/depth_sensor.wgsl";
const PURPOSE_NOISE: u32 = 0;
/// Rows per workgroup of the shader (`@workgroup_size(64)`, one invocation per row).
const ROWS_PER_GROUP: u32 = 64;
/// The running minimum before the first valid pixel (WGSL `NO_MINIMUM`).
const NO_MINIMUM: f32 = 3.0e38;

/// One sensor's parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SensorModel {
    pub name: &'static str,
    /// Emitter offset along the camera's x axis in metres; its sign says the side.
    pub baseline_m: f32,
    /// Focal length in pixels at the sensor's native depth resolution, where disparity is
    /// measured and quantised.
    pub native_focal_px: f32,
    /// Standard deviation of the disparity noise, native pixels.
    pub sigma_disparity_px: f32,
    /// Disparity quantisation step, native pixels.
    pub disparity_step_px: f32,
    pub z_min: f32,
    pub z_max: f32,
}

impl SensorModel {
    /// F = native f·|b|, so that d = F/z.
    pub fn fb_native(&self) -> f32 {
        self.native_focal_px * self.baseline_m.abs()
    }

    /// The model's axial σ at depth z in metres, noise and quantisation:
    /// z²/F · √(σ_d² + step²/12) (first order in σ_d/d).
    pub fn sigma_z(&self, z: f32) -> f32 {
        let step = self.disparity_step_px;
        let sigma_d = (self.sigma_disparity_px.powi(2) + step * step / 12.0).sqrt();
        z * z / self.fb_native() * sigma_d
    }
}

/// Microsoft Kinect v1 (PrimeSense structured light).
/// - baseline 0.075 m, projector at +x of the IR camera (to the sensor's right; shadows fall on
///   the left of objects in its depth images): Khoshelham & Elberink 2012, "Accuracy and
///   Resolution of Kinect Depth Data for Indoor Mapping Applications", Sensors 12(2), §2–3;
///   Konolige & Mihelich, "Technical description of Kinect calibration" (ROS wiki).
/// - native f ≈ 580 px at 640×480 and disparity in 1/8-pixel steps: Konolige & Mihelich.
/// - σ_d = 0.06 px: our choice, fitted so the model's σ_z (with the quantisation term) follows
///   Nguyen, Izadi & Lovell 2012, eq. 2 (σ_z = 0.0012 + 0.0019(z − 0.4)² m): 1.6/6.4/14.5 mm at
///   1/2/3 m against their 1.9/6.1/14.0 mm.
/// - range 0.5–4.0 m: Khoshelham & Elberink's 0.5–5 m operating range, cut at 4 m where
///   Microsoft's default-mode specification ends (our choice).
pub const KINECT_V1: SensorModel = SensorModel {
    name: "kinect",
    baseline_m: 0.075,
    native_focal_px: 580.0,
    sigma_disparity_px: 0.06,
    disparity_step_px: 0.125,
    z_min: 0.5,
    z_max: 4.0,
};

/// Intel RealSense D435 (active stereo; the depth is in the left imager's frame).
/// - baseline 0.050 m, the right imager (whose view decides occlusion) at +x: Intel RealSense
///   D400 series datasheet.
/// - native f = 0.5·848/tan(90°/2) = 424 px at 848×480 (HFOV 90°) and disparity in 1/32-pixel
///   steps: Grunnet-Jepsen et al., "Subpixel Linearity Improvement for Intel RealSense Depth
///   Cameras D400 Series" (Intel white paper).
/// - σ_d = 0.08 px, the typical subpixel RMS of Intel's depth RMS error formula
///   RMS = z²·subpixel/(f·b): Grunnet-Jepsen, Sweetser & Woodfill, "Tuning depth cameras for best
///   performance" (Intel white paper).
/// - range 0.3–10 m: the datasheet's minimum depth at 848×480 is ≈ 0.2–0.3 m; 10 m is our cut.
pub const REALSENSE_D435: SensorModel = SensorModel {
    name: "realsense",
    baseline_m: 0.050,
    native_focal_px: 424.0,
    sigma_disparity_px: 0.08,
    disparity_step_px: 1.0 / 32.0,
    z_min: 0.3,
    z_max: 10.0,
};

/// The models of the explicit form, by index: `depth_sensor:NAME` parses to `[index]`.
pub const MODELS: [SensorModel; 2] = [KINECT_V1, REALSENSE_D435];

/// Multiplier of the Kinect's σ_d per severity (our choice; 1 = Kinect v1).
pub const MULTIPLIER: [f32; 5] = [1.0, 2.0, 3.0, 4.0, 5.0];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Depth,
    description: "Kinect v1 / RealSense D435 from the geometry: disparity noise and quantisation, projector shadow, range; severity k = Kinect with k·σ_d",
    parameters: |s| {
        let m = model_at(s as usize - 1);
        format!("kinect σ_d={:.2} px", m.sigma_disparity_px)
    },
    build: |kit| Ok(Box::new(DepthSensor::new(kit)?)),
    explicit: Some(ExplicitForm {
        syntax: "a sensor model, kinect or realsense, e.g. depth_sensor:kinect",
        example: "realsense",
        parse: parse_model,
        format: |v| {
            MODELS
                .get(v[0] as usize)
                .map_or("?", |m| m.name)
                .to_string()
        },
    }),
    twin: Twin::Depth(twin),
    // Division and the Box-Muller draw differ in the last bits between the GPU and Rust; the
    // same disparity step is chosen unless d/step sits within those bits of a rounding boundary.
    twin_tolerance: Tolerance {
        metres: 1e-5,
        ..Tolerance::EXACT
    },
    uniforms: &[UniformLayout {
        rust: SensorParams::LAYOUT,
        wgsl: "Params",
        shader: SHADER,
    }],
};

/// The Kinect at severity index `level` (σ_d × `MULTIPLIER[level]`).
fn model_at(level: usize) -> SensorModel {
    SensorModel {
        sigma_disparity_px: KINECT_V1.sigma_disparity_px * MULTIPLIER[level.min(4)],
        ..KINECT_V1
    }
}

/// `kinect` or `realsense`.
pub fn parse_model(text: &str) -> Result<Vec<f64>, String> {
    let name = text.trim().to_ascii_lowercase();
    match MODELS.iter().position(|m| m.name == name) {
        Some(i) => Ok(vec![i as f64]),
        None => Err(format!(
            "unknown sensor model '{text}'; valid: kinect, realsense"
        )),
    }
}

/// The model this frame uses: the explicit one, or the severity's.
pub fn model(key: &FrameKey) -> SensorModel {
    match key.explicit {
        Some([index, ..]) => MODELS[(*index as usize).min(MODELS.len() - 1)],
        _ => model_at(key.level()),
    }
}

/// The uniform block of `depth_sensor.wgsl`.
#[repr(C)]
#[derive(Clone, Copy, Debug, Pod, Zeroable)]
struct SensorParams {
    key: [u32; 4],
    geometry: [f32; 4],
    sensor: [f32; 4],
}

impl SensorParams {
    const LAYOUT: RustLayout = rust_layout!(SensorParams {
        key,
        geometry,
        sensor
    });

    fn new(model: &SensorModel, focal_px: f32, key: RngKey) -> Self {
        Self {
            key: key.0,
            geometry: [
                focal_px * model.baseline_m.abs(),
                side(model),
                model.sigma_disparity_px,
                model.disparity_step_px,
            ],
            sensor: [model.fb_native(), model.z_min, model.z_max, 0.0],
        }
    }
}

fn side(model: &SensorModel) -> f32 {
    if model.baseline_m < 0.0 {
        -1.0
    } else {
        1.0
    }
}

fn no_camera() -> PerturbError {
    PerturbError::Unsupported {
        name: NAME.into(),
        message: "needs the camera's focal length, and these frames come without a camera \
                  (image files); use a rendered scene or a dataset with intrinsics"
            .into(),
    }
}

struct DepthSensor {
    pass: DepthPass,
}

impl DepthSensor {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        kit.camera.ok_or_else(no_camera)?;
        Ok(Self {
            pass: DepthPass::new::<SensorParams>(kit, SHADER)?,
        })
    }
}

impl GpuPerturbation for DepthSensor {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        let camera = key.camera.or(kit.camera).ok_or_else(no_camera)?;
        let params = SensorParams::new(&model(key), camera.fx as f32, key.rng(NAME, PURPOSE_NOISE));
        // One invocation per row: the pass dispatches rows / 64 groups instead of 8×8 tiles.
        self.pass.encode_workgroups(
            kit,
            encoder,
            frame,
            &params,
            [kit.height.div_ceil(ROWS_PER_GROUP), 1, 1],
        );
        Ok(())
    }
}

/// CPU twin of `depth_sensor.wgsl`. Without a camera in `key` the depth is returned as it is
/// (the GPU pass refuses to build without one).
pub fn twin(depth: &DepthImage, key: &FrameKey) -> DepthImage {
    match key.camera {
        Some(camera) => sense(depth, &model(key), camera.fx as f32, key),
        None => depth.clone(),
    }
}

/// `model` applied to `depth` taken by a camera of focal length `focal_px` (the twin's body).
pub fn sense(depth: &DepthImage, model: &SensorModel, focal_px: f32, key: &FrameKey) -> DepthImage {
    let p = SensorParams::new(model, focal_px, key.rng(NAME, PURPOSE_NOISE));
    let [fb_frame, side, sigma, step] = p.geometry;
    let [fb_native, z_min, z_max, _] = p.sensor;
    let rng = RngKey(p.key);
    let (w, h) = (depth.width, depth.height);
    let mut out = depth.clone();
    for y in 0..h {
        let mut running = NO_MINIMUM;
        for i in 0..w {
            let x = if side > 0.0 { w - 1 - i } else { i };
            let at = (y * w + x) as usize;
            let z = depth.data[at];
            if z <= 0.0 {
                continue;
            }
            let q = side * x as f32 - fb_frame / z;
            let shadowed = q >= running;
            running = running.min(q);
            let mut value = 0.0;
            if !shadowed {
                let u = rng.draw([x, y, 0, 0]);
                let n = rng::normal_pair(u[0], u[1])[0];
                let d = fb_native / z + sigma * n;
                let dq = (d / step + 0.5).floor() * step;
                if dq > 0.0 {
                    let zq = fb_native / dq;
                    if zq >= z_min && zq <= z_max {
                        value = zq;
                    }
                }
            }
            out.data[at] = value;
        }
    }
    out
}

#[cfg(test)]
#[path = "depth_sensor_tests.rs"]
mod tests;
