//! Baked, view-independent lighting: a sky-like ambient term, Lambert from ceiling lamps with a
//! soft distance falloff, a directional term from the windows, and darkening near the floor.
//! Evaluated once per vertex, so every view of a surface sees the same colour.

use glam::Vec3;

pub struct Lighting {
    pub lamps: Vec<Vec3>,
    /// Unit direction the window light travels in (into the room).
    pub window_light: Vec3,
}

impl Lighting {
    pub fn shade(&self, p: Vec3, n: Vec3) -> f32 {
        let mut light = 0.5 + 0.1 * n.z;
        for lamp in &self.lamps {
            let d = *lamp - p;
            let dist = d.length().max(0.05);
            light += 0.45 * (n.dot(d) / dist).max(0.0) / (1.0 + (dist / 3.0).powi(2));
        }
        light += 0.15 * (-n.dot(self.window_light)).max(0.0);
        let near_floor = (p.z / 0.5).clamp(0.0, 1.0);
        (light * (0.82 + 0.18 * near_floor)).min(1.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_turned_to_a_lamp_are_brighter_and_light_stays_in_range() {
        let l = Lighting {
            lamps: vec![Vec3::new(0.0, 0.0, 2.5)],
            window_light: Vec3::X,
        };
        let p = Vec3::new(1.0, 0.0, 1.0);
        let towards = l.shade(p, Vec3::new(-1.0, 0.0, 1.0).normalize());
        let away = l.shade(p, Vec3::new(1.0, 0.0, 0.0));
        assert!(towards > away + 0.1, "{towards} vs {away}");
        for n in [Vec3::X, -Vec3::X, Vec3::Y, Vec3::Z, -Vec3::Z] {
            let s = l.shade(Vec3::new(0.2, 0.1, 0.01), n);
            assert!((0.2..=1.0).contains(&s), "{s}");
        }
    }
}
