//! The timeline's clock: which output frame is shown, playing at the sequence rate or stepped.

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Playback {
    pub playing: bool,
    /// Seconds of play not yet turned into whole frames.
    pending: f64,
}

impl Playback {
    /// The frame to show after `dt` seconds of play at `rate_hz`, from `index` of `len` frames;
    /// play stops on the last frame.
    pub fn advance(&mut self, dt: f64, rate_hz: f64, index: usize, len: usize) -> usize {
        if !self.playing || len == 0 {
            self.pending = 0.0;
            return index;
        }
        self.pending += dt.max(0.0) * rate_hz;
        let whole = self.pending.floor();
        self.pending -= whole;
        let next = (index + whole as usize).min(len - 1);
        if next == len - 1 {
            self.playing = false;
        }
        next
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plays_at_the_rate_and_stops_at_the_end() {
        let mut p = Playback {
            playing: true,
            ..Default::default()
        };
        assert_eq!(p.advance(0.03, 20.0, 0, 10), 0, "0.6 of a frame");
        assert_eq!(p.advance(0.03, 20.0, 0, 10), 1, "1.2 frames");
        assert_eq!(p.advance(1.0, 20.0, 1, 10), 9);
        assert!(!p.playing);
        assert_eq!(p.advance(1.0, 20.0, 9, 10), 9);
    }
}
