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
//! - **Lateral noise at edges** (Kinect only): every depth edge, a boundary between two pixels
//!   of a row (column) where the depth jumps by more than a surface at 85° to the ray would
//!   (|Δz| > tan 85°/f · z) or valid meets invalid, moves along the row (column) by an integer
//!   shift s of standard deviation σ_L(θ) = 0.8 + 0.035·θ/(π/2 − θ) native px (Nguyen et al. 2012,
//!   eq. 3; θ of the nearer side) scaled to the frame by f/f_native. The pixels it sweeps show the
//!   measurement (below) of the growing side's pixel at the edge; a pixel follows the nearest
//!   edge within the reach (4 σ_L at the clamped θ), one shift drawn per edge and row (column),
//!   so the edge moves as a whole and pixels farther from any edge do not move. A pixel moved
//!   along x is not moved along y.
//!   s = round(N(0, √(σ² − 1/12))) from σ ≥ 0.6 px (rounding adds 1/12 px², Sheppard), and below
//!   (frames coarser than the sensor) s ∈ {−1, 0, 1} with P(±1) = σ²/2: both have variance σ².
//! - **Axial noise and quantisation**, in the sensor's native disparity d = F/z (F = native
//!   f·|b|): d' = round_step(d + N(0, σ)), z' = F/d'. To first order
//!   σ_z = z²/F · √(σ² + step²/12) (Khoshelham & Elberink 2012, eq. 10, with the quantisation's
//!   uniform variance step²/12 added). With σ = σ_d this is the fronto-parallel σ_z(z). The
//!   Kinect adds the angle term of Nguyen et al. 2012, eq. 2, σ_θ = 0.0001/√z · θ²/(π/2 − θ)² m,
//!   to that σ_z as their fit adds it: σ² = σ_d² + a² + 2a·√(σ_d² + step²/12) with a = σ_θ·F/z²
//!   gives σ_z(z, θ) = σ_z(z) + σ_θ(z, θ). θ is the angle between the surface normal and the
//!   viewing ray; the normal is the cross product of the back-projected neighbour differences
//!   along x and y (central, or one-sided where one neighbour is across an edge; θ = 0 where
//!   both are), clamped at 80° (their fit covers 10°–60°; near grazing the term would diverge).
//! - **Range**: z' outside [z_min, z_max] becomes invalid (0).
//!
//! Shadow, noise and range are measured on the rendered geometry; the lateral moves then
//! reassign those measurements (passes: geometry → sense per row → lateral). Draws: the noise
//! from purpose 0 at counter (x, y, 0, 0), an edge's shift from purpose 1 at (x, y, axis, 0) of
//! the pixel before the edge, so every draw depends on (seed, frame, pixel) alone.
//!
//! Spec: `depth_sensor:kinect`, `depth_sensor:realsense`; severities 1..=5 are the Kinect v1
//! with σ_d multiplied by the severity (1 = a real Kinect v1; the angle term and σ_L stay
//! Nguyen's). Needs the camera: image-only
//! inputs (no camera, no depth) are refused when the perturber is built.
//!
//! Not modelled: speckle-window effects; for the RealSense, the angle term and lateral noise
//! (Nguyen's fits are of the Kinect's structured light; we know no published fit of the D435's).

use std::f32::consts::FRAC_PI_2;

use bytemuck::{Pod, Zeroable};
use rslam_core::{DepthImage, Intrinsics};
use rslam_gpu::FrameTextures;

use crate::perturbation::{
    view, CatalogueEntry, ExplicitForm, FrameKey, GpuPerturbation, Group, Kit,
};
use crate::rng::{self, RngKey};
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, RustLayout, UniformLayout};
use crate::PerturbError;

#[path = "depth_sensor_geometry.rs"]
mod geometry;

const NAME: &str = "depth_sensor";
const SHADER: &str = "perturb/depth/depth_sensor.wgsl";
const PURPOSE_NOISE: u32 = 0;
const PURPOSE_LATERAL: u32 = 1;
/// Rows per workgroup of the shader (`@workgroup_size(64)`, one invocation per row).
const ROWS_PER_GROUP: u32 = 64;
/// The running minimum before the first valid pixel (WGSL `NO_MINIMUM`).
const NO_MINIMUM: f32 = 3.0e38;
/// θ is clamped here: Nguyen et al.'s fit covers 10°–60°, and θ²/(π/2 − θ)² diverges at grazing
/// incidence; at 80° the angle term is 64 × 0.1 mm/√z (our choice).
pub const MAX_ANGLE_DEG: f32 = 80.0;
/// Neighbours are across a depth edge when the depth jumps more than a surface at this angle to
/// the ray would between two pixels (our choice: steeper than the clamped θ, so a surface the
/// angle term covers is never cut into edges).
pub const EDGE_ANGLE_DEG: f32 = 85.0;
/// From this lateral σ (frame px) up, a rounded normal has variance σ² to within 1 %.
const ROUNDED_NORMAL_FROM_PX: f32 = 0.6;
/// Edges move at most this many σ_L (at the clamped θ): the reach of the lateral search.
const REACH_SIGMAS: f32 = 4.0;

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
    /// c of the axial angle term c/√z · θ²/(π/2 − θ)² in metres (z in metres); 0 = none.
    pub angle_noise_m: f32,
    /// σ_L(θ) = l₀ + l₁·θ/(π/2 − θ) of an edge's position, native px: [l₀, l₁]; zeros = none.
    pub lateral_px: [f32; 2],
}

impl SensorModel {
    /// F = native f·|b|, so that d = F/z.
    pub fn fb_native(&self) -> f32 {
        self.native_focal_px * self.baseline_m.abs()
    }

    /// The model's axial σ at depth z in metres on a surface facing the camera, noise and
    /// quantisation: z²/F · √(σ_d² + step²/12) (first order in σ_d/d).
    pub fn sigma_z(&self, z: f32) -> f32 {
        let step = self.disparity_step_px;
        let sigma_d = (self.sigma_disparity_px.powi(2) + step * step / 12.0).sqrt();
        z * z / self.fb_native() * sigma_d
    }

    /// The axial angle term at depth z and angle θ (radians, clamped at [`MAX_ANGLE_DEG`]).
    pub fn sigma_angle(&self, z: f32, theta: f32) -> f32 {
        self.angle_noise_m / z.sqrt() * angle_ratio(theta.min(MAX_ANGLE_DEG.to_radians()))
    }

    /// The model's axial σ at depth z on a surface at θ to the ray: σ_z(z) + σ_θ(z, θ).
    pub fn sigma_z_at(&self, z: f32, theta: f32) -> f32 {
        self.sigma_z(z) + self.sigma_angle(z, theta)
    }

    /// σ_L of an edge's position at θ (clamped), in the sensor's native pixels.
    pub fn sigma_lateral_native(&self, theta: f32) -> f32 {
        let theta = theta.min(MAX_ANGLE_DEG.to_radians());
        self.lateral_px[0] + self.lateral_px[1] * theta / (FRAC_PI_2 - theta)
    }
}

/// θ²/(π/2 − θ)².
fn angle_ratio(theta: f32) -> f32 {
    let r = theta / (FRAC_PI_2 - theta);
    r * r
}

/// Microsoft Kinect v1 (PrimeSense structured light).
/// - baseline 0.075 m, projector at +x of the IR camera (to the sensor's right; shadows fall on
///   the left of objects in its depth images): Khoshelham & Elberink 2012, "Accuracy and
///   Resolution of Kinect Depth Data for Indoor Mapping Applications", Sensors 12(2), §2–3;
///   Konolige & Mihelich, "Technical description of Kinect calibration" (ROS wiki).
/// - native f ≈ 580 px at 640×480 and disparity in 1/8-pixel steps: Konolige & Mihelich.
/// - σ_d = 0.06 px: our choice, fitted so the model's σ_z (with the quantisation term) follows
///   Nguyen, Izadi & Lovell 2012, eq. 2 (σ_z = 0.0012 + 0.0019(z − 0.4)² m): 1.6/6.4/14.5 mm at
///   1/2/3 m against their 1.9/6.1/14.0 mm; their eq. 2's angle term 0.0001/√z · θ²/(π/2 − θ)² m
///   is added (see the module doc).
/// - lateral σ_L(θ) = 0.8 + 0.035·θ/(π/2 − θ) px at 640×480: Nguyen, Izadi & Lovell 2012, eq. 3.
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
    angle_noise_m: 0.0001,
    lateral_px: [0.8, 0.035],
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
/// - no angle term and no lateral noise: Nguyen et al.'s fits are of the Kinect's structured
///   light and we know no published fit of the D435's (Intel's RMS formula is fronto-parallel).
pub const REALSENSE_D435: SensorModel = SensorModel {
    name: "realsense",
    baseline_m: 0.050,
    native_focal_px: 424.0,
    sigma_disparity_px: 0.08,
    disparity_step_px: 1.0 / 32.0,
    z_min: 0.3,
    z_max: 10.0,
    angle_noise_m: 0.0,
    lateral_px: [0.0, 0.0],
};

/// The models of the explicit form, by index: `depth_sensor:NAME` parses to `[index]`.
pub const MODELS: [SensorModel; 2] = [KINECT_V1, REALSENSE_D435];

/// Multiplier of the Kinect's σ_d per severity (our choice; 1 = Kinect v1).
pub const MULTIPLIER: [f32; 5] = [1.0, 2.0, 3.0, 4.0, 5.0];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Depth,
    description: "Kinect v1 / RealSense D435 from the geometry: disparity noise and quantisation (Kinect: + angle term), lateral noise at edges (Kinect), projector shadow, range; severity k = Kinect with k·σ_d",
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
    // Division, acos and the Box-Muller draw differ in the last bits between the GPU and Rust;
    // the same disparity step and edge shift are chosen unless a value sits within those bits
    // of a rounding boundary.
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
    lateral_key: [u32; 4],
    geometry: [f32; 4],
    sensor: [f32; 4],
    camera: [f32; 4],
    lateral: [f32; 4],
    limits: [f32; 4],
}

impl SensorParams {
    const LAYOUT: RustLayout = rust_layout!(SensorParams {
        key,
        lateral_key,
        geometry,
        sensor,
        camera,
        lateral,
        limits
    });

    fn new(model: &SensorModel, camera: &Intrinsics, key: &FrameKey) -> Self {
        let (fx, fy) = (camera.fx as f32, camera.fy as f32);
        let widest = MAX_ANGLE_DEG.to_radians();
        let sigma_max = model.sigma_lateral_native(widest) * fx.max(fy) / model.native_focal_px;
        let reach = if sigma_max > 0.0 {
            (REACH_SIGMAS * sigma_max).ceil().max(1.0)
        } else {
            0.0
        };
        Self {
            key: key.rng(NAME, PURPOSE_NOISE).0,
            lateral_key: key.rng(NAME, PURPOSE_LATERAL).0,
            geometry: [
                fx * model.baseline_m.abs(),
                side(model),
                model.sigma_disparity_px,
                model.disparity_step_px,
            ],
            sensor: [
                model.fb_native(),
                model.z_min,
                model.z_max,
                model.angle_noise_m,
            ],
            camera: [fx, fy, camera.cx as f32, camera.cy as f32],
            lateral: [
                model.lateral_px[0],
                model.lateral_px[1],
                reach,
                ROUNDED_NORMAL_FROM_PX,
            ],
            limits: [
                widest,
                EDGE_ANGLE_DEG.to_radians().tan(),
                model.native_focal_px,
                0.0,
            ],
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

/// The `geometry` pass hands each pixel's source to the `lateral` pass as an f32 index, exact
/// up to 2²⁴.
const MAX_PIXELS: u32 = 1 << 24;

struct DepthSensor {
    geometry: wgpu::ComputePipeline,
    sense: wgpu::ComputePipeline,
    lateral: wgpu::ComputePipeline,
    params: wgpu::Buffer,
}

impl DepthSensor {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        kit.camera.ok_or_else(no_camera)?;
        if kit.width * kit.height > MAX_PIXELS {
            return Err(PerturbError::Unsupported {
                name: NAME.into(),
                message: format!(
                    "frames of {}×{} pixels are over the {MAX_PIXELS} it handles",
                    kit.width, kit.height
                ),
            });
        }
        let entry = |name| kit.pipeline_entry(SHADER, name);
        Ok(Self {
            geometry: entry("geometry")?,
            sense: entry("sense")?,
            lateral: entry("lateral")?,
            params: kit.uniform_buffer::<SensorParams>(SHADER),
        })
    }
}

impl GpuPerturbation for DepthSensor {
    /// geometry (sources and θ into the scratch) → sense (in place, one invocation per row) →
    /// the sensed depth copied over θ → lateral (each pixel takes its source's measurement).
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        use wgpu::BindingResource as R;
        let camera = key.camera.or(kit.camera).ok_or_else(no_camera)?;
        kit.write_uniform(&self.params, &SensorParams::new(&model(key), &camera, key));
        let depth = frame.depth_view();
        let [sources, angles] = [view(&kit.scratch.float1[0]), view(&kit.scratch.float1[1])];
        let params = || self.params.as_entire_binding();
        let group = kit.bind_group_at(
            &self.geometry,
            NAME,
            &[
                (0, R::TextureView(depth)),
                (1, params()),
                (2, R::TextureView(&sources)),
                (3, R::TextureView(&angles)),
            ],
        );
        kit.dispatch(encoder, &self.geometry, &group, "depth_sensor geometry");
        let group = kit.bind_group_at(
            &self.sense,
            NAME,
            &[
                (0, R::TextureView(depth)),
                (1, params()),
                (5, R::TextureView(&angles)),
            ],
        );
        let rows = [kit.height.div_ceil(ROWS_PER_GROUP), 1, 1];
        kit.dispatch_workgroups(encoder, &self.sense, &group, "depth_sensor sense", rows);
        encoder.copy_texture_to_texture(
            frame.depth.as_image_copy(),
            kit.scratch.float1[1].as_image_copy(),
            frame.size(),
        );
        let group = kit.bind_group_at(
            &self.lateral,
            NAME,
            &[
                (0, R::TextureView(depth)),
                (4, R::TextureView(&sources)),
                (6, R::TextureView(&angles)),
            ],
        );
        kit.dispatch(encoder, &self.lateral, &group, "depth_sensor lateral");
        Ok(())
    }
}

/// CPU twin of `depth_sensor.wgsl`. Without a camera in `key` the depth is returned as it is
/// (the GPU pass refuses to build without one).
pub fn twin(depth: &DepthImage, key: &FrameKey) -> DepthImage {
    match key.camera {
        Some(camera) => sense(depth, &model(key), &camera, key),
        None => depth.clone(),
    }
}

/// `model` applied to `depth` taken by `camera` (the twin's body): the `geometry`, `sense` and
/// `lateral` passes.
pub fn sense(
    depth: &DepthImage,
    model: &SensorModel,
    camera: &Intrinsics,
    key: &FrameKey,
) -> DepthImage {
    let p = SensorParams::new(model, camera, key);
    let (sources, angles) = geometry::Geometry::new(depth, &p).survey();
    let [fb_frame, side, sigma, step] = p.geometry;
    let [fb_native, z_min, z_max, angle_m] = p.sensor;
    let rng = RngKey(p.key);
    let (w, h) = (depth.width, depth.height);
    let mut sensed = depth.clone();
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
                let spread = disparity_sigma(sigma, step, fb_native, angle_m, z, angles[at]);
                let d = fb_native / z + spread * n;
                let dq = (d / step + 0.5).floor() * step;
                if dq > 0.0 {
                    let zq = fb_native / dq;
                    if zq >= z_min && zq <= z_max {
                        value = zq;
                    }
                }
            }
            sensed.data[at] = value;
        }
    }
    DepthImage {
        data: sources.iter().map(|&from| sensed.data[from]).collect(),
        ..sensed
    }
}

/// The disparity σ that gives σ_z(z) + σ_θ(z, θ) (WGSL `disparity_sigma`): with a = σ_θ·F/z²,
/// √(σ_d² + a² + 2a·√(σ_d² + step²/12)).
fn disparity_sigma(sigma: f32, step: f32, fb_native: f32, angle_m: f32, z: f32, theta: f32) -> f32 {
    let a = angle_m / z.sqrt() * angle_ratio(theta) * fb_native / (z * z);
    let spread = (sigma * sigma + step * step / 12.0).sqrt();
    (sigma * sigma + a * a + 2.0 * a * spread).sqrt()
}

#[cfg(test)]
#[path = "depth_sensor_tests.rs"]
mod tests;
