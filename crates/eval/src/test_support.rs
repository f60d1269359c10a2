//! Deterministic random fixtures for unit tests (SplitMix64; no global RNG).

use glam::{DMat3, DQuat, DVec3};
use rslam_core::hash::{splitmix64, splitmix64_next};
use rslam_core::RgbImage;

pub struct TestRng(u64);

impl TestRng {
    pub fn new(seed: u64) -> Self {
        Self(seed)
    }

    fn next_u64(&mut self) -> u64 {
        let out = splitmix64(self.0);
        self.0 = splitmix64_next(self.0);
        out
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [-1, 1)³.
    pub fn vec3(&mut self) -> DVec3 {
        DVec3::new(self.unit(), self.unit(), self.unit()) * 2.0 - DVec3::ONE
    }
}

pub fn random_rotation(rng: &mut TestRng) -> DMat3 {
    DMat3::from_quat(random_quat(rng))
}

pub fn random_quat(rng: &mut TestRng) -> DQuat {
    loop {
        let q = DQuat::from_xyzw(rng.vec3().x, rng.vec3().y, rng.vec3().z, rng.vec3().x);
        if q.length() > 0.1 {
            return q.normalize();
        }
    }
}

/// Uniform noise in [-amplitude, amplitude)³.
pub fn noise(rng: &mut TestRng, amplitude: f64) -> DVec3 {
    rng.vec3() * amplitude
}

/// A `w`×`h` image whose pixel (x, y) is `pixel(x, y)`.
pub fn image(w: u32, h: u32, pixel: impl Fn(u32, u32) -> [u8; 3]) -> RgbImage {
    let mut image = RgbImage::new(w, h);
    for y in 0..h {
        for x in 0..w {
            let i = ((y * w + x) * 3) as usize;
            image.data[i..i + 3].copy_from_slice(&pixel(x, y));
        }
    }
    image
}
