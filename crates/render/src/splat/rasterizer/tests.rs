use std::sync::OnceLock;

use glam::{DQuat, DVec3};
use rslam_gpu::{AdapterChoice, FrameReadback};

use super::*;

fn context() -> &'static GpuContext {
    static CONTEXT: OnceLock<GpuContext> = OnceLock::new();
    CONTEXT.get_or_init(|| {
        GpuContext::new(&AdapterChoice::default())
            .unwrap_or_else(|e| panic!("these tests need an adapter (lavapipe is fine): {e}"))
    })
}

const CAMERA: Intrinsics = Intrinsics {
    width: 64,
    height: 48,
    fx: 50.0,
    fy: 50.0,
    cx: 31.5,
    cy: 23.5,
};

/// 1000 degree-1 Gaussians on a grid in front of the camera, each its own colour.
fn cloud() -> SplatCloud {
    let mut cloud = SplatCloud {
        sh_degree: 1,
        ..Default::default()
    };
    for i in 0..1000 {
        let (x, y, z) = ((i % 10) as f32, ((i / 10) % 10) as f32, (i / 100) as f32);
        cloud
            .means
            .push([0.1 * x - 0.45, 0.1 * y - 0.45, 1.0 + 0.2 * z]);
        cloud.log_scales.push([-3.0, -3.5, -4.0]);
        cloud.rotations.push([1.0, 0.1 * x, 0.0, 0.1 * y]);
        cloud.opacity_logits.push(0.5);
        cloud.sh.push([x / 10.0, y / 10.0, z / 10.0]);
        cloud.sh.extend([[0.1, -0.1, 0.2]; 3]);
    }
    cloud
}

fn render(rasterizer: &mut SplatRasterizer) -> (Vec<u8>, Vec<f32>) {
    let ctx = context();
    let frame = FrameTextures::new(ctx, CAMERA.width, CAMERA.height);
    let readback = FrameReadback::new(ctx, CAMERA.width, CAMERA.height, true);
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    let pose = Pose::new(DQuat::from_rotation_y(0.05), DVec3::new(0.02, 0.0, -0.1));
    rasterizer.encode(ctx, &mut encoder, &frame, &pose).unwrap();
    readback.encode_copy(&mut encoder, &frame);
    let submission = ctx.queue.submit([encoder.finish()]);
    let (rgb, depth) = readback.read(ctx, submission).unwrap();
    (rgb.data, depth.unwrap().data)
}

#[test]
fn harmonics_bound_in_chunks_render_the_same_frame() {
    let ctx = context();
    let (cloud, settings) = (cloud(), SplatSettings::default());
    let whole = &mut SplatRasterizer::new(ctx, &cloud, CAMERA, settings).unwrap();
    // 256 Gaussians' harmonics a binding: four chunks, the last of 232.
    let limit = 256 * cloud.coefficients() as u64 * 12;
    let chunked =
        &mut SplatRasterizer::with_binding_limit(ctx, &cloud, CAMERA, settings, limit).unwrap();
    assert_eq!(chunked.project.len(), 4);
    let frame = render(whole);
    assert!(
        frame.0.iter().any(|&c| c > 40),
        "a frame that shows the Gaussians"
    );
    assert_eq!(render(chunked), frame);
}

#[test]
fn instance_buffers_grow_when_a_view_needs_more() {
    let ctx = context();
    let cloud = cloud();
    let mut rasterizer =
        SplatRasterizer::new(ctx, &cloud, CAMERA, SplatSettings::default()).unwrap();
    let fresh = render(&mut rasterizer);
    // Shrink the instance buffers below what the view needs: the next frame regrows them.
    rasterizer.instances = rasterizer.instances_for(ctx, 16).unwrap();
    assert_eq!(render(&mut rasterizer), fresh);
    assert!(rasterizer.instances.sort.capacity() > 16);
}

#[test]
fn an_empty_capture_is_refused() {
    let err = SplatRasterizer::new(
        context(),
        &SplatCloud::default(),
        CAMERA,
        SplatSettings::default(),
    );
    assert!(matches!(err, Err(RenderError::EmptyCapture)));
}
