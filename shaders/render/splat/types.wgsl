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

// A Gaussian projected into the frame: pixel position (OpenCV convention, pixel centres at
// integers), z-depth, opacity, the inverse 2D covariance (conic: xx, xy, yy), view-dependent
// colour (display values), and the rectangle of 16×16 tiles it touches ([min, max) in tiles;
// empty when culled).
struct Splat {
    pixel: vec2<f32>,
    depth: f32,
    opacity: f32,
    conic: vec3<f32>,
    pad0: f32,
    color: vec3<f32>,
    pad1: f32,
    tile_min: vec2<u32>,
    tile_max: vec2<u32>,
}

const TILE: u32 = 16u;
