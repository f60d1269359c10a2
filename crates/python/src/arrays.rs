//! numpy ↔ image buffers. Colour comes in as uint8 HxWx3 (also HxW grey, HxWx1 and HxWx4 with
//! alpha) and goes back in the caller's layout; depth as float32 metres or uint16 sensor units.
//! A C-contiguous HxWx3 array is read with one copy into the buffer the GPU upload takes; results
//! are handed to numpy as the Rust buffer itself (no copy) whenever the layout is plain RGB.

use numpy::ndarray::{ArrayViewD, Axis};
use numpy::{PyArray1, PyArrayDyn, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use rslam_core::{DepthImage, MaskImage, RgbImage};

/// How the caller laid out colour, to give the result back the same way.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ColorLayout {
    /// HxW.
    Grey,
    /// HxWx1.
    GreyChannel,
    /// HxWx3.
    Rgb,
    /// HxWx4: alpha is passed through untouched.
    Rgba,
}

impl ColorLayout {
    fn channels(self) -> usize {
        match self {
            Self::Grey | Self::GreyChannel => 1,
            Self::Rgb => 3,
            Self::Rgba => 4,
        }
    }

    /// The trailing shape of one frame after H, W.
    fn tail(self) -> Option<usize> {
        match self {
            Self::Grey => None,
            Self::GreyChannel => Some(1),
            Self::Rgb => Some(3),
            Self::Rgba => Some(4),
        }
    }
}

/// One colour frame as the GPU takes it, and the alpha channel to put back (HxWx4 only).
pub struct ColorIn {
    pub image: RgbImage,
    pub alpha: Option<Vec<u8>>,
}

/// Colour frames read from one array: a frame, or a batch along the first axis.
pub struct ColorBatch {
    pub layout: ColorLayout,
    pub frames: Vec<ColorIn>,
}

fn dtype_name(array: &Bound<'_, PyUntypedArray>) -> String {
    array
        .dtype()
        .str()
        .map(|s| s.to_string())
        .unwrap_or_else(|_| "?".into())
}

/// `obj` as a numpy array of `T`, or a `TypeError` naming what it is.
fn typed<'py, T: numpy::Element>(
    obj: &Bound<'py, PyAny>,
    what: &str,
    expected: &str,
) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
    let untyped = obj.cast::<PyUntypedArray>().map_err(|_| {
        let got = obj
            .get_type()
            .name()
            .map(|n| n.to_string())
            .unwrap_or_else(|_| "?".into());
        PyTypeError::new_err(format!(
            "{what}: expected a numpy array of {expected}, got {got}"
        ))
    })?;
    obj.cast::<PyArrayDyn<T>>().cloned().map_err(|_| {
        PyTypeError::new_err(format!(
            "{what}: expected dtype {expected}, got {}",
            dtype_name(untyped)
        ))
    })
}

fn shape_text(shape: &[usize]) -> String {
    let parts: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    format!("({})", parts.join(", "))
}

/// The layout of one frame's shape (without a batch axis).
fn layout_of(shape: &[usize]) -> Option<ColorLayout> {
    match shape {
        [_, _] => Some(ColorLayout::Grey),
        [_, _, 1] => Some(ColorLayout::GreyChannel),
        [_, _, 3] => Some(ColorLayout::Rgb),
        [_, _, 4] => Some(ColorLayout::Rgba),
        _ => None,
    }
}

/// Reads uint8 colour: one frame (`batched` false) or N frames along axis 0.
pub fn read_color(obj: &Bound<'_, PyAny>, what: &str, batched: bool) -> PyResult<ColorBatch> {
    let array = typed::<u8>(obj, what, "uint8")?;
    let readonly = array.readonly();
    let view = readonly.as_array();
    let shape = view.shape().to_vec();
    let frame_shape = if batched {
        shape.get(1..).unwrap_or(&[])
    } else {
        &shape[..]
    };
    let layout = layout_of(frame_shape).filter(|_| !batched || !shape.is_empty());
    let Some(layout) = layout else {
        let expected = if batched {
            "NxHxWx3 (or NxHxW grey, NxHxWx1, NxHxWx4)"
        } else {
            "HxWx3 (or HxW grey, HxWx1, HxWx4)"
        };
        return Err(PyValueError::new_err(format!(
            "{what}: expected shape {expected}, got {}",
            shape_text(&shape)
        )));
    };
    if frame_shape[0] == 0 || frame_shape[1] == 0 {
        return Err(PyValueError::new_err(format!(
            "{what}: empty image of shape {}",
            shape_text(&shape)
        )));
    }
    let frames = if batched {
        if shape[0] == 0 {
            return Err(PyValueError::new_err(format!(
                "{what}: expected at least one frame, got shape {}",
                shape_text(&shape)
            )));
        }
        view.axis_iter(Axis(0))
            .map(|frame| color_frame(frame, layout))
            .collect()
    } else {
        vec![color_frame(view, layout)]
    };
    Ok(ColorBatch { layout, frames })
}

fn color_frame(view: ArrayViewD<'_, u8>, layout: ColorLayout) -> ColorIn {
    let (height, width) = (view.shape()[0], view.shape()[1]);
    let data: Vec<u8> = match (layout, view.as_slice()) {
        // The common case: one copy, straight into the upload buffer.
        (ColorLayout::Rgb, Some(slice)) => slice.to_vec(),
        (ColorLayout::Rgb, None) => view.iter().copied().collect(),
        (ColorLayout::Grey | ColorLayout::GreyChannel, _) => {
            view.iter().flat_map(|&v| [v, v, v]).collect()
        }
        (ColorLayout::Rgba, _) => {
            let mut data = Vec::with_capacity(height * width * 3);
            for (i, &v) in view.iter().enumerate() {
                if i % 4 != 3 {
                    data.push(v);
                }
            }
            data
        }
    };
    let alpha =
        (layout == ColorLayout::Rgba).then(|| view.iter().skip(3).step_by(4).copied().collect());
    ColorIn {
        image: RgbImage {
            width: width as u32,
            height: height as u32,
            data,
        },
        alpha,
    }
}

/// The frame's bytes in `layout`: RGB as is (moved, not copied), grey as the red channel (every
/// channel of a grey input is corrupted alike in distribution; the red one keeps the per-pixel
/// statistics of noise), RGBA with the input's alpha put back.
fn color_bytes(image: RgbImage, alpha: Option<&[u8]>, layout: ColorLayout) -> Vec<u8> {
    match layout {
        ColorLayout::Rgb => image.data,
        ColorLayout::Grey | ColorLayout::GreyChannel => {
            image.data.chunks_exact(3).map(|p| p[0]).collect()
        }
        ColorLayout::Rgba => {
            let alpha = alpha.unwrap_or(&[]);
            image
                .data
                .chunks_exact(3)
                .enumerate()
                .flat_map(|(i, p)| [p[0], p[1], p[2], alpha.get(i).copied().unwrap_or(255)])
                .collect()
        }
    }
}

fn frame_shape(layout: ColorLayout, height: usize, width: usize) -> Vec<usize> {
    let mut shape = vec![height, width];
    shape.extend(layout.tail());
    shape
}

/// One frame back to numpy in `layout`.
pub fn color_to_numpy<'py>(
    py: Python<'py>,
    image: RgbImage,
    alpha: Option<&[u8]>,
    layout: ColorLayout,
) -> PyResult<Bound<'py, PyAny>> {
    let shape = frame_shape(layout, image.height as usize, image.width as usize);
    let bytes = color_bytes(image, alpha, layout);
    Ok(PyArray1::from_vec(py, bytes).reshape(shape)?.into_any())
}

/// N frames back to numpy as one NxHx… array in `layout` (one copy per frame into it).
pub fn colors_to_numpy<'py>(
    py: Python<'py>,
    frames: Vec<(RgbImage, Option<Vec<u8>>)>,
    layout: ColorLayout,
) -> PyResult<Bound<'py, PyAny>> {
    let (height, width) = frames
        .first()
        .map_or((0, 0), |(f, _)| (f.height as usize, f.width as usize));
    let mut all = Vec::with_capacity(frames.len() * height * width * layout.channels());
    let count = frames.len();
    for (image, alpha) in frames {
        all.extend(color_bytes(image, alpha.as_deref(), layout));
    }
    let mut shape = vec![count];
    shape.extend(frame_shape(layout, height, width));
    Ok(PyArray1::from_vec(py, all).reshape(shape)?.into_any())
}

/// How the caller gave depth, to give it back the same way.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DepthUnits {
    /// float32 metres, 0 = no measurement.
    Metres,
    /// uint16 sensor units, `scale` per metre (as depth PNGs store it).
    Raw { scale: f64 },
}

/// Reads depth frames (HxW, or NxHxW when `batched`): float32 metres, or uint16 with
/// `depth_scale` units per metre.
pub fn read_depth(
    obj: &Bound<'_, PyAny>,
    what: &str,
    batched: bool,
    depth_scale: Option<f64>,
) -> PyResult<(DepthUnits, Vec<DepthImage>)> {
    let dims = if batched { "NxHxW" } else { "HxW" };
    let check_shape = |shape: &[usize]| -> PyResult<()> {
        let ok = shape.len() == if batched { 3 } else { 2 } && shape.iter().all(|&d| d > 0);
        if ok {
            Ok(())
        } else {
            Err(PyValueError::new_err(format!(
                "{what}: expected shape {dims}, got {}",
                shape_text(shape)
            )))
        }
    };
    let frames_of = |shape: &[usize]| -> Vec<(usize, usize)> {
        let (n, h, w) = if batched {
            (shape[0], shape[1], shape[2])
        } else {
            (1, shape[0], shape[1])
        };
        vec![(h, w); n]
    };
    if let Ok(array) = obj.cast::<PyArrayDyn<f32>>() {
        let readonly = array.readonly();
        let view = readonly.as_array();
        check_shape(view.shape())?;
        let sizes = frames_of(view.shape());
        let flat: Vec<f32> = match view.as_slice() {
            Some(s) => s.to_vec(),
            None => view.iter().copied().collect(),
        };
        return Ok((DepthUnits::Metres, split_depth(flat, &sizes, |v| v)));
    }
    if let Ok(array) = obj.cast::<PyArrayDyn<u16>>() {
        let scale = depth_scale
            .filter(|s| s.is_finite() && *s > 0.0)
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "{what}: uint16 depth needs depth_scale, its units per metre (5000 for TUM, \
                 6553.5 for Replica, 1000 for millimetres)"
                ))
            })?;
        let readonly = array.readonly();
        let view = readonly.as_array();
        check_shape(view.shape())?;
        let sizes = frames_of(view.shape());
        let flat: Vec<f32> = view.iter().map(|&v| (v as f64 / scale) as f32).collect();
        return Ok((DepthUnits::Raw { scale }, split_depth(flat, &sizes, |v| v)));
    }
    typed::<f32>(obj, what, "float32 (metres) or uint16 (with depth_scale)")?;
    unreachable!("typed() fails for anything but float32")
}

fn split_depth(
    flat: Vec<f32>,
    sizes: &[(usize, usize)],
    map: impl Fn(f32) -> f32,
) -> Vec<DepthImage> {
    let mut frames = Vec::with_capacity(sizes.len());
    let mut at = 0;
    for &(h, w) in sizes {
        frames.push(DepthImage {
            width: w as u32,
            height: h as u32,
            data: flat[at..at + h * w].iter().map(|&v| map(v)).collect(),
        });
        at += h * w;
    }
    frames
}

/// Depth frames back to numpy (HxW, or NxHxW when `batched`) in `units`; uint16 values are
/// quantised exactly as depth PNGs are written.
pub fn depth_to_numpy<'py>(
    py: Python<'py>,
    frames: Vec<DepthImage>,
    units: DepthUnits,
    batched: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let (height, width) = frames
        .first()
        .map_or((0, 0), |f| (f.height as usize, f.width as usize));
    let mut shape = if batched { vec![frames.len()] } else { vec![] };
    shape.extend([height, width]);
    match units {
        DepthUnits::Metres => {
            let data: Vec<f32> = if frames.len() == 1 {
                frames
                    .into_iter()
                    .next()
                    .map(|f| f.data)
                    .unwrap_or_default()
            } else {
                frames.into_iter().flat_map(|f| f.data).collect()
            };
            Ok(PyArray1::from_vec(py, data).reshape(shape)?.into_any())
        }
        DepthUnits::Raw { scale } => {
            let data: Vec<u16> = frames.iter().flat_map(|f| f.to_u16(scale)).collect();
            Ok(PyArray1::from_vec(py, data).reshape(shape)?.into_any())
        }
    }
}

/// Instance masks as one uint16 NxHxW array (0 the static scene, k walker k).
pub fn masks_to_numpy(py: Python<'_>, frames: Vec<MaskImage>) -> PyResult<Bound<'_, PyAny>> {
    let (height, width) = frames
        .first()
        .map_or((0, 0), |f| (f.height as usize, f.width as usize));
    let shape = [frames.len(), height, width];
    let data: Vec<u16> = frames.into_iter().flat_map(|f| f.data).collect();
    Ok(PyArray1::from_vec(py, data).reshape(shape)?.into_any())
}
