//! Image encoding and decoding. Colour PNG with fast compression (the default level costs 10–40×
//! more time for a few percent of size); depth PNG fast or small ([`DepthPng`]); JPEG through
//! libjpeg-turbo.

use std::io::Cursor;
use std::path::Path;

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};

use crate::dataset::DepthPng;
use crate::limits::MAX_IMAGE_SIDE;
use crate::{printable, CoreError, DepthImage, MaskImage, RgbImage};

fn encode_failed(what: &str, e: impl std::fmt::Display) -> CoreError {
    CoreError::Encode {
        message: format!("{what}: {e}"),
    }
}

/// JPEG at `quality` with full-resolution chroma (4:4:4), through libjpeg-turbo: its SIMD
/// encoder takes about a third of `jpeg-encoder`'s time for the same quantisation tables, sizes
/// and PSNR (docs/src/performance.md, "JPEG encoding"). libjpeg allows at most 65,500 pixels a side.
pub fn encode_jpeg(image: &RgbImage, quality: u8) -> Result<Vec<u8>, CoreError> {
    let failed = |e: String| {
        encode_failed(
            "JPEG",
            format!("{}x{} image: {e}", image.width, image.height),
        )
    };
    let expected = 3 * image.width as usize * image.height as usize;
    if image.data.len() != expected {
        let got = image.data.len();
        return Err(failed(format!("{got} bytes of RGB, expected {expected}")));
    }
    let pixels = turbojpeg::Image {
        pixels: image.data.as_slice(),
        width: image.width as usize,
        pitch: 3 * image.width as usize,
        height: image.height as usize,
        format: turbojpeg::PixelFormat::RGB,
    };
    let mut compressor = turbojpeg::Compressor::new().map_err(|e| encode_failed("JPEG", e))?;
    compressor
        .set_quality(i32::from(quality))
        .and_then(|()| compressor.set_subsamp(turbojpeg::Subsamp::None))
        .and_then(|()| compressor.compress_to_vec(pixels))
        .map_err(|e| failed(e.to_string()))
}

/// Fast deflate (Default takes 10–40× longer). Paeth alone gave the same sizes as per-row
/// adaptive filtering on rendered and on noisy frames, 15–25 % sooner.
fn png_encoder(out: &mut Vec<u8>) -> PngEncoder<&mut Vec<u8>> {
    PngEncoder::new_with_quality(out, CompressionType::Fast, FilterType::Paeth)
}

/// Depth goes to the png crate itself, as big-endian samples, with the settings the image crate's
/// encoder would pass: the image crate takes native-endian samples and swaps every byte pair
/// into a second buffer first. `Small` is zlib level 2 with adaptive filtering, the knee on
/// rendered depth (the `depth_png_settings` example; docs/src/performance.md, "Depth PNG encoding"): a third of `Fast`'s
/// bytes for 2.3–2.7× its time. Level 1 is 38 % larger; level 3 saves 13 % more for 1.75× the
/// time, level 9 27 % for 8×.
fn write_depth_png(
    out: &mut Vec<u8>,
    (width, height): (u32, u32),
    samples: &[u8],
    encoding: DepthPng,
) -> Result<(), png::EncodingError> {
    let mut encoder = png::Encoder::new(out, width, height);
    encoder.set_color(png::ColorType::Grayscale);
    encoder.set_depth(png::BitDepth::Sixteen);
    match encoding {
        DepthPng::Fast => {
            encoder.set_compression(png::Compression::Fast);
            encoder.set_filter(png::Filter::Paeth);
        }
        DepthPng::Small => {
            encoder.set_compression(png::Compression::Fast);
            encoder.set_deflate_compression(png::DeflateCompression::Level(2));
            encoder.set_filter(png::Filter::Adaptive);
        }
    }
    encoder.write_header()?.write_image_data(samples)
}

pub fn encode_png(image: &RgbImage) -> Result<Vec<u8>, CoreError> {
    let mut out = Vec::new();
    png_encoder(&mut out)
        .write_image(
            &image.data,
            image.width,
            image.height,
            ExtendedColorType::Rgb8,
        )
        .map_err(|e| encode_failed("PNG", e))?;
    Ok(out)
}

/// `image`'s luma, `round(0.299 R + 0.587 G + 0.114 B)` (ITU-R BT.601, as OpenCV's
/// `COLOR_RGB2GRAY`).
pub(crate) fn luma8(image: &RgbImage) -> impl Iterator<Item = u8> + '_ {
    image
        .data
        .chunks_exact(3)
        .map(|p| (0.299 * p[0] as f64 + 0.587 * p[1] as f64 + 0.114 * p[2] as f64).round() as u8)
}

/// 8-bit grey PNG of `image`'s luma (EuRoC's cameras are grey).
pub fn encode_grey_png(image: &RgbImage) -> Result<Vec<u8>, CoreError> {
    let grey: Vec<u8> = luma8(image).collect();
    let mut out = Vec::new();
    png_encoder(&mut out)
        .write_image(&grey, image.width, image.height, ExtendedColorType::L8)
        .map_err(|e| encode_failed("grey PNG", e))?;
    Ok(out)
}

/// 16-bit grey PNG of `image`'s 8-bit luma times 257, so that full scale stays full scale and
/// the high byte, which [`read_grey16_high_byte`] and OpenCV's 8-bit read take, is the luma.
pub fn encode_grey16_png(image: &RgbImage) -> Result<Vec<u8>, CoreError> {
    let grey: Vec<u16> = luma8(image).map(|v| v as u16 * 257).collect();
    let native: &[u8] = bytemuck::cast_slice(&grey);
    let mut out = Vec::new();
    png_encoder(&mut out)
        .write_image(native, image.width, image.height, ExtendedColorType::L16)
        .map_err(|e| encode_failed("16-bit grey PNG", e))?;
    Ok(out)
}

/// Whether the PNG or JPEG at `path` holds colour (not grey), from its header alone.
pub fn read_image_has_colour(path: &Path) -> Result<bool, CoreError> {
    Ok(read_image_colour_type(path)?.has_color())
}

/// The PNG's or JPEG's colour type (channels and bits per sample), from its header alone.
pub(crate) fn read_image_colour_type(path: &Path) -> Result<image::ColorType, CoreError> {
    let decoder = image::ImageReader::open(path)
        .map_err(|e| CoreError::io(path, e))?
        .with_guessed_format()
        .map_err(|e| CoreError::io(path, e))?
        .into_decoder()
        .map_err(|e| {
            CoreError::bad_file(
                path,
                format!("not a readable image: {}", printable(e.to_string().trim())),
            )
        })?;
    Ok(image::ImageDecoder::color_type(&decoder))
}

/// 16-bit grayscale PNG of `round(z · scale)`, saturating; 0 stays 0 (invalid).
pub fn encode_depth_png(
    depth: &DepthImage,
    scale: f64,
    encoding: DepthPng,
) -> Result<Vec<u8>, CoreError> {
    let samples = depth.to_u16_be_bytes(scale);
    let mut out = Vec::new();
    write_depth_png(&mut out, (depth.width, depth.height), &samples, encoding)
        .map_err(|e| encode_failed("depth PNG", e))?;
    Ok(out)
}

/// Reads a colour image (PNG or JPEG); alpha and 16-bit depth are dropped to 8-bit RGB.
pub fn read_rgb(path: &Path) -> Result<RgbImage, CoreError> {
    Ok(rgb_of(read_decoded(path)?))
}

/// The PNG or JPEG at `path`, decoded as it is stored.
fn read_decoded(path: &Path) -> Result<image::DynamicImage, CoreError> {
    let bytes = std::fs::read(path).map_err(|e| CoreError::io(path, e))?;
    decode(&bytes).map_err(|message| CoreError::bad_file(path, message))
}

/// Width and height of a PNG or JPEG from its header, without decoding the pixels.
pub fn read_image_size(path: &Path) -> Result<(u32, u32), CoreError> {
    let (width, height) = image::ImageReader::open(path)
        .map_err(|e| CoreError::io(path, e))?
        .with_guessed_format()
        .map_err(|e| CoreError::io(path, e))?
        .into_dimensions()
        .map_err(|e| {
            CoreError::bad_file(
                path,
                format!("not a readable image: {}", printable(e.to_string().trim())),
            )
        })?;
    if width.max(height) > MAX_IMAGE_SIDE {
        return Err(CoreError::bad_file(
            path,
            format!("{width}x{height} image: over the limit of {MAX_IMAGE_SIDE} pixels a side"),
        ));
    }
    Ok((width, height))
}

/// A decoder for `bytes` that refuses images over [`MAX_IMAGE_SIDE`] pixels a side before
/// allocating their pixels.
fn limited_reader(bytes: &[u8]) -> Result<image::ImageReader<Cursor<&[u8]>>, String> {
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_IMAGE_SIDE);
    limits.max_image_height = Some(MAX_IMAGE_SIDE);
    let mut reader = image::ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| e.to_string())?;
    reader.limits(limits);
    Ok(reader)
}

fn decode(bytes: &[u8]) -> Result<image::DynamicImage, String> {
    limited_reader(bytes)?
        .decode()
        .map_err(|e| format!("not a readable image: {}", printable(e.to_string().trim())))
}

/// The width and height of an encoded image, from its header.
pub(crate) fn encoded_image_size(bytes: &[u8]) -> Result<(u32, u32), String> {
    limited_reader(bytes)?
        .into_dimensions()
        .map_err(|e| format!("not a readable image: {}", printable(e.to_string().trim())))
}

pub fn decode_rgb(bytes: &[u8]) -> Result<RgbImage, String> {
    Ok(rgb_of(decode(bytes)?))
}

/// [`read_rgb`] for a frame whose every bit must reach the 8-bit GPU frames: an image with
/// 16-bit samples is refused rather than cut to its high byte.
pub fn read_rgb8(path: &Path) -> Result<RgbImage, CoreError> {
    let image = read_decoded(path)?;
    let colour = image.color();
    if colour.bytes_per_pixel() > colour.channel_count() {
        return Err(CoreError::bad_file(
            path,
            "16-bit samples, but the GPU frames are 8-bit and would drop the low byte; expected an 8-bit image",
        ));
    }
    Ok(rgb_of(image))
}

/// A 16-bit grey PNG as 8-bit RGB (R = G = B) of each sample's high byte, as libpng's
/// `png_set_strip_16` (OpenCV's 8-bit read) makes it.
pub fn read_grey16_high_byte(path: &Path) -> Result<RgbImage, CoreError> {
    let image::DynamicImage::ImageLuma16(grey) = read_decoded(path)? else {
        return Err(CoreError::bad_file(
            path,
            "expected a 16-bit grey PNG, as the camera's first frame is",
        ));
    };
    Ok(RgbImage {
        width: grey.width(),
        height: grey.height(),
        data: grey.iter().flat_map(|&v| [(v >> 8) as u8; 3]).collect(),
    })
}

fn rgb_of(image: image::DynamicImage) -> RgbImage {
    let image = image.into_rgb8();
    RgbImage {
        width: image.width(),
        height: image.height(),
        data: image.into_raw(),
    }
}

/// An instance mask as a 16-bit grey PNG (mostly zeros: fast deflate keeps it a few kilobytes).
pub fn encode_mask_png(mask: &MaskImage) -> Result<Vec<u8>, CoreError> {
    let mut out = Vec::new();
    write_depth_png(
        &mut out,
        (mask.width, mask.height),
        &mask.to_be_bytes(),
        DepthPng::Fast,
    )
    .map_err(|e| encode_failed("mask PNG", e))?;
    Ok(out)
}

/// A 16-bit single-channel PNG as an instance mask.
pub fn decode_mask_png(path: &Path) -> Result<MaskImage, CoreError> {
    let image = decode_png_file(path, "mask")?;
    if image.color() != image::ColorType::L16 {
        return Err(CoreError::bad_file(
            path,
            "expected a 16-bit grey instance-mask PNG",
        ));
    }
    let raw = image.into_luma16();
    Ok(MaskImage {
        width: raw.width(),
        height: raw.height(),
        data: raw.into_raw(),
    })
}

/// The image in the PNG at `path`, read within the size limits; an error names the file and
/// `what` it was to hold.
fn decode_png_file(path: &Path, what: &str) -> Result<image::DynamicImage, CoreError> {
    let bytes = std::fs::read(path).map_err(|e| CoreError::io(path, e))?;
    let not_readable =
        |e: String| CoreError::bad_file(path, format!("not a readable {what} PNG: {e}"));
    limited_reader(&bytes)
        .map_err(not_readable)?
        .decode()
        .map_err(|e| not_readable(printable(e.to_string().trim())))
}

/// A 16-bit (or 8-bit) single-channel PNG as metric depth.
pub fn decode_depth_png(path: &Path, scale: f64) -> Result<DepthImage, CoreError> {
    let image = decode_png_file(path, "depth")?;
    if image.color().channel_count() != 1 {
        return Err(CoreError::bad_file(
            path,
            "expected a single-channel (grayscale) depth PNG",
        ));
    }
    let raw = image.into_luma16();
    Ok(DepthImage::from_u16(
        raw.width(),
        raw.height(),
        raw.as_raw(),
        scale,
    ))
}

/// Writes `image` in the format that `path` names by its extension (PNG or JPEG at `quality`).
pub fn write_rgb_like(path: &Path, image: &RgbImage, quality: u8) -> Result<(), CoreError> {
    let bytes = encode_rgb_like(path, image, quality)?;
    std::fs::write(path, bytes).map_err(|e| CoreError::io(path, e))
}

/// `image` encoded in the format that `path` names by its extension (PNG or JPEG at `quality`).
pub fn encode_rgb_like(path: &Path, image: &RgbImage, quality: u8) -> Result<Vec<u8>, CoreError> {
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_lowercase())
        .unwrap_or_default();
    match ext.as_str() {
        "jpg" | "jpeg" => encode_jpeg(image, quality).map_err(|e| in_file(path, e)),
        "png" => encode_png(image).map_err(|e| in_file(path, e)),
        other => Err(CoreError::bad_file(
            path,
            format!("unsupported image extension '{other}': expected .png, .jpg or .jpeg"),
        )),
    }
}

/// An encoding error, naming the file it was for.
fn in_file(path: &Path, error: CoreError) -> CoreError {
    CoreError::bad_file(path, error.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn depth_png_round_trips_within_one_step() {
        let depth = DepthImage {
            width: 3,
            height: 1,
            data: vec![0.0, 1.23456, 12.0],
        };
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("d.png");
        std::fs::write(
            &path,
            encode_depth_png(&depth, 6553.5, DepthPng::Fast).unwrap(),
        )
        .unwrap();
        let back = decode_depth_png(&path, 6553.5).unwrap();
        let raw = image::open(&path).unwrap().into_luma16();
        assert_eq!(
            raw.get_pixel(1, 0).0[0],
            (1.23456f64 * 6553.5).round() as u16,
            "stored value"
        );
        assert_eq!(back.data[0], 0.0);
        assert!((back.data[1] - 1.23456).abs() <= 0.5 / 6553.5 + 1e-6);
        assert!(
            (back.data[2] - 65535.0 / 6553.5).abs() < 1e-4,
            "saturates at 10 m"
        );
    }

    /// Depth as a camera sees a room: a tilted wall and floor (depth smooth in 1/z), a box in
    /// front with sharp edges, and a strip without depth.
    fn rendered_like_depth(width: u32, height: u32) -> DepthImage {
        let mut depth = DepthImage::new(width, height);
        for y in 0..height {
            for x in 0..width {
                let (u, v) = (x as f32 / width as f32, y as f32 / height as f32);
                let z = if v > 0.6 {
                    1.0 / (0.15 + 0.9 * (v - 0.6))
                } else if (0.3..0.55).contains(&u) && v > 0.35 {
                    1.8 - 0.4 * u
                } else if u > 0.9 {
                    0.0
                } else {
                    1.0 / (0.2 + 0.1 * u + 0.02 * v)
                };
                depth.data[(y * width + x) as usize] = z;
            }
        }
        depth
    }

    #[test]
    fn small_depth_png_holds_the_samples_of_fast_in_fewer_bytes() {
        let depth = rendered_like_depth(320, 240);
        let decoded = |png: &[u8]| image::load_from_memory(png).unwrap().into_luma16();
        let fast = encode_depth_png(&depth, 6553.5, DepthPng::Fast).unwrap();
        let small = encode_depth_png(&depth, 6553.5, DepthPng::Small).unwrap();
        let small_image = decoded(&small);
        assert_eq!(small_image.as_raw(), &depth.to_u16(6553.5), "lossless");
        assert_eq!(small_image, decoded(&fast));
        assert!(
            small.len() * 2 < fast.len(),
            "small {} bytes, fast {} bytes",
            small.len(),
            fast.len()
        );
    }

    #[test]
    fn jpeg_over_65500_pixels_a_side_is_an_error_not_a_wrapped_size() {
        for wide in [RgbImage::new(65_501, 1), RgbImage::new(65_536, 1)] {
            let error = encode_jpeg(&wide, 95).unwrap_err().to_string();
            assert!(error.contains("65500"), "{error}");
            assert!(
                error.contains(&format!("{}x1 image", wide.width)),
                "{error}"
            );
        }
        assert!(encode_jpeg(&RgbImage::new(65_500, 1), 95).is_ok());
    }

    #[test]
    fn jpeg_of_an_empty_or_inconsistent_image_is_an_error() {
        let empty = encode_jpeg(&RgbImage::new(0, 4), 95)
            .unwrap_err()
            .to_string();
        assert!(empty.contains("0x4 image"), "{empty}");
        let mut short = RgbImage::new(4, 4);
        short.data.pop();
        let error = encode_jpeg(&short, 95).unwrap_err().to_string();
        assert!(error.contains("47 bytes of RGB, expected 48"), "{error}");
    }

    #[test]
    fn png_colour_round_trips_exactly_and_jpeg_closely() {
        let mut image = RgbImage::new(16, 8);
        for (i, v) in image.data.iter_mut().enumerate() {
            *v = (i * 7 % 256) as u8;
        }
        assert_eq!(decode_rgb(&encode_png(&image).unwrap()).unwrap(), image);
        let jpeg = decode_rgb(&encode_jpeg(&image, 95).unwrap()).unwrap();
        assert_eq!((jpeg.width, jpeg.height), (16, 8));
    }

    #[test]
    fn grey_png_holds_bt601_luma_and_reads_as_grey() {
        let mut image = RgbImage::new(3, 1);
        image.data = vec![255, 0, 0, 0, 255, 0, 10, 20, 30];
        let png = encode_grey_png(&image).unwrap();
        let decoded = image::load_from_memory(&png).unwrap();
        assert_eq!(decoded.color(), image::ColorType::L8);
        // 0.299·255 = 76.2, 0.587·255 = 149.7, 0.299·10 + 0.587·20 + 0.114·30 = 18.15.
        assert_eq!(decoded.into_luma8().into_raw(), vec![76, 150, 18]);
        let dir = tempfile::tempdir().unwrap();
        let (grey, colour) = (dir.path().join("g.png"), dir.path().join("c.png"));
        std::fs::write(&grey, png).unwrap();
        std::fs::write(&colour, encode_png(&image).unwrap()).unwrap();
        assert!(!read_image_has_colour(&grey).unwrap());
        assert!(read_image_has_colour(&colour).unwrap());
    }
}
