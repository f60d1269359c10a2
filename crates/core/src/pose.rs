use glam::{DMat3, DMat4, DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// Largest |RᵀR − I| entry accepted for a rotation block read from a matrix: files printed with
/// 6 significant digits (KITTI) or from float32 stay far below it, a scaled (Sim(3)) or sheared
/// matrix does not.
const ORTHONORMAL_TOLERANCE: f64 = 1e-4;
/// Largest deviation of a 4×4 matrix's last row from `0 0 0 1`.
const LAST_ROW_TOLERANCE: f64 = 1e-6;

/// A rigid transform `world_from_camera` (camera-to-world), camera axes OpenCV (x right, y down,
/// z forward).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    pub rotation: DQuat,
    pub translation: DVec3,
}

impl Pose {
    pub const IDENTITY: Pose = Pose {
        rotation: DQuat::IDENTITY,
        translation: DVec3::ZERO,
    };

    pub fn new(rotation: DQuat, translation: DVec3) -> Self {
        Self {
            rotation: rotation.normalize(),
            translation,
        }
    }

    /// From a 4×4 rigid matrix; the rotation block is re-orthonormalised through a quaternion.
    pub fn from_mat4(m: &DMat4) -> Self {
        let r = DMat3::from_mat4(*m);
        Self::new(DQuat::from_mat3(&r), m.w_axis.truncate())
    }

    pub fn to_mat4(&self) -> DMat4 {
        DMat4::from_rotation_translation(self.rotation, self.translation)
    }

    pub fn inverse(&self) -> Pose {
        let inv = self.rotation.inverse();
        Pose {
            rotation: inv,
            translation: -(inv * self.translation),
        }
    }

    /// `self ∘ other`: applies `other` first.
    pub fn compose(&self, other: &Pose) -> Pose {
        Pose {
            rotation: (self.rotation * other.rotation).normalize(),
            translation: self.rotation * other.translation + self.translation,
        }
    }

    pub fn transform_point(&self, p: DVec3) -> DVec3 {
        self.rotation * p + self.translation
    }

    /// Row-major 4×4, as Replica's traj.txt stores it.
    pub fn to_row_major(&self) -> [f64; 16] {
        let cols = self.to_mat4().to_cols_array_2d();
        std::array::from_fn(|i| cols[i % 4][i / 4])
    }

    /// A pose from a row-major rigid matrix read from a file: `[R | t]` (12 numbers) or 4×4 (16,
    /// its last row `0 0 0 1`). Anything else, or a rotation block that is not a rotation
    /// (scaled, sheared, mirrored), is refused with the reason.
    pub fn rigid_from_rows(rows: &[f64]) -> Result<Self, String> {
        if rows.len() != 12 && rows.len() != 16 {
            return Err(format!(
                "{} numbers: expected 12 ([R | t], row-major) or 16 (4x4)",
                rows.len()
            ));
        }
        if let Some(last) = rows.get(12..16) {
            let expected = [0.0, 0.0, 0.0, 1.0];
            if last
                .iter()
                .zip(expected)
                .any(|(v, e)| (v - e).abs() > LAST_ROW_TOLERANCE)
            {
                return Err(format!(
                    "last matrix row is {last:?}; expected 0 0 0 1 (a rigid 4x4 transform)"
                ));
            }
        }
        let r = DMat3::from_cols_array(&[
            rows[0], rows[4], rows[8], rows[1], rows[5], rows[9], rows[2], rows[6], rows[10],
        ]);
        let gram = r.transpose() * r - DMat3::IDENTITY;
        let deviation = gram
            .to_cols_array()
            .iter()
            .fold(0.0_f64, |m, v| m.max(v.abs()));
        if !(deviation <= ORTHONORMAL_TOLERANCE && r.determinant() > 0.0) {
            return Err(format!(
                "rotation block is not a rotation (max |RᵀR − I| = {deviation:.2e}, det = {:.6}); \
                 expected a rigid transform",
                r.determinant()
            ));
        }
        let translation = DVec3::new(rows[3], rows[7], rows[11]);
        if !translation.is_finite() {
            return Err(format!(
                "translation {translation}: expected finite numbers"
            ));
        }
        Ok(Self::new(DQuat::from_mat3(&r), translation))
    }

    pub fn from_row_major(v: &[f64; 16]) -> Self {
        let m = DMat4::from_cols_array_2d(&std::array::from_fn(|c| {
            std::array::from_fn(|r| v[r * 4 + c])
        }));
        Self::from_mat4(&m)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const EPS: f64 = 1e-12;

    #[test]
    fn inverse_composes_to_identity() {
        let p = Pose::new(
            DQuat::from_euler(glam::EulerRot::XYZ, 0.3, -1.1, 2.0),
            DVec3::new(1.0, -2.0, 0.5),
        );
        let id = p.compose(&p.inverse());
        assert!(id.translation.length() < EPS);
        assert!(id.rotation.angle_between(DQuat::IDENTITY) < 1e-7);
    }

    #[test]
    fn row_major_round_trip_keeps_translation_in_last_column() {
        let p = Pose::new(DQuat::from_rotation_z(0.7), DVec3::new(4.0, 5.0, 6.0));
        let rm = p.to_row_major();
        assert_eq!([rm[3], rm[7], rm[11], rm[15]], [4.0, 5.0, 6.0, 1.0]);
        let back = Pose::from_row_major(&rm);
        assert!((back.translation - p.translation).length() < EPS);
        assert!(back.rotation.angle_between(p.rotation) < 1e-7);
    }
}
