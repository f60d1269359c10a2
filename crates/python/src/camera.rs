//! A camera from Python: 'replica', 'tum', "W,H,FX,FY,CX,CY", or a 6-sequence (w, h, fx, fy, cx,
//! cy); parsed by `rslam_core::Intrinsics::parse`, as `--camera` is.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use rslam_core::Intrinsics;

pub fn intrinsics(obj: &Bound<'_, PyAny>) -> PyResult<Intrinsics> {
    let text = if let Ok(text) = obj.extract::<String>() {
        text
    } else if let Ok(values) = obj.extract::<Vec<f64>>() {
        values
            .iter()
            .map(|v| v.to_string())
            .collect::<Vec<_>>()
            .join(",")
    } else {
        return Err(PyTypeError::new_err(
            "camera: expected 'replica', 'tum', \"W,H,FX,FY,CX,CY\" or (w, h, fx, fy, cx, cy)",
        ));
    };
    Intrinsics::parse(&text).map_err(crate::errors::core)
}

/// The camera as the tuple (width, height, fx, fy, cx, cy).
pub fn to_tuple(k: &Intrinsics) -> (u32, u32, f64, f64, f64, f64) {
    (k.width, k.height, k.fx, k.fy, k.cx, k.cy)
}
