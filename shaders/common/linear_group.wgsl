// Workgroups dispatched as rows of at most 65535 (the per-dimension limit), numbered row by row;
// driven by rslam_gpu::compute::dispatch_linear.
fn linear_group(id: vec3<u32>, count: vec3<u32>) -> u32 {
    return id.y * count.x + id.x;
}
