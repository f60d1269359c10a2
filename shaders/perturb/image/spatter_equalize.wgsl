// spatter (water), pass 11: cv2.equalizeHist's lookup table from the histogram (one invocation):
// the first occupied level maps to 0, each later level to round(cdf * 255 / (total - first)).

@group(0) @binding(0) var<storage, read> histogram: array<u32, 256>;
@group(0) @binding(1) var<storage, read_write> lut: array<u32, 256>;

@compute @workgroup_size(1)
fn main() {
    var total = 0u;
    for (var i = 0u; i < 256u; i++) {
        total += histogram[i];
        lut[i] = 0u;
    }
    var first = 0u;
    while (first < 255u && histogram[first] == 0u) {
        first++;
    }
    if (histogram[first] == total) {
        lut[first] = first;
        return;
    }
    let scale = 255.0 / f32(total - histogram[first]);
    var sum = 0u;
    for (var i = first + 1u; i < 256u; i++) {
        sum += histogram[i];
        lut[i] = u32(clamp(round(f32(sum) * scale), 0.0, 255.0));
    }
}
