// The entry point of the 3x3-neighbourhood passes (spatter's Sobel, non-maximum suppression,
// hysteresis, distance, emboss and shade): each invocation walks a run of 8 pixels of a row with
// a sliding 3x3 window, reading each of the 30 samples it needs once instead of 9 per pixel (on
// lavapipe per-invocation overhead and loads dominate these passes). The includer defines
// `fn frame_size() -> vec2<i32>`, `fn sample(p: vec2<i32>) -> f32` (its own edge rule for p
// outside the frame) and `fn pixel(p: vec2<i32>, w: Window)`. Dispatch: (width / 8, height).

// Columns x-1 (l), x (c) and x+1 (r) around a pixel; in each, .x is row y-1, .y row y, .z y+1.
struct Window {
    l: vec3<f32>,
    c: vec3<f32>,
    r: vec3<f32>,
}

var<private> window: Window;

fn window_column(x: i32, y: i32) -> vec3<f32> {
    return vec3<f32>(sample(vec2<i32>(x, y - 1)), sample(vec2<i32>(x, y)), sample(vec2<i32>(x, y + 1)));
}

fn window_step(x: i32, y: i32, width: i32) {
    window = Window(window.c, window.r, window_column(x + 1, y));
    if (x < width) {
        pixel(vec2<i32>(x, y), window);
    }
}

@compute @workgroup_size(8, 8)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let size = frame_size();
    let x0 = i32(id.x) * 8;
    let y = i32(id.y);
    if (x0 >= size.x || y >= size.y) {
        return;
    }
    window.c = window_column(x0 - 1, y);
    window.r = window_column(x0, y);
    window_step(x0, y, size.x);
    window_step(x0 + 1, y, size.x);
    window_step(x0 + 2, y, size.x);
    window_step(x0 + 3, y, size.x);
    window_step(x0 + 4, y, size.x);
    window_step(x0 + 5, y, size.x);
    window_step(x0 + 6, y, size.x);
    window_step(x0 + 7, y, size.x);
}
