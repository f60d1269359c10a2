//! Each frame's dynamic fraction (the share of its pixels an actor covers), kept as its instance
//! mask is written and recorded in the manifest (`extra.masks`) when the dataset is finished.

use std::collections::HashMap;
use std::hash::Hash;
use std::path::Path;
use std::sync::Mutex;

use crate::dataset::decode_mask_png;
use crate::{CoreError, MaskImage};

/// What a mask's ids mean, as the manifest says it.
pub const MASK_IDS: &str =
    "0 the static scene, k actor k: the walkers (extra.actors.walkers), then the user's actors (extra.actors.user), then the objects (extra.actors.objects), in that order from 1";

/// The fractions of the masks written, by frame key.
pub(crate) struct DynamicFractions<K> {
    written: Mutex<HashMap<K, f64>>,
}

impl<K: Eq + Hash> Default for DynamicFractions<K> {
    fn default() -> Self {
        Self {
            written: Mutex::default(),
        }
    }
}

impl<K: Eq + Hash> DynamicFractions<K> {
    pub fn record(&self, key: K, mask: &MaskImage) {
        let mut written = self.written.lock().unwrap_or_else(|p| p.into_inner());
        written.insert(key, mask.dynamic_fraction());
    }

    /// The fraction of frame `key`, rounded to 1e-6: as its mask was written, or for a frame an
    /// interrupted run wrote, read back from its file at `path`.
    pub fn of(&self, key: &K, path: &Path) -> Result<f64, CoreError> {
        let written = self.written.lock().unwrap_or_else(|p| p.into_inner());
        let fraction = match written.get(key) {
            Some(&fraction) => fraction,
            None => decode_mask_png(path)?.dynamic_fraction(),
        };
        Ok(rounded(fraction))
    }
}

/// A dynamic fraction as the manifest records it, to 1e-6.
pub fn rounded(fraction: f64) -> f64 {
    (fraction * 1e6).round() / 1e6
}
