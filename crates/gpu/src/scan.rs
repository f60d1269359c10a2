//! Exclusive prefix sums of u32 on the GPU, in place (shaders/common/scan.wgsl): 256 values a
//! workgroup, the blocks' totals scanned the same way, level by level, and added back.

use crate::compute::{bind_group, dispatch_linear, storage_buffer, uniform_buffer};
use crate::{GpuContext, GpuError};

const SHADER: &str = "common/scan.wgsl";
const BLOCK: u32 = 256;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct ScanParams {
    n: u32,
    pad: [u32; 3],
}

/// One level: its size (a uniform) and the bind groups over its values and its blocks' totals.
struct Level {
    params: wgpu::Buffer,
    scan: wgpu::BindGroup,
    add: wgpu::BindGroup,
}

/// Scans the first `n ≤ capacity` values of one buffer.
pub struct Scan {
    scan_blocks: wgpu::ComputePipeline,
    add_block_sums: wgpu::ComputePipeline,
    levels: Vec<Level>,
    /// Keeps every level's block totals alive.
    _sums: Vec<wgpu::Buffer>,
}

impl Scan {
    /// Scans `data` (a storage buffer of at least `capacity` u32s).
    pub fn new(ctx: &GpuContext, data: &wgpu::Buffer, capacity: u32) -> Result<Self, GpuError> {
        let scan_blocks = ctx.compute_pipeline_entry(SHADER, "scan_blocks")?;
        let add_block_sums = ctx.compute_pipeline_entry(SHADER, "add_block_sums")?;
        let mut sums = Vec::new();
        let mut levels = Vec::new();
        let mut count = capacity.max(1);
        loop {
            let blocks = count.div_ceil(BLOCK);
            sums.push(storage_buffer(ctx, "scan block sums", blocks as u64 * 4));
            let params = uniform_buffer::<ScanParams>(ctx, "scan params");
            let level_data = if levels.is_empty() {
                data
            } else {
                &sums[sums.len() - 2]
            };
            let bind = |pipeline| {
                bind_group(
                    ctx,
                    pipeline,
                    "scan",
                    &[
                        params.as_entire_binding(),
                        level_data.as_entire_binding(),
                        sums[sums.len() - 1].as_entire_binding(),
                    ],
                )
            };
            levels.push(Level {
                scan: bind(&scan_blocks),
                add: bind(&add_block_sums),
                params,
            });
            if blocks == 1 {
                break;
            }
            count = blocks;
        }
        Ok(Self {
            scan_blocks,
            add_block_sums,
            levels,
            _sums: sums,
        })
    }

    /// Records the scan of the first `n` values (at most the capacity). The level sizes are
    /// uniforms written now: submit before encoding another scan with this one.
    pub fn encode(&self, ctx: &GpuContext, encoder: &mut wgpu::CommandEncoder, n: u32) {
        let mut counts = vec![n];
        while *counts.last().expect("one") > BLOCK {
            counts.push(counts.last().expect("one").div_ceil(BLOCK));
        }
        for (level, &count) in self.levels.iter().zip(&counts) {
            let params = ScanParams {
                n: count,
                pad: [0; 3],
            };
            ctx.queue
                .write_buffer(&level.params, 0, bytemuck::bytes_of(&params));
        }
        let mut pass = encoder.begin_compute_pass(&Default::default());
        for (level, &count) in self.levels.iter().zip(&counts) {
            dispatch_linear(
                &mut pass,
                &self.scan_blocks,
                &level.scan,
                count.div_ceil(BLOCK),
            );
        }
        for (level, &count) in self.levels.iter().zip(&counts).rev().skip(1) {
            dispatch_linear(
                &mut pass,
                &self.add_block_sums,
                &level.add,
                count.div_ceil(BLOCK),
            );
        }
    }
}
