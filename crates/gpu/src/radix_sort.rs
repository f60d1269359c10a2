//! A stable LSD radix sort of (u32 key, u32 value) pairs on the GPU, 4 bits a pass
//! (shaders/common/radix_sort.wgsl): count each block's digits, scan the digit-major histogram,
//! scatter. Pairs with equal keys keep their order, so sorting by depth and then stably by tile
//! leaves each tile's pairs in depth order.

use crate::compute::{bind_group, bind_group_at, dispatch_linear, storage_buffer, uniform_buffer};
use crate::scan::Scan;
use crate::{GpuContext, GpuError};

const SHADER: &str = "common/radix_sort.wgsl";
const BLOCK: u32 = 256;
const DIGITS: u32 = 16;
const BITS_PER_PASS: u32 = 4;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SortParams {
    n: u32,
    shift: u32,
    blocks: u32,
    pad: u32,
}

struct Pass {
    params: wgpu::Buffer,
    count: wgpu::BindGroup,
    scatter: wgpu::BindGroup,
}

/// Sorts up to `capacity` pairs held in [`RadixSort::keys`] and [`RadixSort::values`]; the
/// sorted pairs end in the same buffers (the passes ping-pong through a second pair, an even
/// number of times).
pub struct RadixSort {
    capacity: u32,
    count_digits: wgpu::ComputePipeline,
    scatter: wgpu::ComputePipeline,
    keys: [wgpu::Buffer; 2],
    values: [wgpu::Buffer; 2],
    scan: Scan,
    passes: Vec<Pass>,
    _histogram: wgpu::Buffer,
}

impl RadixSort {
    /// A sort of up to `capacity` pairs whose keys use their low `key_bits` bits.
    pub fn new(ctx: &GpuContext, capacity: u32, key_bits: u32) -> Result<Self, GpuError> {
        let capacity = capacity.max(1);
        let count_digits = ctx.compute_pipeline_entry(SHADER, "count_digits")?;
        let scatter = ctx.compute_pipeline_entry(SHADER, "scatter")?;
        let buffer = |label| storage_buffer(ctx, label, capacity as u64 * 4);
        let keys = [buffer("sort keys"), buffer("sort keys (other)")];
        let values = [buffer("sort values"), buffer("sort values (other)")];
        let histogram_len = DIGITS * capacity.div_ceil(BLOCK);
        let histogram = storage_buffer(ctx, "sort histogram", histogram_len as u64 * 4);
        let scan = Scan::new(ctx, &histogram, histogram_len)?;
        let pass_count = key_bits
            .clamp(1, 32)
            .div_ceil(BITS_PER_PASS)
            .next_multiple_of(2);
        let passes = (0..pass_count)
            .map(|p| {
                let (from, to) = ((p % 2) as usize, ((p + 1) % 2) as usize);
                let params = uniform_buffer::<SortParams>(ctx, "sort params");
                let count = [
                    (0, params.as_entire_binding()),
                    (1, keys[from].as_entire_binding()),
                    (3, histogram.as_entire_binding()),
                ];
                let scatter_resources = [
                    params.as_entire_binding(),
                    keys[from].as_entire_binding(),
                    values[from].as_entire_binding(),
                    histogram.as_entire_binding(),
                    keys[to].as_entire_binding(),
                    values[to].as_entire_binding(),
                ];
                Pass {
                    count: bind_group_at(ctx, &count_digits, "sort count", &count),
                    scatter: bind_group(ctx, &scatter, "sort scatter", &scatter_resources),
                    params,
                }
            })
            .collect();
        Ok(Self {
            capacity,
            count_digits,
            scatter,
            keys,
            values,
            scan,
            passes,
            _histogram: histogram,
        })
    }

    pub fn capacity(&self) -> u32 {
        self.capacity
    }

    /// The keys to sort, and sorted after [`RadixSort::encode`].
    pub fn keys(&self) -> &wgpu::Buffer {
        &self.keys[0]
    }

    /// The values that go with the keys.
    pub fn values(&self) -> &wgpu::Buffer {
        &self.values[0]
    }

    /// Records the sort of the first `n` pairs (at most the capacity). The passes' sizes are
    /// uniforms written now: submit before encoding another sort with this one.
    pub fn encode(&self, ctx: &GpuContext, encoder: &mut wgpu::CommandEncoder, n: u32) {
        assert!(
            n <= self.capacity,
            "{n} pairs for a sort of {}",
            self.capacity
        );
        let blocks = n.div_ceil(BLOCK);
        for (p, pass) in self.passes.iter().enumerate() {
            let params = SortParams {
                n,
                shift: p as u32 * BITS_PER_PASS,
                blocks,
                pad: 0,
            };
            ctx.queue
                .write_buffer(&pass.params, 0, bytemuck::bytes_of(&params));
        }
        for pass in &self.passes {
            {
                let mut compute = encoder.begin_compute_pass(&Default::default());
                dispatch_linear(&mut compute, &self.count_digits, &pass.count, blocks);
            }
            self.scan.encode(ctx, encoder, DIGITS * blocks);
            let mut compute = encoder.begin_compute_pass(&Default::default());
            dispatch_linear(&mut compute, &self.scatter, &pass.scatter, blocks);
        }
    }
}

#[cfg(test)]
mod tests;
