//! 3D Gaussian Splatting captures: the PLY layout of the INRIA reference implementation, which
//! gsplat, nerfstudio and Brush export too. Per Gaussian: the mean `x y z`; the degree-0
//! spherical-harmonic colour `f_dc_0..2`; the higher degrees `f_rest_*`, channel-major (all of
//! red's coefficients, then green's, then blue's); `opacity` as a logit; `scale_0..2` as natural
//! logs; the rotation `rot_0..3` as a quaternion, w first, not necessarily normalised.
//! Properties may come in any order; others (`nx ny nz`, …) are ignored.

use std::path::Path;

use crate::mesh_io::{parse_ply_vertex_columns, ply_vertex_properties, read_mesh_bytes};
use crate::CoreError;

/// Gaussians as the file stores them (activations not applied), in the file's coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SplatCloud {
    pub means: Vec<[f32; 3]>,
    /// 0 to 3.
    pub sh_degree: u32,
    /// Per Gaussian, [`SplatCloud::coefficients`] RGB coefficients, coefficient-major: the
    /// degree-0 (DC) term first.
    pub sh: Vec<[f32; 3]>,
    pub opacity_logits: Vec<f32>,
    pub log_scales: Vec<[f32; 3]>,
    /// (w, x, y, z).
    pub rotations: Vec<[f32; 4]>,
}

impl SplatCloud {
    pub fn len(&self) -> usize {
        self.means.len()
    }

    pub fn is_empty(&self) -> bool {
        self.means.is_empty()
    }

    /// Spherical-harmonic coefficients per colour channel: (degree + 1)².
    pub fn coefficients(&self) -> usize {
        ((self.sh_degree + 1) * (self.sh_degree + 1)) as usize
    }

    /// The capture with every length multiplied by `factor` (its metric scale): the means, and
    /// the scales (whose logs the file stores).
    pub fn scaled(mut self, factor: f64) -> Self {
        let f = factor as f32;
        self.means.iter_mut().flatten().for_each(|c| *c *= f);
        self.log_scales
            .iter_mut()
            .flatten()
            .for_each(|s| *s += f.ln());
        self
    }

    /// The coefficients of Gaussian `i`.
    pub fn sh_of(&self, i: usize) -> &[[f32; 3]] {
        let k = self.coefficients();
        &self.sh[i * k..(i + 1) * k]
    }
}

/// Whether a PLY header declares a Gaussian-splat capture rather than a mesh (its vertices carry
/// `f_dc_0` and `opacity`).
pub fn is_splat_ply(bytes: &[u8]) -> bool {
    ply_vertex_properties(bytes).is_ok_and(|names| {
        names.iter().any(|n| n == "f_dc_0") && names.iter().any(|n| n == "opacity")
    })
}

/// Reads a Gaussian-splat PLY; errors name the file and the property or Gaussian at fault.
pub fn read_splat_ply(path: &Path) -> Result<SplatCloud, CoreError> {
    let bytes = read_mesh_bytes(path)?;
    parse_splat_ply(&bytes).map_err(|message| CoreError::bad_file(path, message))
}

const BASE: [&str; 14] = [
    "x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2", "opacity", "scale_0", "scale_1", "scale_2",
    "rot_0", "rot_1", "rot_2", "rot_3",
];

/// Parses a Gaussian-splat PLY's bytes; the error is one line, without the file's name.
pub fn parse_splat_ply(bytes: &[u8]) -> Result<SplatCloud, String> {
    let declared = ply_vertex_properties(bytes)?;
    let rest = declared.iter().filter(|n| n.starts_with("f_rest_")).count();
    let sh_degree = match rest {
        0 => 0,
        9 => 1,
        24 => 2,
        45 => 3,
        n => {
            return Err(format!(
                "{n} 'f_rest_*' properties: expected 0, 9, 24 or 45 (spherical harmonics of degree 0 to 3)"
            ))
        }
    };
    let rest_names: Vec<String> = (0..rest).map(|i| format!("f_rest_{i}")).collect();
    let names: Vec<&str> = BASE
        .iter()
        .copied()
        .chain(rest_names.iter().map(String::as_str))
        .collect();
    let columns = parse_ply_vertex_columns(bytes, &names)?;
    if let Some((name, (i, value))) = names.iter().zip(&columns).find_map(|(name, column)| {
        let bad = column.iter().enumerate().find(|(_, v)| !v.is_finite());
        bad.map(|bad| (name, bad))
    }) {
        return Err(format!(
            "Gaussian {i}: property '{name}' = {value}: expected a finite number"
        ));
    }
    let count = columns[0].len();
    if count == 0 {
        return Err("the file holds no Gaussians".into());
    }
    let column = |name: &str| &columns[names.iter().position(|n| *n == name).expect("asked")];
    let triple = |a, b, c| -> Vec<[f32; 3]> {
        let (a, b, c) = (column(a), column(b), column(c));
        (0..count).map(|i| [a[i], b[i], c[i]]).collect()
    };
    let (w, x, y, z) = (
        column("rot_0"),
        column("rot_1"),
        column("rot_2"),
        column("rot_3"),
    );
    let rotations: Vec<[f32; 4]> = (0..count).map(|i| [w[i], x[i], y[i], z[i]]).collect();
    if let Some(i) = rotations.iter().position(|q| q.iter().all(|&c| c == 0.0)) {
        return Err(format!(
            "Gaussian {i}: properties 'rot_0..3' are all 0: expected a rotation quaternion"
        ));
    }
    let dc = triple("f_dc_0", "f_dc_1", "f_dc_2");
    let per_channel = rest / 3;
    let mut sh = Vec::with_capacity(count * (per_channel + 1));
    for (i, dc) in dc.iter().enumerate() {
        sh.push(*dc);
        for k in 0..per_channel {
            let channel = |c: usize| columns[BASE.len() + c * per_channel + k][i];
            sh.push([channel(0), channel(1), channel(2)]);
        }
    }
    Ok(SplatCloud {
        means: triple("x", "y", "z"),
        sh_degree,
        sh,
        opacity_logits: column("opacity").clone(),
        log_scales: triple("scale_0", "scale_1", "scale_2"),
        rotations,
    })
}

/// Writes `cloud` as a binary little-endian splat PLY in the INRIA layout (what the tests and
/// the fuzzer make their captures with; `read_splat_ply` reads it back exactly).
pub fn write_splat_ply(cloud: &SplatCloud) -> Vec<u8> {
    let rest = (cloud.coefficients() - 1) * 3;
    let mut names: Vec<String> = BASE[..6].iter().map(|s| s.to_string()).collect();
    names.extend((0..rest).map(|i| format!("f_rest_{i}")));
    names.extend(BASE[6..].iter().map(|s| s.to_string()));
    let mut out = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex {}\n",
        cloud.len()
    );
    for name in &names {
        out.push_str(&format!("property float {name}\n"));
    }
    out.push_str("end_header\n");
    let mut bytes = out.into_bytes();
    let per_channel = cloud.coefficients() - 1;
    for i in 0..cloud.len() {
        let sh = cloud.sh_of(i);
        let mut record: Vec<f32> = cloud.means[i].to_vec();
        record.extend(sh[0]);
        for c in 0..3 {
            record.extend(sh[1..=per_channel].iter().map(|coefficient| coefficient[c]));
        }
        record.push(cloud.opacity_logits[i]);
        record.extend(cloud.log_scales[i]);
        record.extend(cloud.rotations[i]);
        bytes.extend(record.iter().flat_map(|v| v.to_le_bytes()));
    }
    bytes
}

#[cfg(test)]
mod tests;
