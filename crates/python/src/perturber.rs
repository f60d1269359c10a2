//! `rslam.Perturber`: a spec's image and depth corruptions applied to frames in memory, frame by
//! frame or in batches, with the same bytes `rslam perturb` writes for the same spec, seed and
//! frame index.

use std::sync::Mutex;

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rslam_core::Intrinsics;
use rslam_perturb::{severity_on, PerturbSpec};
use rslam_pipeline::source::BufferSource;
use rslam_pipeline::{settings, FramesInMemory};

use crate::arrays::{self, colors_to_numpy, read_color, read_depth};
use crate::camera;
use crate::frames;

/// Image and depth corruptions of a spec, for frames in memory (a data loader's frames).
///
/// Args:
///     spec: a ``--perturb`` string of image and depth corruptions, e.g.
///         ``"fog:3"``, ``"motion_blur:2,depth_missing:5"``, ``"gaussian_noise:5@dynamic"``,
///         ``"depth_range:0.42-10"``. Trajectory (rot, trans) and stream (fast, misalign) items
///         act on whole sequences and are refused here; use ``rslam render`` / ``rslam perturb``.
///     seed: the one seed behind every random draw (as ``--seed``).
///     camera: optional; fixes the frame size up front ('replica', 'tum', "W,H,FX,FY,CX,CY" or
///         (w, h, fx, fy, cx, cy)) so the GPU work is built now and frames of another size are
///         refused. Without it, the corruptions are built for the first frame's size (and
///         rebuilt if a later frame has another size). ``depth_sensor`` needs it: its noise,
///         quantisation, surface angles, edge moves and projector shadow follow from the camera.
///
/// Frame ``i`` of a sequence gets exactly what ``rslam perturb --perturb SPEC --seed SEED``
/// writes for frame ``i`` (image ``i`` of a folder in name order, or frame ``i`` of a dataset),
/// whatever order frames are asked for in: randomness is keyed by (seed, name, frame index).
///
/// Example:
///     >>> p = rslam.Perturber("fog:3,depth_missing:5", seed=7)
///     >>> rgb2, depth2 = p.apply(rgb, depth, frame_index=i)   # in __getitem__(i)
#[pyclass(frozen, module = "rslam")]
pub struct Perturber {
    spec: PerturbSpec,
    seed: u64,
    camera: Option<Intrinsics>,
    built: Mutex<Option<FramesInMemory<BufferSource>>>,
}

/// Frame indices from any sequence of non-negative integers.
fn frame_numbers(obj: &Bound<'_, PyAny>) -> PyResult<Vec<usize>> {
    let values: Vec<i64> = obj
        .extract()
        .map_err(|_| PyTypeError::new_err("frame_indices: expected a sequence of integers"))?;
    values.into_iter().map(frame_number).collect()
}

fn frame_number(value: i64) -> PyResult<usize> {
    usize::try_from(value)
        .map_err(|_| PyValueError::new_err(format!("frame index {value}: expected ≥ 0")))
}

impl Perturber {
    /// Runs colour (and depth) frames as frames `numbers` of the sequence.
    fn run<'py>(
        &self,
        py: Python<'py>,
        rgb: &Bound<'py, PyAny>,
        depth: Option<&Bound<'py, PyAny>>,
        numbers: Option<Vec<usize>>,
        depth_scale: Option<f64>,
        batched: bool,
    ) -> PyResult<(Bound<'py, PyAny>, Option<Bound<'py, PyAny>>)> {
        let what = if batched { "rgbs" } else { "rgb" };
        let colors = read_color(rgb, what, batched)?;
        let depths = match depth {
            Some(d) => Some(read_depth(
                d,
                if batched { "depths" } else { "depth" },
                batched,
                depth_scale,
            )?),
            None => None,
        };
        let count = colors.frames.len();
        let numbers = numbers.unwrap_or_else(|| (0..count).collect());
        let first = &colors.frames[0].image;
        let (width, height) = (first.width, first.height);
        if let Some(k) = &self.camera {
            if (k.width, k.height) != (width, height) {
                return Err(PyValueError::new_err(format!(
                    "{what}: {width}x{height} frames given to a Perturber built for the \
                     {}x{} camera",
                    k.width, k.height
                )));
            }
        }
        let (units, depth_frames) = match depths {
            Some((units, frames)) => {
                if frames.len() != count {
                    return Err(PyValueError::new_err(format!(
                        "depths: {} depth frames for {count} colour frames",
                        frames.len()
                    )));
                }
                if let Some(d) = frames
                    .iter()
                    .find(|d| (d.width, d.height) != (width, height))
                {
                    return Err(PyValueError::new_err(format!(
                        "depth: {}x{} (WxH) does not match the colour's {width}x{height}",
                        d.width, d.height
                    )));
                }
                (Some(units), frames.into_iter().map(Some).collect())
            }
            None => (None, vec![None; count]),
        };
        let layout = colors.layout;
        let mut alphas = Vec::with_capacity(count);
        let mut inputs = Vec::with_capacity(count);
        for (color, depth) in colors.frames.into_iter().zip(depth_frames) {
            alphas.push(color.alpha);
            inputs.push((color.image, depth));
        }
        let out = py.detach(|| {
            let mut built = self.built.lock().unwrap_or_else(|p| p.into_inner());
            frames::run(
                &mut built,
                &self.spec,
                self.seed,
                inputs,
                numbers,
                self.camera,
            )
        })?;
        let mut colors_out = Vec::with_capacity(count);
        let mut depths_out = Vec::with_capacity(count);
        for (frame, alpha) in out.into_iter().zip(alphas) {
            colors_out.push((frame.color, alpha));
            depths_out.extend(frame.depth);
        }
        let depth_array = match units {
            Some(units) => Some(arrays::depth_to_numpy(py, depths_out, units, batched)?),
            None => None,
        };
        let color_array = if batched {
            colors_to_numpy(py, colors_out, layout)?
        } else {
            let (image, alpha) = colors_out
                .pop()
                .ok_or_else(|| PyValueError::new_err("rgb: no frame came back"))?;
            arrays::color_to_numpy(py, image, alpha.as_deref(), layout)?
        };
        Ok((color_array, depth_array))
    }
}

#[pymethods]
impl Perturber {
    #[new]
    #[pyo3(signature = (spec, seed = 0, camera = None))]
    fn new(
        py: Python<'_>,
        spec: &str,
        seed: u64,
        camera: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let spec = PerturbSpec::parse(spec).map_err(crate::errors::perturb)?;
        settings::check(&spec, &settings::frames_in_memory(true))
            .map_err(crate::errors::pipeline)?;
        let camera = camera.map(camera::intrinsics).transpose()?;
        let mut built = None;
        if let Some(k) = camera {
            // Build now, for the camera's size, on a blank frame (nothing is run).
            let blank = rslam_core::RgbImage::new(k.width, k.height);
            let depth =
                (!spec.depth.is_empty()).then(|| rslam_core::DepthImage::new(k.width, k.height));
            let frames = vec![(blank, depth)];
            built = Some(py.detach(|| -> Result<_, frames::RunError> {
                let ctx = crate::gpu::context().map_err(frames::RunError::NoGpu)?;
                let source = BufferSource::new(frames)?.with_camera(k)?;
                Ok(FramesInMemory::buffers(ctx, source, &spec, seed)?)
            })?);
        }
        Ok(Self {
            spec,
            seed,
            camera,
            built: Mutex::new(built),
        })
    }

    /// Perturbs one frame as frame ``frame_index`` of the sequence.
    ///
    /// Args:
    ///     rgb: uint8 HxWx3 (also HxW / HxWx1 grey, HxWx4 with alpha passed through).
    ///     depth: optional HxW depth: float32 metres (0 = no measurement), or uint16 sensor
    ///         units with ``depth_scale``. Needed when the spec has depth corruptions.
    ///     frame_index: the frame's index in its sequence; keys the randomness (and the
    ///         severity under ``@dynamic``).
    ///     depth_scale: units per metre of uint16 depth (5000 TUM, 6553.5 Replica, 1000 mm);
    ///         uint16 depth comes back quantised exactly as ``rslam perturb`` writes depth PNGs.
    ///
    /// Returns:
    ///     (rgb, depth): new arrays of the inputs' shapes and dtypes; depth is None when none
    ///     was given.
    #[pyo3(signature = (rgb, depth = None, frame_index = 0, depth_scale = None))]
    fn apply<'py>(
        &self,
        py: Python<'py>,
        rgb: &Bound<'py, PyAny>,
        depth: Option<&Bound<'py, PyAny>>,
        frame_index: i64,
        depth_scale: Option<f64>,
    ) -> PyResult<(Bound<'py, PyAny>, Option<Bound<'py, PyAny>>)> {
        let numbers = vec![frame_number(frame_index)?];
        self.run(py, rgb, depth, Some(numbers), depth_scale, false)
    }

    /// Perturbs N frames at once (one GPU pass over the batch, frames in flight overlap).
    ///
    /// Args:
    ///     rgbs: uint8 NxHxWx3 (or NxHxW, NxHxWx1, NxHxWx4).
    ///     depths: optional NxHxW float32 metres or uint16 with ``depth_scale``.
    ///     frame_indices: the frames' indices in their sequence, all different (default
    ///         0..N-1); e.g. a shuffled data loader batch ``[40, 7, 12]``.
    ///     depth_scale: as in ``apply``.
    ///
    /// Returns:
    ///     (rgbs, depths) as NxHxW… arrays; frame k equals ``apply(rgbs[k], depths[k],
    ///     frame_indices[k])``.
    #[pyo3(signature = (rgbs, depths = None, frame_indices = None, depth_scale = None))]
    fn apply_batch<'py>(
        &self,
        py: Python<'py>,
        rgbs: &Bound<'py, PyAny>,
        depths: Option<&Bound<'py, PyAny>>,
        frame_indices: Option<&Bound<'py, PyAny>>,
        depth_scale: Option<f64>,
    ) -> PyResult<(Bound<'py, PyAny>, Option<Bound<'py, PyAny>>)> {
        let numbers = frame_indices.map(frame_numbers).transpose()?;
        self.run(py, rgbs, depths, numbers, depth_scale, true)
    }

    /// The severity each corruption gives frame ``frame_index`` (0 = left clean), as the
    /// manifest of ``rslam perturb`` records it; differs from the spec's only under @dynamic.
    /// Whole severities are ints, real ones (``fog:2.5``) floats.
    fn severities<'py>(&self, py: Python<'py>, frame_index: u32) -> PyResult<Bound<'py, PyDict>> {
        let dict = PyDict::new(py);
        for item in self.spec.frame_items() {
            let severity = severity_on(&item.name, &item.level, self.seed, frame_index);
            match severity.as_whole() {
                Some(whole) => dict.set_item(&item.name, whole)?,
                None => dict.set_item(&item.name, severity.value())?,
            }
        }
        Ok(dict)
    }

    /// The spec in canonical form.
    #[getter]
    fn spec(&self) -> String {
        self.spec.to_string()
    }

    #[getter]
    fn seed(&self) -> u64 {
        self.seed
    }

    /// (width, height, fx, fy, cx, cy), or None.
    #[getter]
    fn camera(&self) -> Option<(u32, u32, f64, f64, f64, f64)> {
        self.camera.as_ref().map(camera::to_tuple)
    }

    fn __repr__(&self) -> String {
        format!("Perturber('{}', seed={})", self.spec, self.seed)
    }
}
