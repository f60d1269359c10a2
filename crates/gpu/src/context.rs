use std::sync::{Arc, Mutex};

use crate::GpuError;

/// Which adapter to use: the first Vulkan adapter that is a real GPU, else the CPU one, or the
/// first whose name contains the given text (case-insensitive).
#[derive(Clone, Debug, Default)]
pub struct AdapterChoice {
    pub name_contains: Option<String>,
}

/// Device, queue and the adapter they came from; one per process, shared by reference. Instance
/// and adapter are kept so that a window (the viewer's eframe) can present with the same device.
pub struct GpuContext {
    pub instance: wgpu::Instance,
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub adapter_info: wgpu::AdapterInfo,
    uncaptured: Arc<Mutex<Option<String>>>,
}

fn adapter_rank(info: &wgpu::AdapterInfo) -> u8 {
    match info.device_type {
        wgpu::DeviceType::DiscreteGpu => 0,
        wgpu::DeviceType::IntegratedGpu => 1,
        wgpu::DeviceType::VirtualGpu => 2,
        wgpu::DeviceType::Cpu => 3,
        wgpu::DeviceType::Other => 4,
    }
}

impl GpuContext {
    pub fn new(choice: &AdapterChoice) -> Result<Self, GpuError> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = wgpu::Backends::VULKAN;
        let instance = wgpu::Instance::new(desc);
        let mut adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
        if adapters.is_empty() {
            return Err(GpuError::NoAdapter {
                detail: "Vulkan reports no devices".into(),
            });
        }
        adapters.sort_by_key(|a| adapter_rank(&a.get_info()));
        let adapter = match &choice.name_contains {
            None => adapters.swap_remove(0),
            Some(wanted) => {
                let needle = wanted.to_lowercase();
                let pos = adapters
                    .iter()
                    .position(|a| a.get_info().name.to_lowercase().contains(&needle));
                match pos {
                    Some(i) => adapters.swap_remove(i),
                    None => {
                        let available = adapters
                            .iter()
                            .map(|a| a.get_info().name)
                            .collect::<Vec<_>>()
                            .join(", ");
                        return Err(GpuError::AdapterNotFound {
                            wanted: wanted.clone(),
                            available,
                        });
                    }
                }
            }
        };
        let adapter_info = adapter.get_info();
        let required_limits = wgpu::Limits {
            max_texture_dimension_2d: adapter.limits().max_texture_dimension_2d,
            max_texture_array_layers: adapter.limits().max_texture_array_layers,
            max_buffer_size: adapter.limits().max_buffer_size,
            max_storage_buffer_binding_size: adapter.limits().max_storage_buffer_binding_size,
            ..wgpu::Limits::default()
        };
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("rslam"),
            required_features: wgpu::Features::empty(),
            required_limits,
            ..Default::default()
        }))
        .map_err(|e| GpuError::Device {
            adapter: adapter_info.name.clone(),
            message: e.to_string(),
        })?;
        let uncaptured = Arc::new(Mutex::new(None));
        let sink = uncaptured.clone();
        device.on_uncaptured_error(Arc::new(move |error: wgpu::Error| {
            let mut slot = sink.lock().unwrap_or_else(|p| p.into_inner());
            slot.get_or_insert_with(|| error.to_string());
        }));
        Ok(Self {
            instance,
            adapter,
            device,
            queue,
            adapter_info,
            uncaptured,
        })
    }

    /// "NAME (TYPE, driver DRIVER)", for the log line that names the chosen adapter.
    pub fn describe(&self) -> String {
        let i = &self.adapter_info;
        format!(
            "{} ({:?}, {} {})",
            i.name, i.device_type, i.driver, i.driver_info
        )
    }

    pub fn is_cpu(&self) -> bool {
        self.adapter_info.device_type == wgpu::DeviceType::Cpu
    }

    /// The first GPU error raised outside an error scope since the last check, as data.
    pub fn check(&self) -> Result<(), GpuError> {
        let mut slot = self.uncaptured.lock().unwrap_or_else(|p| p.into_inner());
        match slot.take() {
            Some(message) => Err(GpuError::Validation { message }),
            None => Ok(()),
        }
    }

    /// Blocks until all submitted work is done.
    pub fn wait_idle(&self) -> Result<(), GpuError> {
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| GpuError::Validation {
                message: e.to_string(),
            })?;
        self.check()
    }

    /// A compute pipeline from an embedded shader (entry point `main`, layout derived from the
    /// shader); shader errors come back as [`GpuError::Shader`] naming the file.
    pub fn compute_pipeline(&self, shader_path: &str) -> Result<wgpu::ComputePipeline, GpuError> {
        self.compute_pipeline_entry(shader_path, "main")
    }

    pub fn compute_pipeline_entry(
        &self,
        shader_path: &str,
        entry_point: &str,
    ) -> Result<wgpu::ComputePipeline, GpuError> {
        let module = self.shader_module(shader_path)?;
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let pipeline = self
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(shader_path),
                layout: None,
                module: &module,
                entry_point: Some(entry_point),
                compilation_options: Default::default(),
                cache: None,
            });
        match pollster::block_on(scope.pop()) {
            Some(e) => Err(GpuError::Shader {
                path: shader_path.to_string(),
                message: e.to_string(),
            }),
            None => Ok(pipeline),
        }
    }

    /// A shader module from an embedded shader, includes resolved.
    pub fn shader_module(&self, shader_path: &str) -> Result<wgpu::ShaderModule, GpuError> {
        let source = crate::shader::source(shader_path)?;
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(shader_path),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
        match pollster::block_on(scope.pop()) {
            Some(e) => Err(GpuError::Shader {
                path: shader_path.to_string(),
                message: e.to_string(),
            }),
            None => Ok(module),
        }
    }
}
