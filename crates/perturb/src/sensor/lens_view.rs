//! Where each pixel of a lens image looks in a wider pinhole render: the map the lens pass
//! samples through, computed once on the CPU by inverting the lens model at every pixel.

use glam::DVec2;
use rslam_core::{Distortion, Intrinsics};

/// The largest side of the wider pinhole render: wgpu's default limit on a 2-D texture.
pub const MAX_WIDE_SIDE: u32 = 8192;

/// A camera with a lens, drawn as a pinhole render plus a per-pixel map.
#[derive(Clone, Debug, PartialEq)]
pub struct LensView {
    /// The pinhole to render: the lens camera's focal lengths, its image grown (and principal
    /// point shifted) to hold every ray the lens image sees plus one texel for bilinear sampling.
    pub wide: Intrinsics,
    /// For each pixel of the lens image, row-major: the pixel of `wide` its ray passes through
    /// (pixel centres at integers).
    pub map: Vec<[f32; 2]>,
}

impl LensView {
    /// The view of `camera` through `lens`; the error says why the lens cannot be drawn.
    pub fn new(camera: &Intrinsics, lens: &Distortion) -> Result<Self, String> {
        let (w, h) = (camera.width, camera.height);
        let mut rays = Vec::with_capacity(w as usize * h as usize);
        for v in 0..h {
            for u in 0..w {
                let distorted = DVec2::new(
                    (u as f64 - camera.cx) / camera.fx,
                    (v as f64 - camera.cy) / camera.fy,
                );
                let ray = lens.undistort(distorted).ok_or_else(|| {
                    format!("pixel ({u}, {v}) of the {w}x{h} camera has no ray the model inverts to (it folds over or looks 90° or more off the axis there); expected a lens invertible over the whole image")
                })?;
                rays.push(ray);
            }
        }
        let pinhole =
            |ray: &DVec2| DVec2::new(camera.fx * ray.x + camera.cx, camera.fy * ray.y + camera.cy);
        let (low, high) = rays.iter().map(pinhole).fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(low, high), p| (low.min(p), high.max(p)),
        );
        let first = low.floor() - 1.0;
        let size = high.ceil() + 1.0 - first + 1.0;
        if size.max_element() > MAX_WIDE_SIDE as f64 {
            return Err(format!(
                "the lens sees a field a {:.0}x{:.0} pinhole render of this {w}x{h} camera would hold, more than {MAX_WIDE_SIDE} px a side; expected milder coefficients",
                size.x, size.y
            ));
        }
        let wide = Intrinsics {
            width: size.x as u32,
            height: size.y as u32,
            fx: camera.fx,
            fy: camera.fy,
            cx: camera.cx - first.x,
            cy: camera.cy - first.y,
        };
        let map = rays
            .iter()
            .map(|ray| {
                let p = pinhole(ray) - first;
                [p.x as f32, p.y as f32]
            })
            .collect();
        Ok(Self { wide, map })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const CAMERA: Intrinsics = Intrinsics {
        width: 64,
        height: 48,
        fx: 40.0,
        fy: 42.0,
        cx: 31.5,
        cy: 23.5,
    };

    /// Every map entry, pushed back through the lens model from the wide pinhole, lands on its
    /// own pixel within 1e-3 px; barrel distortion needs a wider render, inside the size limit.
    #[test]
    fn the_map_sends_each_pixel_to_its_own_ray() {
        for text in [
            "radtan(-0.3,0.08,0.001,-0.002)",
            "equidistant(0.05,-0.02,0.004,-0.001)",
        ] {
            let lens = Distortion::parse(text).unwrap();
            let view = LensView::new(&CAMERA, &lens).unwrap();
            assert!(view.wide.width > CAMERA.width && view.wide.height > CAMERA.height);
            assert_eq!(view.map.len(), (CAMERA.width * CAMERA.height) as usize);
            for (i, [x, y]) in view.map.iter().enumerate() {
                assert!(*x >= 1.0 && *y >= 1.0, "{text}: {x} {y}: no margin");
                assert!(*x <= view.wide.width as f32 - 2.0 && *y <= view.wide.height as f32 - 2.0);
                let ray = DVec2::new(
                    (*x as f64 - view.wide.cx) / view.wide.fx,
                    (*y as f64 - view.wide.cy) / view.wide.fy,
                );
                let d = lens.distort(ray);
                let (u, v) = (d.x * CAMERA.fx + CAMERA.cx, d.y * CAMERA.fy + CAMERA.cy);
                let (want_u, want_v) = (
                    (i as u32 % CAMERA.width) as f64,
                    (i as u32 / CAMERA.width) as f64,
                );
                // f32 storage of the map: a few 1e-5 px at these sizes.
                assert!(
                    (u - want_u).abs() < 1e-3 && (v - want_v).abs() < 1e-3,
                    "{text}: pixel {i} → ({u}, {v})"
                );
            }
        }
    }

    /// No distortion: the map is the identity and the render the camera itself, with its margin.
    #[test]
    fn no_distortion_is_the_identity_with_a_margin() {
        let lens = Distortion::parse("radtan(0,0,0,0)").unwrap();
        let view = LensView::new(&CAMERA, &lens).unwrap();
        assert_eq!(
            (view.wide.width, view.wide.height),
            (CAMERA.width + 2, CAMERA.height + 2)
        );
        assert_eq!(view.map[0], [1.0, 1.0]);
        assert_eq!(
            (view.wide.cx, view.wide.cy),
            (CAMERA.cx + 1.0, CAMERA.cy + 1.0)
        );
    }

    #[test]
    fn lenses_that_cannot_be_drawn_are_refused_with_the_reason() {
        let folded = Distortion::parse("radtan(-2,0,0,0)").unwrap();
        let message = LensView::new(&CAMERA, &folded).unwrap_err();
        assert!(message.contains("folds over"), "{message}");
        // An ideal fisheye whose corners look 89.9° off the axis: a pinhole would need
        // f·tan 89.9° ≈ 13 000 px from its centre to see them.
        let wide = Intrinsics {
            fx: 25.05,
            fy: 25.05,
            ..CAMERA
        };
        let fisheye = Distortion::parse("equidistant(0,0,0,0)").unwrap();
        let message = LensView::new(&wide, &fisheye).unwrap_err();
        assert!(message.contains("8192 px"), "{message}");
    }
}
