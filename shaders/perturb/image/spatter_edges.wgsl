// spatter (water), pass 5: OpenCV Canny's first half on the 8-bit liquid layer: Sobel 3x3
// (edges replicated), L1 magnitude, non-maximum suppression in four directions (neighbours
// outside the image count as 0), thresholds 50 / 150. Writes 2 (strong), 1 (weak) or 0.

@group(0) @binding(0) var liquid_layer: texture_2d<f32>;
@group(0) @binding(1) var output: texture_storage_2d<r32float, write>;

const LOW: i32 = 50;
const HIGH: i32 = 150;
// tan(22.5 deg) in Q15, as OpenCV's TG22.
const TG22: i32 = 13573;

var<private> size: vec2<i32>;

fn level(p: vec2<i32>) -> i32 {
    let q = clamp(p, vec2<i32>(0), size - 1);
    return i32(floor(textureLoad(liquid_layer, q, 0).x * 255.0));
}

fn gradient(p: vec2<i32>) -> vec2<i32> {
    let a = level(p + vec2<i32>(-1, -1));
    let b = level(p + vec2<i32>(0, -1));
    let c = level(p + vec2<i32>(1, -1));
    let d = level(p + vec2<i32>(-1, 0));
    let f = level(p + vec2<i32>(1, 0));
    let g = level(p + vec2<i32>(-1, 1));
    let h = level(p + vec2<i32>(0, 1));
    let i = level(p + vec2<i32>(1, 1));
    return vec2<i32>((c + 2 * f + i) - (a + 2 * d + g), (g + 2 * h + i) - (a + 2 * b + c));
}

fn magnitude(p: vec2<i32>) -> i32 {
    if (any(p < vec2<i32>(0)) || any(p >= size)) {
        return 0;
    }
    let g = gradient(p);
    return abs(g.x) + abs(g.y);
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    size = vec2<i32>(textureDimensions(liquid_layer));
    let p = vec2<i32>(id.xy);
    if (p.x >= size.x || p.y >= size.y) {
        return;
    }
    let g = gradient(p);
    let m = abs(g.x) + abs(g.y);
    var kind = 0.0;
    if (m > LOW) {
        let ax = abs(g.x);
        let ay = abs(g.y) << 15u;
        let tg22x = ax * TG22;
        var maximum = false;
        if (ay < tg22x) {
            maximum = m > magnitude(p + vec2<i32>(-1, 0)) && m >= magnitude(p + vec2<i32>(1, 0));
        } else if (ay > tg22x + (ax << 16u)) {
            maximum = m > magnitude(p + vec2<i32>(0, -1)) && m >= magnitude(p + vec2<i32>(0, 1));
        } else {
            let s = select(1, -1, (g.x ^ g.y) < 0);
            maximum = m > magnitude(p + vec2<i32>(-s, -1)) && m > magnitude(p + vec2<i32>(s, 1));
        }
        if (maximum) {
            kind = select(1.0, 2.0, m > HIGH);
        }
    }
    textureStore(output, p, vec4<f32>(kind, 0.0, 0.0, 0.0));
}
