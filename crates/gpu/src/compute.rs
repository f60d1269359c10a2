//! Small helpers for compute passes, shared by the perturbations and the splat rasteriser:
//! storage and uniform buffers, bind groups of derived layouts (resources numbered from 0, or
//! numbered explicitly), and dispatches of more workgroups than one grid row holds.

use crate::GpuContext;

/// The most workgroups one dispatch dimension takes (WebGPU's default limit).
const MAX_GROUPS_PER_ROW: u32 = 65_535;

/// A storage buffer of at least 4 bytes that can be copied to and from.
pub fn storage_buffer(ctx: &GpuContext, label: &str, size: u64) -> wgpu::Buffer {
    ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: size.max(4).next_multiple_of(4),
        usage: wgpu::BufferUsages::STORAGE
            | wgpu::BufferUsages::COPY_DST
            | wgpu::BufferUsages::COPY_SRC,
        mapped_at_creation: false,
    })
}

/// A uniform buffer sized for `T`, written with `queue.write_buffer`.
pub fn uniform_buffer<T: bytemuck::Pod>(ctx: &GpuContext, label: &str) -> wgpu::Buffer {
    ctx.device.create_buffer(&wgpu::BufferDescriptor {
        label: Some(label),
        size: std::mem::size_of::<T>() as u64,
        usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
        mapped_at_creation: false,
    })
}

/// A bind group for group 0 of `pipeline`, binding `resources[i]` at binding `i`.
pub fn bind_group(
    ctx: &GpuContext,
    pipeline: &wgpu::ComputePipeline,
    label: &str,
    resources: &[wgpu::BindingResource],
) -> wgpu::BindGroup {
    let numbered: Vec<(u32, wgpu::BindingResource)> = (resources.iter().enumerate())
        .map(|(i, resource)| (i as u32, resource.clone()))
        .collect();
    bind_group_at(ctx, pipeline, label, &numbered)
}

/// A bind group for group 0 of `pipeline` with explicit binding numbers, for entry points that
/// use only some of their shader's bindings (the layout derived for them has only those).
pub fn bind_group_at(
    ctx: &GpuContext,
    pipeline: &wgpu::ComputePipeline,
    label: &str,
    resources: &[(u32, wgpu::BindingResource)],
) -> wgpu::BindGroup {
    let entries: Vec<wgpu::BindGroupEntry> = resources
        .iter()
        .map(|(binding, resource)| wgpu::BindGroupEntry {
            binding: *binding,
            resource: resource.clone(),
        })
        .collect();
    ctx.device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some(label),
        layout: &pipeline.get_bind_group_layout(0),
        entries: &entries,
    })
}

/// Dispatches `groups` workgroups as rows of at most 65535; shaders number them with
/// `linear_group` (shaders/common/linear_group.wgsl) and skip what lies past their data.
pub fn dispatch_linear(
    pass: &mut wgpu::ComputePass,
    pipeline: &wgpu::ComputePipeline,
    bind_group: &wgpu::BindGroup,
    groups: u32,
) {
    if groups == 0 {
        return;
    }
    pass.set_pipeline(pipeline);
    pass.set_bind_group(0, bind_group, &[]);
    let rows = groups.div_ceil(MAX_GROUPS_PER_ROW);
    pass.dispatch_workgroups(groups.min(MAX_GROUPS_PER_ROW), rows, 1);
}
