// motion_blur: imagecorruptions' one-sided line kernel. Tap i reads the source at the integer
// offset (dx_i, dy_i) along the frame's angle with weight exp(-i²/2σ²) (normalised); edges
// replicated; truncated to 8 bits. Offsets and weights are computed on the CPU per frame. Each
// invocation writes a run of 8 pixels of a row (one tap read per 8 outputs; see filter.wgsl).
#include "common/color.wgsl"
#include "perturb/image/filter.wgsl"

@group(0) @binding(0) var source: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<rgba8unorm, write>;
@group(0) @binding(2) var<uniform> line: LineKernel;

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = vec2<i32>(textureDimensions(source));
    let x0 = i32(id.x) * 8;
    let y = i32(id.y);
    if (x0 >= size.x || y >= size.y) {
        return;
    }
    let last = size - 1;
    var s0 = vec3<f32>(0.0);
    var s1 = vec3<f32>(0.0);
    var s2 = vec3<f32>(0.0);
    var s3 = vec3<f32>(0.0);
    var s4 = vec3<f32>(0.0);
    var s5 = vec3<f32>(0.0);
    var s6 = vec3<f32>(0.0);
    var s7 = vec3<f32>(0.0);
    for (var k = 0; k < line.count; k++) {
        let t = line.taps[k];
        let row = clamp(y + i32(t.y), 0, last.y);
        let x = x0 + i32(t.x);
        s0 += t.z * textureLoad(source, vec2<i32>(clamp(x + 0, 0, last.x), row), 0).rgb;
        s1 += t.z * textureLoad(source, vec2<i32>(clamp(x + 1, 0, last.x), row), 0).rgb;
        s2 += t.z * textureLoad(source, vec2<i32>(clamp(x + 2, 0, last.x), row), 0).rgb;
        s3 += t.z * textureLoad(source, vec2<i32>(clamp(x + 3, 0, last.x), row), 0).rgb;
        s4 += t.z * textureLoad(source, vec2<i32>(clamp(x + 4, 0, last.x), row), 0).rgb;
        s5 += t.z * textureLoad(source, vec2<i32>(clamp(x + 5, 0, last.x), row), 0).rgb;
        s6 += t.z * textureLoad(source, vec2<i32>(clamp(x + 6, 0, last.x), row), 0).rgb;
        s7 += t.z * textureLoad(source, vec2<i32>(clamp(x + 7, 0, last.x), row), 0).rgb;
    }
    if (x0 + 0 < size.x) {
        textureStore(output, vec2<i32>(x0 + 0, y), vec4<f32>(truncate8(s0 + SUM_EPSILON), 1.0));
    }
    if (x0 + 1 < size.x) {
        textureStore(output, vec2<i32>(x0 + 1, y), vec4<f32>(truncate8(s1 + SUM_EPSILON), 1.0));
    }
    if (x0 + 2 < size.x) {
        textureStore(output, vec2<i32>(x0 + 2, y), vec4<f32>(truncate8(s2 + SUM_EPSILON), 1.0));
    }
    if (x0 + 3 < size.x) {
        textureStore(output, vec2<i32>(x0 + 3, y), vec4<f32>(truncate8(s3 + SUM_EPSILON), 1.0));
    }
    if (x0 + 4 < size.x) {
        textureStore(output, vec2<i32>(x0 + 4, y), vec4<f32>(truncate8(s4 + SUM_EPSILON), 1.0));
    }
    if (x0 + 5 < size.x) {
        textureStore(output, vec2<i32>(x0 + 5, y), vec4<f32>(truncate8(s5 + SUM_EPSILON), 1.0));
    }
    if (x0 + 6 < size.x) {
        textureStore(output, vec2<i32>(x0 + 6, y), vec4<f32>(truncate8(s6 + SUM_EPSILON), 1.0));
    }
    if (x0 + 7 < size.x) {
        textureStore(output, vec2<i32>(x0 + 7, y), vec4<f32>(truncate8(s7 + SUM_EPSILON), 1.0));
    }
}
