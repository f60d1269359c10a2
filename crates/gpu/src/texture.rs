//! Frame-sized textures: the one place their descriptor is written.

use crate::GpuContext;

impl GpuContext {
    /// A 2-D texture of one mip level and one sample.
    pub fn texture_2d(
        &self,
        label: &str,
        format: wgpu::TextureFormat,
        (width, height): (u32, u32),
        usage: wgpu::TextureUsages,
        view_formats: &[wgpu::TextureFormat],
    ) -> wgpu::Texture {
        self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width,
                height,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage,
            view_formats,
        })
    }

    /// What compute passes write and read: storage, sampled, copyable.
    pub fn storage_texture(
        &self,
        label: &str,
        format: wgpu::TextureFormat,
        size: (u32, u32),
    ) -> wgpu::Texture {
        let usage = wgpu::TextureUsages::STORAGE_BINDING
            | wgpu::TextureUsages::TEXTURE_BINDING
            | wgpu::TextureUsages::COPY_SRC
            | wgpu::TextureUsages::COPY_DST;
        self.texture_2d(label, format, size, usage, &[])
    }
}
