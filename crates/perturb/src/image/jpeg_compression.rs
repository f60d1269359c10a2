//! jpeg_compression: a real baseline-JPEG round trip (imagecorruptions saves with Pillow at the
//! severity's quality and decodes again), in libjpeg-turbo's integer arithmetic: YCbCr, 4:2:0
//! chroma, accurate-integer 8×8 DCT, IJG tables scaled by quality, fancy upsampling. Entropy
//! coding is lossless and skipped. Matches Pillow's output bit for bit where libjpeg-turbo's
//! SIMD paths equal its C code (they are designed to).

use bytemuck::{Pod, Zeroable};
use rslam_gpu::FrameTextures;

use super::textures::storage_texture;
use crate::image_f32::RgbF32;
use crate::perturbation::{view, Between, CatalogueEntry, FrameKey, GpuPerturbation, Group, Kit};
use crate::twin::{Tolerance, Twin};
use crate::uniform_layout::{rust_layout, UniformLayout};
use crate::PerturbError;

const NAME: &str = "jpeg_compression";
const BLOCKS_SHADER: &str = "perturb/image/jpeg_compression_blocks.wgsl";
const DECODE_SHADER: &str = "perturb/image/jpeg_compression.wgsl";

/// JPEG quality per severity (docs/src/perturbations.md §3, imagecorruptions `jpeg_compression`).
pub const QUALITY: [u32; 5] = [25, 18, 15, 10, 7];

/// ITU T.81 Annex K luminance table (natural order), libjpeg's `std_luminance_quant_tbl`.
const LUMA_BASE: [u32; 64] = [
    16, 11, 10, 16, 24, 40, 51, 61, 12, 12, 14, 19, 26, 58, 60, 55, 14, 13, 16, 24, 40, 57, 69, 56,
    14, 17, 22, 29, 51, 87, 80, 62, 18, 22, 37, 56, 68, 109, 103, 77, 24, 35, 55, 64, 81, 104, 113,
    92, 49, 64, 78, 87, 103, 121, 120, 101, 72, 92, 95, 98, 112, 100, 103, 99,
];

/// ITU T.81 Annex K chrominance table (natural order).
const CHROMA_BASE: [u32; 64] = [
    17, 18, 24, 47, 99, 99, 99, 99, 18, 21, 26, 66, 99, 99, 99, 99, 24, 26, 56, 99, 99, 99, 99, 99,
    47, 66, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99,
    99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99, 99,
];

pub const ENTRY: CatalogueEntry = CatalogueEntry {
    name: NAME,
    group: Group::Image,
    description: "JPEG round trip (libjpeg-turbo arithmetic: 4:2:0, integer DCT, IJG tables)",
    parameters: |s| format!("quality={}", QUALITY[s as usize - 1]),
    build: |kit| Ok(Box::new(JpegCompression::new(kit)?)),
    between: Between::Interpolated("quality linear from 100, rounded"),
    explicit: None,
    twin: Twin::Color(twin),
    // libjpeg-turbo's integer arithmetic on both sides.
    twin_tolerance: Tolerance::EXACT,
    uniforms: &[UniformLayout {
        rust: rust_layout!(Tables { quant }),
        wgsl: "Tables",
        shader: BLOCKS_SHADER,
    }],
};

/// libjpeg's `jpeg_set_quality(quality, force_baseline = TRUE)`: luma and chroma tables.
pub fn quant_tables(quality: u32) -> [[i32; 64]; 2] {
    let q = quality.clamp(1, 100);
    let scale = if q < 50 { 5000 / q } else { 200 - 2 * q };
    let table = |base: &[u32; 64]| base.map(|b| ((b * scale + 50) / 100).clamp(1, 255) as i32);
    [table(&LUMA_BASE), table(&CHROMA_BASE)]
}

#[repr(C)]
#[derive(Clone, Copy, Pod, Zeroable)]
struct Tables {
    quant: [[i32; 4]; 32],
}

/// The quality at the frame's severity: linear between the table's rows from 100 at severity 0,
/// rounded to a whole quality as libjpeg takes it.
fn quality(key: &FrameKey) -> u32 {
    key.interpolate(100.0, &QUALITY).round() as u32
}

fn tables(key: &FrameKey) -> Tables {
    let [luma, chroma] = quant_tables(quality(key));
    let mut quant = [[0; 4]; 32];
    for (i, v) in luma.iter().chain(chroma.iter()).enumerate() {
        quant[i / 4][i % 4] = *v;
    }
    Tables { quant }
}

struct JpegCompression {
    blocks: wgpu::ComputePipeline,
    decode: wgpu::ComputePipeline,
    tables: wgpu::Buffer,
    luma: wgpu::Texture,
    chroma: wgpu::Texture,
}

impl JpegCompression {
    fn new(kit: &Kit) -> Result<Self, PerturbError> {
        let (w16, h16) = (
            kit.width.next_multiple_of(16),
            kit.height.next_multiple_of(16),
        );
        let r32 = wgpu::TextureFormat::R32Uint;
        Ok(Self {
            blocks: kit.pipeline(BLOCKS_SHADER)?,
            decode: kit.pipeline(DECODE_SHADER)?,
            tables: kit.uniform_buffer::<Tables>("jpeg tables"),
            luma: storage_texture(kit, "jpeg luma", r32, w16, h16),
            chroma: storage_texture(kit, "jpeg chroma", r32, w16, h16 / 2),
        })
    }
}

impl GpuPerturbation for JpegCompression {
    fn encode(
        &mut self,
        kit: &Kit,
        encoder: &mut wgpu::CommandEncoder,
        frame: &FrameTextures,
        key: &FrameKey,
    ) -> Result<(), PerturbError> {
        kit.write_uniform(&self.tables, &tables(key));
        let (luma, chroma, color) = (view(&self.luma), view(&self.chroma), frame.color_view());
        let blocks = kit.bind_group(
            &self.blocks,
            "jpeg blocks",
            &[
                wgpu::BindingResource::TextureView(color),
                wgpu::BindingResource::TextureView(&luma),
                wgpu::BindingResource::TextureView(&chroma),
                self.tables.as_entire_binding(),
            ],
        );
        let mcus = [kit.width.div_ceil(16), kit.height.div_ceil(16)];
        let groups = [mcus[0].div_ceil(8), mcus[1].div_ceil(8), 5];
        kit.dispatch_workgroups(encoder, &self.blocks, &blocks, "jpeg blocks", groups);
        let decode = kit.bind_group(
            &self.decode,
            "jpeg decode",
            &[
                wgpu::BindingResource::TextureView(&luma),
                wgpu::BindingResource::TextureView(&chroma),
                wgpu::BindingResource::TextureView(color),
            ],
        );
        // One invocation per chroma sample: its 2×2 pixels.
        let (w, h) = (kit.width.div_ceil(2), kit.height.div_ceil(2));
        kit.dispatch_grid(encoder, &self.decode, &decode, "jpeg decode", w, h);
        Ok(())
    }
}

const CONST_BITS: i32 = 13;
const PASS1_BITS: i32 = 2;

fn descale(x: i32, n: i32) -> i32 {
    (x + (1 << (n - 1))) >> n
}

/// One 1-D pass of jfdctint.c (the twin of `fdct8`).
fn fdct8(d: [i32; 8], first: bool) -> [i32; 8] {
    let mut o = [0; 8];
    let (tmp0, tmp7) = (d[0] + d[7], d[0] - d[7]);
    let (tmp1, tmp6) = (d[1] + d[6], d[1] - d[6]);
    let (tmp2, tmp5) = (d[2] + d[5], d[2] - d[5]);
    let (tmp3, tmp4) = (d[3] + d[4], d[3] - d[4]);
    let (tmp10, tmp13) = (tmp0 + tmp3, tmp0 - tmp3);
    let (tmp11, tmp12) = (tmp1 + tmp2, tmp1 - tmp2);
    let shift = if first {
        o[0] = (tmp10 + tmp11) << PASS1_BITS;
        o[4] = (tmp10 - tmp11) << PASS1_BITS;
        CONST_BITS - PASS1_BITS
    } else {
        o[0] = descale(tmp10 + tmp11, PASS1_BITS);
        o[4] = descale(tmp10 - tmp11, PASS1_BITS);
        CONST_BITS + PASS1_BITS
    };
    let z1 = (tmp12 + tmp13) * 4433;
    o[2] = descale(z1 + tmp13 * 6270, shift);
    o[6] = descale(z1 - tmp12 * 15137, shift);
    let z5 = (tmp4 + tmp5 + tmp6 + tmp7) * 9633;
    let b1 = (tmp4 + tmp7) * -7373;
    let b2 = (tmp5 + tmp6) * -20995;
    let b3 = (tmp4 + tmp6) * -16069 + z5;
    let b4 = (tmp5 + tmp7) * -3196 + z5;
    o[7] = descale(tmp4 * 2446 + b1 + b3, shift);
    o[5] = descale(tmp5 * 16819 + b2 + b4, shift);
    o[3] = descale(tmp6 * 25172 + b2 + b3, shift);
    o[1] = descale(tmp7 * 12299 + b1 + b4, shift);
    o
}

/// One 1-D pass of jidctint.c on dequantised input (the twin of `idct8`).
fn idct8(d: [i32; 8], shift: i32) -> [i32; 8] {
    let z1 = (d[2] + d[6]) * 4433;
    let tmp2 = z1 - d[6] * 15137;
    let tmp3 = z1 + d[2] * 6270;
    let tmp0 = (d[0] + d[4]) << CONST_BITS;
    let tmp1 = (d[0] - d[4]) << CONST_BITS;
    let (tmp10, tmp13) = (tmp0 + tmp3, tmp0 - tmp3);
    let (tmp11, tmp12) = (tmp1 + tmp2, tmp1 - tmp2);
    let (i0, i1, i2, i3) = (d[7], d[5], d[3], d[1]);
    let z5 = (i0 + i1 + i2 + i3) * 9633;
    let c1 = (i0 + i3) * -7373;
    let c2 = (i1 + i2) * -20995;
    let c3 = (i0 + i2) * -16069 + z5;
    let c4 = (i1 + i3) * -3196 + z5;
    let e0 = i0 * 2446 + c1 + c3;
    let e1 = i1 * 16819 + c2 + c4;
    let e2 = i2 * 25172 + c2 + c3;
    let e3 = i3 * 12299 + c1 + c4;
    [
        descale(tmp10 + e3, shift),
        descale(tmp11 + e2, shift),
        descale(tmp12 + e1, shift),
        descale(tmp13 + e0, shift),
        descale(tmp13 - e0, shift),
        descale(tmp12 - e1, shift),
        descale(tmp11 - e2, shift),
        descale(tmp10 - e3, shift),
    ]
}

/// libjpeg's post-IDCT range-limit table, `table[x & 1023]`.
fn range_limit(x: i32) -> u8 {
    match x & 1023 {
        i @ 0..128 => (i + 128) as u8,
        128..512 => 255,
        512..896 => 0,
        i => (i - 896) as u8,
    }
}

/// FDCT, quantise, dequantise, IDCT of one block of level-shifted samples.
fn round_trip(samples: [i32; 64], table: &[i32; 64]) -> [u8; 64] {
    let mut m = samples;
    for r in 0..8 {
        let row = fdct8(std::array::from_fn(|c| m[r * 8 + c]), true);
        m[r * 8..r * 8 + 8].copy_from_slice(&row);
    }
    for c in 0..8 {
        let column = fdct8(std::array::from_fn(|r| m[r * 8 + c]), false);
        for (r, v) in column.iter().enumerate() {
            let q = table[r * 8 + c];
            let divisor = 8 * q;
            let level = (v.abs() + (divisor >> 1)) / divisor;
            m[r * 8 + c] = if *v < 0 { -level } else { level } * q;
        }
    }
    for c in 0..8 {
        let column = idct8(
            std::array::from_fn(|r| m[r * 8 + c]),
            CONST_BITS - PASS1_BITS,
        );
        for (r, v) in column.iter().enumerate() {
            m[r * 8 + c] = *v;
        }
    }
    std::array::from_fn(|i| {
        let (r, c) = (i / 8, i % 8);
        let row = idct8(
            std::array::from_fn(|k| m[r * 8 + k]),
            CONST_BITS + PASS1_BITS + 3,
        );
        range_limit(row[c])
    })
}

fn luma_of([r, g, b]: [i32; 3]) -> i32 {
    (19595 * r + 38470 * g + 7471 * b + 32768) >> 16
}

fn chroma_of([r, g, b]: [i32; 3]) -> [i32; 2] {
    let offset = (128 << 16) + 32767;
    [
        (-11059 * r - 21709 * g + 32768 * b + offset) >> 16,
        (32768 * r - 27439 * g - 5329 * b + offset) >> 16,
    ]
}

/// CPU twin of both passes.
pub fn twin(image: &RgbF32, key: &FrameKey) -> RgbF32 {
    let [luma_q, chroma_q] = quant_tables(quality(key));
    let (w, h) = (image.width as i32, image.height as i32);
    let (w16, h16) = ((w + 15) / 16 * 16, (h + 15) / 16 * 16);
    let rgb = |x: i32, y: i32| -> [i32; 3] {
        let p = image.at_clamped(x as i64, y as i64);
        p.map(|v| (v * 255.0).round() as i32)
    };
    let mut luma = vec![0u8; (w16 * h16) as usize];
    let (cw16, ch16) = (w16 / 2, h16 / 2);
    let mut chroma = [
        vec![0u8; (cw16 * ch16) as usize],
        vec![0u8; (cw16 * ch16) as usize],
    ];
    for by in (0..h16).step_by(8) {
        for bx in (0..w16).step_by(8) {
            let samples =
                std::array::from_fn(|i| luma_of(rgb(bx + i as i32 % 8, by + i as i32 / 8)) - 128);
            for (i, v) in round_trip(samples, &luma_q).iter().enumerate() {
                luma[((by + i as i32 / 8) * w16 + bx + i as i32 % 8) as usize] = *v;
            }
        }
    }
    for (channel, plane) in chroma.iter_mut().enumerate() {
        for by in (0..ch16).step_by(8) {
            for bx in (0..cw16).step_by(8) {
                let samples = std::array::from_fn(|i| {
                    let (cx, cy) = (bx + i as i32 % 8, by + i as i32 / 8);
                    let sum: i32 = [(0, 0), (1, 0), (0, 1), (1, 1)]
                        .iter()
                        .map(|(dx, dy)| chroma_of(rgb(2 * cx + dx, 2 * cy + dy))[channel])
                        .sum();
                    ((sum + 1 + (cx & 1)) >> 2) - 128
                });
                for (i, v) in round_trip(samples, &chroma_q).iter().enumerate() {
                    plane[((by + i as i32 / 8) * cw16 + bx + i as i32 % 8) as usize] = *v;
                }
            }
        }
    }
    let (last_x, last_y) = ((w + 1) / 2 - 1, (h + 1) / 2 - 1);
    let upsample = |plane: &[u8], x: i32, y: i32| -> i32 {
        let at = |cx: i32, cy: i32| {
            plane[(cy.clamp(0, last_y) * cw16 + cx.clamp(0, last_x)) as usize] as i32
        };
        let (cx, cy) = (x / 2, y / 2);
        let far = if y & 1 == 0 { cy - 1 } else { cy + 1 };
        let sum = |c: i32| 3 * at(c, cy) + at(c, far);
        if x & 1 == 0 {
            (3 * sum(cx) + sum(cx - 1) + 8) >> 4
        } else {
            (3 * sum(cx) + sum(cx + 1) + 7) >> 4
        }
    };
    let mut out = image.clone();
    for y in 0..h {
        for x in 0..w {
            let luma_value = luma[(y * w16 + x) as usize] as i32;
            let cb = upsample(&chroma[0], x, y) - 128;
            let cr = upsample(&chroma[1], x, y) - 128;
            let r = luma_value + ((91881 * cr + 32768) >> 16);
            let g = luma_value + ((-22554 * cb + 32768 - 46802 * cr) >> 16);
            let b = luma_value + ((116130 * cb + 32768) >> 16);
            let i = out.index(x as u32, y as u32);
            out.data[i] = [r, g, b].map(|v| v.clamp(0, 255) as f32 / 255.0);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing;

    #[test]
    fn quality_scales_the_tables_like_libjpeg() {
        // Pillow at quality 7 reports luma [114, 79, 71, 114, 171, 255, ...], chroma [121, 129, ...].
        let [luma, chroma] = quant_tables(7);
        assert_eq!(luma[..6], [114, 79, 71, 114, 171, 255]);
        assert_eq!(chroma[..3], [121, 129, 171]);
        let [luma25, _] = quant_tables(25);
        assert_eq!(luma25[0], 32);
    }

    #[test]
    fn dct_round_trip_of_a_flat_block_is_exact() {
        // A flat block has only a DC coefficient, exactly representable at any table.
        let table = quant_tables(7)[0];
        let out = round_trip([100 - 128; 64], &table);
        assert!(
            out.iter().all(|&v| (v as i32 - 100).abs() <= table[0] / 16),
            "{out:?}"
        );
        let exact = round_trip([0; 64], &table);
        assert!(exact.iter().all(|&v| v == 128));
    }

    #[test]
    fn twin_reproduces_pillow_bit_for_bit() {
        // Expected: Pillow 13 (libjpeg-turbo) `save(quality=q)` + decode of this 37×29 pattern,
        // as a 64-bit FNV-1a of the RGB bytes and two pixels.
        let (w, h) = (37u32, 29u32);
        let mut image = rslam_core::RgbImage::new(w, h);
        for y in 0..h {
            for x in 0..w {
                let i = 3 * (y * w + x) as usize;
                let v = [(x * 7 + y * 13) % 256, (x * x + 3 * y) % 256, (x * y) % 256];
                for (c, value) in v.iter().enumerate() {
                    image.data[i + c] = *value as u8;
                }
            }
        }
        for (severity, hash, first, last) in [
            (1, 0xb105_0b9d_ac9c_74ef_u64, [6, 7, 0], [102, 101, 221]),
            (5, 0x5874_ebd8_edf5_5f95, [0, 21, 0], [55, 55, 185]),
        ] {
            let out = twin(&RgbF32::from_rgb8(&image), &testing::key(0, severity)).to_rgb8();
            assert_eq!(out.pixel(0, 0), first, "severity {severity}");
            assert_eq!(out.pixel(36, 28), last, "severity {severity}");
            assert_eq!(
                rslam_core::hash::fnv1a64(&out.data),
                hash,
                "severity {severity}"
            );
        }
    }
}
