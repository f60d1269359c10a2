//! A capture made from a mesh scene: Gaussians sampled over its triangles by area, flat along
//! them and as wide as their mean spacing, each coloured by the surface under it (vertex colour
//! times texture, multiplied in linear light as the rasterizer does). What `rslam scene export
//! --gaussians N` writes: a capture with known geometry and ground truth, for trying captures and
//! for measuring the splat renderer against the mesh one.

use glam::{Quat, Vec2, Vec3};
use rslam_core::splat_io::SplatCloud;

use crate::scene::builtin::rng::{seed_from_name, Rng};
use crate::scene::srgb::{linear_to_srgb, srgb_to_linear};
use crate::{Scene, Texture};

/// The degree-0 spherical-harmonic basis value: colour = C0 · coefficient + 0.5.
const SH_C0: f32 = 0.282_094_8;
/// Opacity of every Gaussian, as a logit (0.95).
const OPACITY_LOGIT: f32 = 2.944_439;
/// Thickness across the surface, as a share of the width.
const FLATNESS: f32 = 0.05;

/// About `count` Gaussians over `scene`'s mesh (the same draws for the same scene name and
/// count).
pub fn capture_of_mesh(scene: &Scene, count: usize) -> SplatCloud {
    let mesh = &scene.mesh;
    let corner = |t: usize, k: usize| &mesh.vertices[mesh.indices[3 * t + k] as usize];
    let areas: Vec<f32> = (0..mesh.triangle_count())
        .map(|t| {
            let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(corner(t, k).position));
            0.5 * (b - a).cross(c - a).length()
        })
        .collect();
    let total: f32 = areas.iter().sum();
    let width = (total / count.max(1) as f32).sqrt();
    let mut random = Rng::new(seed_from_name(&scene.name)).fork("capture");
    let mut cloud = SplatCloud::default();
    let mut owed = 0.0;
    for (t, area) in areas.iter().enumerate() {
        owed += area / total * count as f32;
        let [a, b, c] = [0, 1, 2].map(|k| Vec3::from(corner(t, k).position));
        let normal = (b - a).cross(c - a).normalize_or_zero();
        let rotation = Quat::from_rotation_arc(Vec3::Z, normal);
        let [ta, tb, tc] = [0, 1, 2].map(|k| Vec2::from(corner(t, k).uv));
        let texture = &scene.textures[corner(t, 0).layer as usize];
        while owed >= 1.0 {
            owed -= 1.0;
            let (mut u, mut v) = (random.f32(), random.f32());
            if u + v > 1.0 {
                (u, v) = (1.0 - u, 1.0 - v);
            }
            let w = 1.0 - u - v;
            cloud.means.push((w * a + u * b + v * c).to_array());
            cloud
                .log_scales
                .push([width.ln(), width.ln(), (FLATNESS * width).ln()]);
            cloud
                .rotations
                .push([rotation.w, rotation.x, rotation.y, rotation.z]);
            cloud.opacity_logits.push(OPACITY_LOGIT);
            let texel = texel(texture, w * ta + u * tb + v * tc);
            let vertex = [w, u, v]
                .iter()
                .zip(0..3)
                .fold([0.0f32; 3], |sum, (weight, k)| {
                    let colour = corner(t, k).color;
                    std::array::from_fn(|i| sum[i] + weight * srgb_to_linear(colour[i]))
                });
            let display =
                |i: usize| linear_to_srgb(vertex[i] * srgb_to_linear(texel[i])) as f32 / 255.0;
            cloud.sh.push([0, 1, 2].map(|i| (display(i) - 0.5) / SH_C0));
        }
    }
    cloud
}

/// The texel at `uv` (repeating; v = 0 at the top row), nearest.
fn texel(texture: &Texture, uv: Vec2) -> [u8; 3] {
    let (w, h) = (texture.width as f32, texture.height as f32);
    let x = ((uv.x.rem_euclid(1.0) * w) as usize).min(texture.width as usize - 1);
    let y = ((uv.y.rem_euclid(1.0) * h) as usize).min(texture.height as usize - 1);
    let at = 4 * (y * texture.width as usize + x);
    [texture.rgba[at], texture.rgba[at + 1], texture.rgba[at + 2]]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Mesh, Vertex};

    /// A 2 × 1 m quad at z = 3, its texture red on the left half and blue on the right, under a
    /// grey vertex colour.
    fn quad() -> Scene {
        let v = |x: f32, y: f32| Vertex {
            position: [x, y, 3.0],
            uv: [x / 2.0, y],
            color: [128, 128, 128, 255],
            layer: 1,
        };
        let texture = Texture {
            width: 2,
            height: 1,
            rgba: vec![255, 0, 0, 255, 0, 0, 255, 255],
        };
        Scene {
            name: "quad".into(),
            mesh: Mesh {
                vertices: vec![v(0.0, 0.0), v(2.0, 0.0), v(2.0, 1.0), v(0.0, 1.0)],
                indices: vec![0, 1, 2, 0, 2, 3],
            },
            textures: vec![Texture::white(), texture],
            default_trajectory: None,
            lights: None,
            splats: None,
            floor: None,
        }
    }

    #[test]
    fn gaussians_lie_on_the_surface_coloured_by_it() {
        let cloud = capture_of_mesh(&quad(), 1000);
        assert!((999..=1000).contains(&cloud.len()), "{}", cloud.len());
        // Spaced to cover 2 m² with 1000 discs: √(2/1000) m wide, 5 % of that thick.
        let width = (2.0f32 / 1000.0).sqrt();
        for (i, mean) in cloud.means.iter().enumerate() {
            let inside =
                (-1e-5..=2.00001).contains(&mean[0]) && (-1e-5..=1.00001).contains(&mean[1]);
            assert!((mean[2] - 3.0).abs() < 1e-5 && inside, "{mean:?}");
            assert!((cloud.log_scales[i][0] - width.ln()).abs() < 1e-5);
            // Grey 128 times red (or blue) in linear light, shown: 128 in the one channel.
            let shown = cloud.sh[i].map(|c| ((c * SH_C0 + 0.5) * 255.0).round() as u8);
            let expected = if mean[0] < 1.0 {
                [128, 0, 0]
            } else {
                [0, 0, 128]
            };
            assert_eq!(shown, expected, "Gaussian at {mean:?}");
        }
        // Flat along the quad: the disc's thin axis is the quad's normal.
        let [w, x, y, z] = cloud.rotations[0];
        let thin = Quat::from_xyzw(x, y, z, w) * Vec3::Z;
        assert!(thin.abs().abs_diff_eq(Vec3::Z, 1e-5), "{thin}");
        assert_eq!(capture_of_mesh(&quad(), 1000), cloud, "the same draws");
    }
}
