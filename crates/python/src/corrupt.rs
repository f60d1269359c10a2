//! `rslam.corrupt` and `rslam.get_corruption_names`: the `imagecorruptions` API (same signature,
//! names, severities and subsets) on rslam's GPU corruptions.

use std::collections::HashMap;
use std::sync::Mutex;

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use rslam_perturb::PerturbSpec;
use rslam_pipeline::source::BufferSource;
use rslam_pipeline::FramesInMemory;

use crate::arrays::{color_to_numpy, read_color};
use crate::frames;

/// `imagecorruptions`' `corruption_tuple`, in its order: `corruption_number` indexes it, and its
/// slices are the subsets of `get_corruption_names` (imagecorruptions 1.1.2, `__init__.py`).
pub const IMAGECORRUPTIONS_ORDER: [&str; 19] = [
    "gaussian_noise",
    "shot_noise",
    "impulse_noise",
    "defocus_blur",
    "glass_blur",
    "motion_blur",
    "zoom_blur",
    "snow",
    "frost",
    "fog",
    "brightness",
    "contrast",
    "elastic_transform",
    "pixelate",
    "jpeg_compression",
    "speckle_noise",
    "gaussian_blur",
    "spatter",
    "saturate",
];

/// Subset name → range of [`IMAGECORRUPTIONS_ORDER`], as `imagecorruptions` slices it.
const SUBSETS: [(&str, std::ops::Range<usize>); 7] = [
    ("common", 0..15),
    ("validation", 15..19),
    ("all", 0..19),
    ("noise", 0..3),
    ("blur", 3..7),
    ("weather", 7..11),
    ("digital", 11..15),
];

/// Perturbations built for one (name, severity, width, height, seed), kept for later calls.
type Key = (&'static str, u8, u32, u32, u64);

/// At most this many sets of built corruptions are kept; past it the cache starts over.
const CACHE_ENTRIES: usize = 16;

static BUILT: Mutex<Option<HashMap<Key, FramesInMemory<BufferSource>>>> = Mutex::new(None);

/// Names of the corruptions in `subset`, as `imagecorruptions.get_corruption_names`.
///
/// subset: 'common' (the 15 ImageNet-C corruptions), 'validation' (the 4 extra ones), 'all',
/// 'noise', 'blur', 'weather' or 'digital'.
#[pyfunction]
#[pyo3(signature = (subset = "common"))]
pub fn get_corruption_names(subset: &str) -> PyResult<Vec<&'static str>> {
    SUBSETS
        .iter()
        .find(|(name, _)| *name == subset)
        .map(|(_, range)| IMAGECORRUPTIONS_ORDER[range.clone()].to_vec())
        .ok_or_else(|| {
            let valid: Vec<&str> = SUBSETS.iter().map(|(n, _)| *n).collect();
            PyValueError::new_err(format!(
                "unknown subset '{subset}'; valid: {}",
                valid.join(", ")
            ))
        })
}

fn valid_names() -> String {
    IMAGECORRUPTIONS_ORDER.join(", ")
}

/// The corruption `corrupt` was asked for, by name or by number.
fn resolve_name(name: Option<&str>, number: i64) -> PyResult<&'static str> {
    if let Some(name) = name {
        return IMAGECORRUPTIONS_ORDER
            .iter()
            .find(|n| **n == name)
            .copied()
            .ok_or_else(|| {
                PyValueError::new_err(format!(
                    "unknown corruption '{name}'; valid: {}",
                    valid_names()
                ))
            });
    }
    if number == -1 {
        return Err(PyValueError::new_err(
            "either corruption_name or corruption_number must be passed",
        ));
    }
    usize::try_from(number)
        .ok()
        .and_then(|i| IMAGECORRUPTIONS_ORDER.get(i).copied())
        .ok_or_else(|| {
            PyValueError::new_err(format!(
                "corruption_number {number}: expected 0-18, an index into \
                 get_corruption_names('all'): {}",
                valid_names()
            ))
        })
}

/// A severity 1..=5 from any Python integer (numpy integers included).
pub fn severity(value: &Bound<'_, PyAny>) -> PyResult<u8> {
    let number: i64 = value.extract().map_err(|_| {
        let got = value.repr().map(|r| r.to_string()).unwrap_or_default();
        PyTypeError::new_err(format!("severity must be an integer 1-5, got {got}"))
    })?;
    u8::try_from(number)
        .ok()
        .filter(|s| (1..=5).contains(s))
        .ok_or_else(|| {
            PyValueError::new_err(format!("severity must be an integer 1-5, got {number}"))
        })
}

/// Corrupts `image` like ``imagecorruptions.corrupt``, on the GPU.
///
/// A drop-in replacement: the same arguments in the same order, the same 19 corruption names
/// (``get_corruption_names('all')``) and severities 1-5, with rslam's GPU implementations
/// (ImageNet-C parameters; see ``rslam list`` for each one's numbers).
///
/// Args:
///     image: numpy uint8 array, HxWx3 RGB. Also HxW or HxWx1 grey (corrupted as RGB with
///         equal channels; the red channel comes back, in the input's shape) and HxWx4 RGBA
///         (alpha passed through).
///     severity: 1 (mild) to 5 (strong).
///     corruption_name: e.g. 'fog'; see ``get_corruption_names``.
///     corruption_number: index into ``get_corruption_names('all')`` when no name is given.
///     seed: randomness of the stochastic corruptions (noises, motion angle, snow, frost, ...).
///         The same image, name, severity and seed give the same bytes every time, which
///         imagecorruptions does not; pass a different seed per image for independent draws.
///         Equals ``rslam perturb --seed SEED`` on frame 0, and ``Perturber(f"{name}:{severity}",
///         seed).apply(image)``.
///
/// Returns:
///     numpy uint8 array of the input's shape.
///
/// Raises:
///     TypeError: image is not a uint8 numpy array, or severity is not an integer.
///     ValueError: wrong shape, unknown name or number, severity outside 1-5.
///     RuntimeError: no GPU adapter (not even lavapipe) or a GPU failure.
///
/// The GPU context is created on the first call (one per process); the GIL is released while
/// the GPU works; corruptions are built once per (name, severity, size, seed) and reused.
#[pyfunction]
#[pyo3(
    signature = (image, severity = None, corruption_name = None, corruption_number = -1, seed = 0),
    text_signature = "(image, severity=1, corruption_name=None, corruption_number=-1, seed=0)"
)]
pub fn corrupt<'py>(
    py: Python<'py>,
    image: &Bound<'py, PyAny>,
    severity: Option<&Bound<'py, PyAny>>,
    corruption_name: Option<&str>,
    corruption_number: i64,
    seed: u64,
) -> PyResult<Bound<'py, PyAny>> {
    let batch = read_color(image, "image", false)?;
    let severity = match severity {
        Some(s) => self::severity(s)?,
        None => 1,
    };
    let name = resolve_name(corruption_name, corruption_number)?;
    let spec = PerturbSpec::parse(&format!("{name}:{severity}")).map_err(crate::errors::perturb)?;
    let layout = batch.layout;
    let mut inputs = batch.frames;
    let input = inputs
        .pop()
        .ok_or_else(|| PyValueError::new_err("image: no frame"))?;
    let (width, height) = (input.image.width, input.image.height);
    let alpha = input.alpha;
    let key: Key = (name, severity, width, height, seed);
    let frames = py.detach(|| {
        let mut cache = BUILT.lock().unwrap_or_else(|p| p.into_inner());
        let cache = cache.get_or_insert_with(HashMap::new);
        if !cache.contains_key(&key) && cache.len() >= CACHE_ENTRIES {
            cache.clear();
        }
        let mut slot = cache.remove(&key);
        let result = frames::run(
            &mut slot,
            &spec,
            seed,
            vec![(input.image, None)],
            vec![0],
            None,
        );
        if let Some(built) = slot {
            cache.insert(key, built);
        }
        result
    })?;
    let frame = frames
        .into_iter()
        .next()
        .ok_or_else(|| PyValueError::new_err("image: no frame came back"))?;
    color_to_numpy(py, frame.color, alpha.as_deref(), layout)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_imagecorruptions_name_is_an_image_corruption_of_the_catalogue() {
        for name in IMAGECORRUPTIONS_ORDER {
            let entry = rslam_perturb::find(name).unwrap_or_else(|| panic!("{name} missing"));
            assert_eq!(entry.group, rslam_perturb::Group::Image, "{name}");
        }
    }

    #[test]
    fn subsets_slice_the_order_like_imagecorruptions() {
        let names = |subset| {
            SUBSETS
                .iter()
                .find(|(n, _)| *n == subset)
                .unwrap()
                .1
                .clone()
        };
        assert_eq!(
            IMAGECORRUPTIONS_ORDER[names("weather")],
            ["snow", "frost", "fog", "brightness"]
        );
        assert_eq!(IMAGECORRUPTIONS_ORDER[names("digital")].len(), 4);
        let common = names("common");
        let covered: usize = ["noise", "blur", "weather", "digital"]
            .iter()
            .map(|s| names(s).len())
            .sum();
        assert_eq!(covered, common.len());
        assert_eq!(names("validation").end, IMAGECORRUPTIONS_ORDER.len());
    }
}
