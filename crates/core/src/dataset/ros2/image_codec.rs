//! The image encodings rslam reads from and writes back to a recorded bag: raw
//! `sensor_msgs/Image` colour (`rgb8`, `bgr8`, `mono8`) and depth (`16UC1` millimetres, `32FC1`
//! metres; REP 118), and `sensor_msgs/CompressedImage` colour (JPEG or PNG, image_transport's
//! `compressed` formats). Each message written back keeps its header and encoding.

use super::messages::{cdr_bytes, from_cdr, Bytes, CompressedImage, Header, Image};
use super::options::BagDepth;
use super::DEPTH_UNITS_PER_METRE;
use crate::dataset::codec::{decode_rgb, encode_grey_png, encode_jpeg, encode_png, luma8};
use crate::dataset::writer::JPEG_QUALITY;
use crate::{DepthImage, RgbImage};

/// How an image topic's messages hold their pixels.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ImageEncoding {
    Rgb8,
    Bgr8,
    Mono8,
    /// Depth in millimetres, 0 = no measurement.
    Depth16,
    /// Depth in metres, NaN (or ±∞) = no measurement.
    Depth32,
    /// A `CompressedImage` of colour (`grey`: of one channel) in `format`.
    Compressed {
        format: String,
        codec: Codec,
        grey: bool,
    },
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Codec {
    Jpeg,
    Png,
}

impl ImageEncoding {
    /// A raw image's `encoding`, or why rslam cannot perturb it.
    pub fn raw(encoding: &str) -> Result<Self, String> {
        match encoding {
            "rgb8" => Ok(Self::Rgb8),
            "bgr8" => Ok(Self::Bgr8),
            "mono8" | "8UC1" => Ok(Self::Mono8),
            "16UC1" => Ok(Self::Depth16),
            "32FC1" => Ok(Self::Depth32),
            other => Err(format!(
                "encoding '{}': expected rgb8, bgr8, mono8, 16UC1 or 32FC1",
                crate::printable(other)
            )),
        }
    }

    /// A compressed image's `format` (`jpeg`, `png`, or `<raw>; <codec> compressed <target>`).
    pub fn compressed(format: &str) -> Result<Self, String> {
        let lower = format.to_ascii_lowercase();
        if lower.contains("compresseddepth") {
            return Err(format!(
                "format '{}': compressedDepth images are not built yet; record depth raw",
                crate::printable(format)
            ));
        }
        let codec = if lower.contains("jpeg") || lower.contains("jpg") {
            Codec::Jpeg
        } else if lower.contains("png") {
            Codec::Png
        } else {
            return Err(format!(
                "format '{}': expected JPEG or PNG",
                crate::printable(format)
            ));
        };
        let grey = lower.starts_with("mono8") || lower.starts_with("8uc1");
        if grey && codec == Codec::Jpeg {
            return Err(format!(
                "format '{}': grey JPEG is not built yet; expected colour JPEG, or PNG",
                crate::printable(format)
            ));
        }
        Ok(Self::Compressed {
            format: format.to_string(),
            codec,
            grey,
        })
    }

    pub fn is_depth(&self) -> bool {
        matches!(self, Self::Depth16 | Self::Depth32)
    }

    /// The name a message states: a raw image's encoding, a compressed image's format.
    pub fn name(&self) -> &str {
        match self {
            Self::Rgb8 => "rgb8",
            Self::Bgr8 => "bgr8",
            Self::Mono8 => "mono8",
            Self::Depth16 => "16UC1",
            Self::Depth32 => "32FC1",
            Self::Compressed { format, .. } => format,
        }
    }
}

/// The pixels of a raw image, row by row without the padding `step` may add, after checking
/// that the message holds them.
fn rows<'a>(image: &Image<'a>, bytes_per_pixel: u32) -> Result<Vec<&'a [u8]>, String> {
    let row = image.width as usize * bytes_per_pixel as usize;
    let step = image.step as usize;
    let needed = step * image.height.saturating_sub(1) as usize + row;
    if step < row || image.data.0.len() < needed {
        return Err(format!(
            "{}x{} {} image with step {} holds {} bytes, expected {needed}",
            image.width,
            image.height,
            crate::printable(&image.encoding),
            image.step,
            image.data.0.len()
        ));
    }
    Ok((0..image.height as usize)
        .map(|y| &image.data.0[y * step..y * step + row])
        .collect())
}

/// The colour of a message in `encoding` (a raw `Image` or a `CompressedImage`), as 8-bit RGB.
pub fn decode_colour(data: &[u8], encoding: &ImageEncoding) -> Result<RgbImage, String> {
    if let ImageEncoding::Compressed { .. } = encoding {
        let message: CompressedImage = from_cdr(data)?;
        return decode_rgb(message.data.0);
    }
    let image: Image = from_cdr(data)?;
    let channels = match encoding {
        ImageEncoding::Rgb8 | ImageEncoding::Bgr8 => 3,
        ImageEncoding::Mono8 => 1,
        _ => return Err(format!("{} is not colour", encoding.name())),
    };
    let mut rgb = Vec::with_capacity(3 * image.width as usize * image.height as usize);
    for row in rows(&image, channels)? {
        match encoding {
            ImageEncoding::Rgb8 => rgb.extend_from_slice(row),
            ImageEncoding::Bgr8 => row
                .chunks_exact(3)
                .for_each(|p| rgb.extend_from_slice(&[p[2], p[1], p[0]])),
            _ => row.iter().for_each(|&v| rgb.extend_from_slice(&[v, v, v])),
        }
    }
    Ok(RgbImage {
        width: image.width,
        height: image.height,
        data: rgb,
    })
}

/// The depth of a raw `16UC1` or `32FC1` image in metres, 0 where there is no measurement.
pub fn decode_depth(data: &[u8], encoding: &ImageEncoding) -> Result<DepthImage, String> {
    let image: Image = from_cdr(data)?;
    let big_endian = image.is_bigendian != 0;
    let mut depth = Vec::with_capacity(image.width as usize * image.height as usize);
    match encoding {
        ImageEncoding::Depth16 => {
            for row in rows(&image, 2)? {
                depth.extend(row.chunks_exact(2).map(|b| {
                    let b = [b[0], b[1]];
                    let mm = if big_endian {
                        u16::from_be_bytes(b)
                    } else {
                        u16::from_le_bytes(b)
                    };
                    (mm as f64 / DEPTH_UNITS_PER_METRE) as f32
                }));
            }
        }
        ImageEncoding::Depth32 => {
            for row in rows(&image, 4)? {
                depth.extend(row.chunks_exact(4).map(|b| {
                    let b = [b[0], b[1], b[2], b[3]];
                    let z = if big_endian {
                        f32::from_be_bytes(b)
                    } else {
                        f32::from_le_bytes(b)
                    };
                    if z.is_finite() && z > 0.0 {
                        z
                    } else {
                        0.0
                    }
                }));
            }
        }
        _ => return Err(format!("{} is not depth", encoding.name())),
    }
    Ok(DepthImage {
        width: image.width,
        height: image.height,
        data: depth,
    })
}

/// `colour` as a message in `encoding` with `header`: grey encodings take its luma (as OpenCV's
/// `COLOR_RGB2GRAY`), JPEG is written at quality [`JPEG_QUALITY`].
pub fn encode_colour(
    header: Header,
    colour: &RgbImage,
    encoding: &ImageEncoding,
) -> Result<Vec<u8>, String> {
    let raw = |encoding: &str, step: u32, data: &[u8]| {
        cdr_bytes(&Image {
            header: header.clone(),
            height: colour.height,
            width: colour.width,
            encoding: encoding.into(),
            is_bigendian: 0,
            step,
            data: Bytes(data),
        })
    };
    match encoding {
        ImageEncoding::Rgb8 => raw("rgb8", 3 * colour.width, &colour.data),
        ImageEncoding::Bgr8 => {
            let bgr: Vec<u8> = colour
                .data
                .chunks_exact(3)
                .flat_map(|p| [p[2], p[1], p[0]])
                .collect();
            raw("bgr8", 3 * colour.width, &bgr)
        }
        ImageEncoding::Mono8 => {
            let grey: Vec<u8> = luma8(colour).collect();
            raw("mono8", colour.width, &grey)
        }
        ImageEncoding::Compressed {
            format,
            codec,
            grey,
        } => {
            let data = match (codec, grey) {
                (Codec::Jpeg, _) => encode_jpeg(colour, JPEG_QUALITY),
                (Codec::Png, false) => encode_png(colour),
                (Codec::Png, true) => encode_grey_png(colour),
            }
            .map_err(|e| e.to_string())?;
            cdr_bytes(&CompressedImage {
                header,
                format: format.clone(),
                data: Bytes(&data),
            })
        }
        ImageEncoding::Depth16 | ImageEncoding::Depth32 => {
            Err(format!("{} is not colour", encoding.name()))
        }
    }
}

/// `depth` (metres, 0 = none) as a message in `encoding` with `header`: whole millimetres
/// (0 for none and beyond 65.535 m) or metres (NaN for none).
pub fn encode_depth(
    header: Header,
    depth: &DepthImage,
    encoding: &ImageEncoding,
) -> Result<Vec<u8>, String> {
    let encoding = match encoding {
        ImageEncoding::Depth16 => BagDepth::Millimetres,
        ImageEncoding::Depth32 => BagDepth::Metres,
        _ => return Err(format!("{} is not depth", encoding.name())),
    };
    let data = depth_bytes(depth, encoding);
    cdr_bytes(&depth_image(header, depth, encoding, &data))
}

/// Depth in metres as `encoding`'s samples: 16UC1 whole millimetres (0: no measurement, and
/// beyond 65.535 m) or 32FC1 metres (NaN: no measurement).
pub(super) fn depth_bytes(depth: &DepthImage, encoding: BagDepth) -> Vec<u8> {
    match encoding {
        BagDepth::Millimetres => depth
            .data
            .iter()
            .flat_map(|&z| super::camera::millimetres(z).to_le_bytes())
            .collect(),
        BagDepth::Metres => depth
            .data
            .iter()
            .flat_map(|&z| if z > 0.0 { z } else { f32::NAN }.to_le_bytes())
            .collect(),
    }
}

/// The `Image` message of `depth`'s size holding `data`, its samples in `encoding`.
pub(super) fn depth_image<'a>(
    header: Header,
    depth: &DepthImage,
    encoding: BagDepth,
    data: &'a [u8],
) -> Image<'a> {
    let bytes_per_sample = match encoding {
        BagDepth::Millimetres => 2,
        BagDepth::Metres => 4,
    };
    Image {
        header,
        height: depth.height,
        width: depth.width,
        encoding: encoding.encoding().into(),
        is_bigendian: 0,
        step: bytes_per_sample * depth.width,
        data: Bytes(data),
    }
}

#[cfg(test)]
mod tests {
    use super::super::messages::Time;
    use super::*;

    fn header() -> Header {
        Header {
            stamp: Time::from_seconds(1.5),
            frame_id: "cam".into(),
        }
    }

    fn two_pixels() -> RgbImage {
        RgbImage {
            width: 2,
            height: 1,
            data: vec![10, 20, 30, 200, 100, 50],
        }
    }

    #[test]
    fn colour_comes_back_from_every_raw_encoding_it_is_written_in() {
        for encoding in [ImageEncoding::Rgb8, ImageEncoding::Bgr8] {
            let bytes = encode_colour(header(), &two_pixels(), &encoding).unwrap();
            assert_eq!(decode_colour(&bytes, &encoding).unwrap(), two_pixels());
        }
        let grey = encode_colour(header(), &two_pixels(), &ImageEncoding::Mono8).unwrap();
        let read = decode_colour(&grey, &ImageEncoding::Mono8).unwrap();
        assert_eq!(read.data, [18, 18, 18, 124, 124, 124]);
    }

    #[test]
    fn bgr8_is_blue_first_on_the_wire() {
        let bytes = encode_colour(header(), &two_pixels(), &ImageEncoding::Bgr8).unwrap();
        let image: Image = from_cdr(&bytes).unwrap();
        assert_eq!(image.data.0, [30, 20, 10, 50, 100, 200]);
        assert_eq!(image.header, header());
    }

    #[test]
    fn a_padded_row_step_is_skipped_and_a_short_image_refused() {
        let padded = Image {
            header: header(),
            height: 2,
            width: 1,
            encoding: "mono8".into(),
            is_bigendian: 0,
            step: 4,
            data: Bytes(&[7, 0, 0, 0, 9]),
        };
        let bytes = cdr_bytes(&padded).unwrap();
        let read = decode_colour(&bytes, &ImageEncoding::Mono8).unwrap();
        assert_eq!(read.data, [7, 7, 7, 9, 9, 9]);
        let short = cdr_bytes(&Image {
            data: Bytes(&[7, 0, 0, 0]),
            ..padded
        })
        .unwrap();
        let error = decode_colour(&short, &ImageEncoding::Mono8).unwrap_err();
        assert!(error.contains("holds 4 bytes, expected 5"), "{error}");
    }

    #[test]
    fn depth_keeps_its_units_and_no_measurement_in_both_encodings() {
        let depth = DepthImage {
            width: 3,
            height: 1,
            data: vec![1.234, 0.0, 70.0],
        };
        let mm = encode_depth(header(), &depth, &ImageEncoding::Depth16).unwrap();
        let read = decode_depth(&mm, &ImageEncoding::Depth16).unwrap();
        assert_eq!(read.data, [1.234, 0.0, 0.0]);
        let metres = encode_depth(header(), &depth, &ImageEncoding::Depth32).unwrap();
        let image: Image = from_cdr(&metres).unwrap();
        assert!(f32::from_le_bytes(image.data.0[4..8].try_into().unwrap()).is_nan());
        let read = decode_depth(&metres, &ImageEncoding::Depth32).unwrap();
        assert_eq!(read.data, depth.data);
    }

    #[test]
    fn big_endian_depth_is_read_by_its_flag() {
        let image = Image {
            header: header(),
            height: 1,
            width: 1,
            encoding: "16UC1".into(),
            is_bigendian: 1,
            step: 2,
            data: Bytes(&1500u16.to_be_bytes()),
        };
        let bytes = cdr_bytes(&image).unwrap();
        let read = decode_depth(&bytes, &ImageEncoding::Depth16).unwrap();
        assert_eq!(read.data, [1.5]);
    }

    #[test]
    fn compressed_colour_keeps_its_format_and_codec() {
        let encoding = ImageEncoding::compressed("rgb8; png compressed bgr8").unwrap();
        let bytes = encode_colour(header(), &two_pixels(), &encoding).unwrap();
        let message: CompressedImage = from_cdr(&bytes).unwrap();
        assert_eq!(message.format, "rgb8; png compressed bgr8");
        assert_eq!(decode_colour(&bytes, &encoding).unwrap(), two_pixels());
    }

    #[test]
    fn encodings_rslam_cannot_perturb_are_named() {
        let error = ImageEncoding::raw("bayer_rggb8").unwrap_err();
        assert!(error.contains("bayer_rggb8"), "{error}");
        let error = ImageEncoding::compressed("16UC1; compressedDepth png").unwrap_err();
        assert!(error.contains("compressedDepth"), "{error}");
        assert!(ImageEncoding::compressed("theora").is_err());
    }
}
