use std::sync::OnceLock;

use wgpu::util::DeviceExt;

use super::*;
use crate::{read_buffer, AdapterChoice};

fn context() -> &'static GpuContext {
    static CONTEXT: OnceLock<GpuContext> = OnceLock::new();
    CONTEXT.get_or_init(|| {
        GpuContext::new(&AdapterChoice::default())
            .unwrap_or_else(|e| panic!("these tests need an adapter (lavapipe is fine): {e}"))
    })
}

/// A xorshift stream: keys with many repeats and all 32 bits in use.
fn keys(n: usize, seed: u32, mask: u32) -> Vec<u32> {
    let mut x = seed | 1;
    (0..n)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x & mask
        })
        .collect()
}

fn read_u32(ctx: &GpuContext, buffer: &wgpu::Buffer, n: usize) -> Vec<u32> {
    let bytes = read_buffer(ctx, buffer).unwrap();
    bytemuck::cast_slice::<u8, u32>(&bytes)[..n].to_vec()
}

fn gpu_sort(keys: &[u32], key_bits: u32, capacity: u32) -> (Vec<u32>, Vec<u32>) {
    let ctx = context();
    let sort = RadixSort::new(ctx, capacity, key_bits).unwrap();
    let values: Vec<u32> = (0..keys.len() as u32).collect();
    ctx.queue
        .write_buffer(sort.keys(), 0, bytemuck::cast_slice(keys));
    ctx.queue
        .write_buffer(sort.values(), 0, bytemuck::cast_slice(&values));
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    sort.encode(ctx, &mut encoder, keys.len() as u32);
    ctx.queue.submit([encoder.finish()]);
    ctx.check().unwrap();
    (
        read_u32(ctx, sort.keys(), keys.len()),
        read_u32(ctx, sort.values(), keys.len()),
    )
}

/// The CPU's stable sort of (key, index) pairs.
fn cpu_sort(keys: &[u32]) -> (Vec<u32>, Vec<u32>) {
    let mut pairs: Vec<(u32, u32)> = keys.iter().copied().zip(0..).collect();
    pairs.sort_by_key(|&(k, _)| k);
    pairs.into_iter().unzip()
}

#[test]
fn sorts_full_keys_like_a_stable_cpu_sort() {
    // 3 blocks and a part; keys of 32 bits with repeats (the mask keeps every 16th bit pattern).
    let keys = keys(3 * 256 + 77, 7, 0xF0F0_F0FF);
    assert_eq!(gpu_sort(&keys, 32, 1000), cpu_sort(&keys));
}

#[test]
fn keeps_the_order_of_equal_keys_across_many_blocks() {
    // Few distinct keys over many blocks: stability is all that orders the values.
    let keys = keys(40_000, 11, 0b1011);
    let (sorted_keys, values) = gpu_sort(&keys, 4, 50_000);
    assert_eq!((sorted_keys, values), cpu_sort(&keys));
}

#[test]
fn a_block_of_one_digit_does_not_overflow_its_counter() {
    // 256 equal keys in a block: the packed 8-bit counters reach their limit.
    let mut keys = vec![9u32; 512];
    keys[300] = 3;
    assert_eq!(gpu_sort(&keys, 4, 512), cpu_sort(&keys));
}

#[test]
fn scans_over_three_levels() {
    let ctx = context();
    let n = 70_001u32; // 274 blocks, then 2, then 1
    let data: Vec<u32> = keys(n as usize, 5, 0xFF);
    let buffer = ctx
        .device
        .create_buffer_init(&wgpu::util::BufferInitDescriptor {
            label: Some("scan test"),
            contents: bytemuck::cast_slice(&data),
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
        });
    let scan = Scan::new(ctx, &buffer, n + 100).unwrap();
    let mut encoder = ctx.device.create_command_encoder(&Default::default());
    scan.encode(ctx, &mut encoder, n);
    ctx.queue.submit([encoder.finish()]);
    let expected: Vec<u32> = data
        .iter()
        .scan(0u32, |sum, &v| {
            let before = *sum;
            *sum += v;
            Some(before)
        })
        .collect();
    assert_eq!(read_u32(ctx, &buffer, n as usize), expected);
}
