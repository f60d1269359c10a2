//! Image buffers handed back once a frame is written, for the next frames read back from the GPU.

use std::sync::{Mutex, MutexGuard};

use crate::{DepthImage, RgbImage};

/// Buffers of images that were handed back, reused for the next frames: a fresh buffer of a few
/// megabytes a frame costs the reading thread a page fault and the zeroing of every page (about
/// a third of the frame loop's CPU time in a whole `rslam render` on lavapipe), while a reused
/// one is already in memory. It keeps every buffer handed back; a run hands back at most as many as it has
/// frames in flight and queued for encoding at once.
#[derive(Default)]
pub struct ImagePool {
    rgb: Mutex<Vec<Vec<u8>>>,
    depth: Mutex<Vec<Vec<f32>>>,
}

impl ImagePool {
    /// [`RgbImage::from_rgba_rows`] into a buffer handed back, when there is one.
    pub fn rgb_from_rgba_rows(
        &self,
        width: u32,
        height: u32,
        rgba: &[u8],
        row_stride: usize,
    ) -> RgbImage {
        let buffer = lock(&self.rgb).pop().unwrap_or_default();
        RgbImage::from_rgba_rows_in(buffer, width, height, rgba, row_stride)
    }

    /// [`DepthImage::from_f32_rows`] into a buffer handed back, when there is one.
    pub fn depth_from_f32_rows(
        &self,
        width: u32,
        height: u32,
        bytes: &[u8],
        row_stride: usize,
    ) -> DepthImage {
        let buffer = lock(&self.depth).pop().unwrap_or_default();
        DepthImage::from_f32_rows_in(buffer, width, height, bytes, row_stride)
    }

    pub fn give_rgb(&self, image: RgbImage) {
        lock(&self.rgb).push(image.data);
    }

    pub fn give_depth(&self, image: DepthImage) {
        lock(&self.depth).push(image.data);
    }
}

/// A buffer list stays whole even if a thread panicked holding it.
fn lock<T>(buffers: &Mutex<Vec<T>>) -> MutexGuard<'_, Vec<T>> {
    buffers.lock().unwrap_or_else(|p| p.into_inner())
}

#[cfg(test)]
mod tests {
    use super::ImagePool;
    use crate::{DepthImage, RgbImage};

    /// Padded RGBA rows (stride 16 for 3 pixels) whose bytes count up from `start`.
    fn rgba_rows(start: u8) -> Vec<u8> {
        (0..32).map(|i| start.wrapping_add(i)).collect()
    }

    #[test]
    fn a_buffer_handed_back_is_reused_and_fully_overwritten() {
        let pool = ImagePool::default();
        let first = pool.rgb_from_rgba_rows(3, 2, &rgba_rows(0), 16);
        let address = first.data.as_ptr();
        pool.give_rgb(first);
        let second = pool.rgb_from_rgba_rows(3, 2, &rgba_rows(100), 16);
        assert_eq!(second.data.as_ptr(), address);
        assert_eq!(second, RgbImage::from_rgba_rows(3, 2, &rgba_rows(100), 16));
    }

    #[test]
    fn a_buffer_of_another_size_gives_an_image_of_the_size_asked_for() {
        let pool = ImagePool::default();
        pool.give_rgb(RgbImage::new(5, 5));
        let small = pool.rgb_from_rgba_rows(3, 2, &rgba_rows(7), 16);
        assert_eq!(small, RgbImage::from_rgba_rows(3, 2, &rgba_rows(7), 16));
        pool.give_rgb(RgbImage::new(1, 1));
        assert_eq!(
            pool.rgb_from_rgba_rows(3, 2, &rgba_rows(9), 16),
            RgbImage::from_rgba_rows(3, 2, &rgba_rows(9), 16)
        );
    }

    #[test]
    fn depth_buffers_are_reused_the_same_way() {
        let rows: Vec<u8> = [1.5f32, 2.0, 0.0, -1.0, 3.25, 4.0, 9.0, 9.0]
            .iter()
            .flat_map(|z| z.to_ne_bytes())
            .collect();
        let pool = ImagePool::default();
        pool.give_depth(DepthImage::new(4, 4));
        let depth = pool.depth_from_f32_rows(3, 2, &rows, 16);
        assert_eq!(depth, DepthImage::from_f32_rows(3, 2, &rows, 16));
        assert_eq!(depth.data, vec![1.5, 2.0, 0.0, 3.25, 4.0, 9.0]);
        let address = depth.data.as_ptr();
        pool.give_depth(depth);
        assert_eq!(
            pool.depth_from_f32_rows(3, 2, &rows, 16).data.as_ptr(),
            address
        );
    }
}
