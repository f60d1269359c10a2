// TEMPORARY micro-benchmark (engineer B); deleted before the report.
use std::time::Instant;
use rslam_gpu::{AdapterChoice, GpuContext};
fn main() {
    let ctx = GpuContext::new(&AdapterChoice::default()).unwrap();
    let (w, h) = (1200u32, 680u32);
    let dir = std::env::args().nth(1).unwrap();
    let tex = |format| ctx.device.create_texture(&wgpu::TextureDescriptor { label: None, size: wgpu::Extent3d { width: w, height: h, depth_or_array_layers: 1 }, mip_level_count: 1, sample_count: 1, dimension: wgpu::TextureDimension::D2, format, usage: wgpu::TextureUsages::STORAGE_BINDING | wgpu::TextureUsages::TEXTURE_BINDING, view_formats: &[] });
    let a8 = tex(wgpu::TextureFormat::Rgba8Unorm);
    let f32t = tex(wgpu::TextureFormat::Rgba32Float);
    let uni = ctx.device.create_buffer(&wgpu::BufferDescriptor { label: None, size: 16 + 256 * 16, usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST, mapped_at_creation: false });
    let mut data = vec![0f32; 4 + 256 * 4];
    data[0] = f32::from_bits(24); data[1] = f32::from_bits(56);
    for k in 0..49 { data[4 + 4 * k] = 0.02; }
    ctx.queue.write_buffer(&uni, 0, bytemuck::cast_slice(&data));
    let samp = ctx.device.create_sampler(&wgpu::SamplerDescriptor { mag_filter: wgpu::FilterMode::Nearest, min_filter: wgpu::FilterMode::Nearest, ..Default::default() });
    let mut entries: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).collect();
    entries.sort();
    for path in entries {
        let src = std::fs::read_to_string(&path).unwrap();
        let module = ctx.device.create_shader_module(wgpu::ShaderModuleDescriptor { label: None, source: wgpu::ShaderSource::Wgsl(src.clone().into()) });
        let pipeline = ctx.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor { label: None, layout: None, module: &module, entry_point: Some("main"), compilation_options: Default::default(), cache: None });
        let va = a8.create_view(&Default::default()); let vf = f32t.create_view(&Default::default());
        let bg = [
            wgpu::BindGroupEntry { binding: 0, resource: wgpu::BindingResource::TextureView(&va) },
            wgpu::BindGroupEntry { binding: 1, resource: wgpu::BindingResource::TextureView(&vf) },
            wgpu::BindGroupEntry { binding: 2, resource: uni.as_entire_binding() }];
        let mut all = bg.to_vec();
        if src.contains("binding(3)") { all.push(wgpu::BindGroupEntry { binding: 3, resource: wgpu::BindingResource::Sampler(&samp) }); }
        let bg = ctx.device.create_bind_group(&wgpu::BindGroupDescriptor { label: None, layout: &pipeline.get_bind_group_layout(0), entries: &all });
        let d: Vec<u32> = src.lines().next().unwrap_or("").trim_start_matches("// dispatch:").split_whitespace().filter_map(|v| v.parse().ok()).collect();
        let (dx, dy) = if d.len() == 2 { (d[0], d[1]) } else { (150, 85) };
        let mut times = vec![];
        for _ in 0..12 {
            let t = Instant::now();
            let mut enc = ctx.device.create_command_encoder(&Default::default());
            { let mut p = enc.begin_compute_pass(&Default::default()); p.set_pipeline(&pipeline); p.set_bind_group(0, &bg, &[]); p.dispatch_workgroups(dx, dy, 1); }
            ctx.queue.submit([enc.finish()]);
            ctx.wait_idle().unwrap();
            times.push(t.elapsed().as_secs_f64()*1e3);
        }
        times.sort_by(f64::total_cmp);
        println!("{:40} min {:7.2} med {:7.2}", path.file_name().unwrap().to_str().unwrap(), times[0], times[6]);
    }
}
