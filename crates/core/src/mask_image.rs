/// Which object each pixel sees: 0 the static scene, k > 0 the k-th actor (walker k − 1), as
/// instance-mask PNGs store it (16-bit grey).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MaskImage {
    pub width: u32,
    pub height: u32,
    pub data: Vec<u16>,
}

impl MaskImage {
    pub fn new(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            data: vec![0; width as usize * height as usize],
        }
    }

    pub fn at(&self, x: u32, y: u32) -> u16 {
        self.data[y as usize * self.width as usize + x as usize]
    }

    /// From native-endian u32 ids in rows `row_stride` bytes apart (a padded GPU readback of an
    /// `R32Uint` texture); ids past `u16::MAX` saturate (a job has at most a few actors).
    pub fn from_u32_rows(width: u32, height: u32, bytes: &[u8], row_stride: usize) -> Self {
        let mut data = Vec::with_capacity(width as usize * height as usize);
        for row in bytes.chunks(row_stride).take(height as usize) {
            let ids: &[u32] = bytemuck::cast_slice(&row[..width as usize * 4]);
            data.extend(ids.iter().map(|&id| id.min(u32::from(u16::MAX)) as u16));
        }
        Self {
            width,
            height,
            data,
        }
    }

    /// The share of pixels that see an actor.
    pub fn dynamic_fraction(&self) -> f64 {
        if self.data.is_empty() {
            return 0.0;
        }
        let moving = self.data.iter().filter(|&&id| id != 0).count();
        moving as f64 / self.data.len() as f64
    }

    /// The ids as PNG stores them: two big-endian bytes per pixel.
    pub fn to_be_bytes(&self) -> Vec<u8> {
        self.data.iter().flat_map(|id| id.to_be_bytes()).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::MaskImage;

    #[test]
    fn padded_rows_unpack_and_ids_saturate() {
        let row_stride = 16;
        let mut bytes = vec![0xAAu8; row_stride * 2];
        for (y, ids) in [[0u32, 3, 70_000], [1, 0, 2]].iter().enumerate() {
            for (x, id) in ids.iter().enumerate() {
                let at = y * row_stride + x * 4;
                bytes[at..at + 4].copy_from_slice(&id.to_ne_bytes());
            }
        }
        let mask = MaskImage::from_u32_rows(3, 2, &bytes, row_stride);
        assert_eq!(mask.data, vec![0, 3, u16::MAX, 1, 0, 2]);
        assert!((mask.dynamic_fraction() - 4.0 / 6.0).abs() < 1e-12);
        assert_eq!(&mask.to_be_bytes()[2..4], &[0, 3]);
    }
}
