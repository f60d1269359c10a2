// What the splat passes share (crates/render/src/splat/): the camera of the frame and each
// Gaussian projected into it.

struct SplatCamera {
    camera_from_world: mat4x4<f32>,
    // The camera centre in world coordinates; the number of Gaussians.
    position: vec3<f32>,
    count: u32,
    focal: vec2<f32>,
    principal: vec2<f32>,
    size: vec2<u32>,
    tiles: vec2<u32>,
    // x/z and y/z are clamped to these before the projection's Jacobian is taken (the frustum
    // widened by 30 % on each side, as the reference implementation does).
    slope_min: vec2<f32>,
    slope_max: vec2<f32>,
    sh_degree: u32,
    // 0: expected depth, 1: median depth.
    depth_mode: u32,
    min_opacity: f32,
    pad: u32,
}

// A Gaussian projected into the frame is kept as four arrays (each under the 128 MiB a binding
// may hold on some adapters, for captures of millions): `splat_position` (pixel in the OpenCV
// convention, pixel centres at integers; z-depth; opacity), `splat_conic` (the inverse 2D
// covariance: xx, xy, yy), `splat_color` (view-dependent colour, display values) and
// `splat_tiles` (the rectangle of 16×16 tiles it touches, [min, max), x in the low and y in the
// high 16 bits; empty when culled).

fn tile_pair(t: vec2<u32>) -> u32 {
    return t.x | (t.y << 16u);
}

fn tile_of(pair: u32) -> vec2<u32> {
    return vec2<u32>(pair & 0xffffu, pair >> 16u);
}

const TILE: u32 = 16u;
