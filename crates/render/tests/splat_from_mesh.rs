//! A mesh turned into a capture by the test (small, dense, nearly opaque flat Gaussians on its
//! faces): the splat render's depth against the mesh's ray-cast depth, its colour against the
//! mesh's colour, away from the cells' colour edges and the silhouettes.

mod fixtures;

use std::sync::Arc;

use glam::{DMat3, DQuat, DVec3};
use rslam_core::splat_io::SplatCloud;
use rslam_core::{Intrinsics, Pose};
use rslam_render::raycast::RayCaster;
use rslam_render::{Mesh, Rasterizer, Scene, Texture, Vertex};

const CAMERA: Intrinsics = Intrinsics {
    width: 160,
    height: 120,
    fx: 110.0,
    fy: 110.0,
    cx: 79.5,
    cy: 59.5,
};

/// An axis-aligned square cell of one colour: `axis` is its normal's axis, at `at` along it,
/// spanning [lo, hi] on the other two axes (in increasing axis order).
struct Cell {
    axis: usize,
    at: f32,
    lo: [f32; 2],
    hi: [f32; 2],
    color: [u8; 3],
}

impl Cell {
    fn point(&self, u: f32, v: f32) -> [f32; 3] {
        let mut p = [0.0; 3];
        let others = others(self.axis);
        p[self.axis] = self.at;
        p[others[0]] = u;
        p[others[1]] = v;
        p
    }
}

fn others(axis: usize) -> [usize; 2] {
    match axis {
        0 => [1, 2],
        1 => [0, 2],
        _ => [0, 1],
    }
}

/// The walls of a 4 × 3 × 2.5 m room in 0.5 m cells of alternating colours, each face its own
/// pair, and a free-standing panel in front of the far wall.
fn cells() -> Vec<Cell> {
    let min = [-2.0f32, -1.5, 0.0];
    let max = [2.0f32, 1.5, 2.5];
    let mut cells = Vec::new();
    for axis in 0..3 {
        for (side, at) in [min[axis], max[axis]].into_iter().enumerate() {
            let [a, b] = others(axis);
            let steps = |k: usize| ((max[k] - min[k]) / 0.5).round() as usize;
            for i in 0..steps(a) {
                for j in 0..steps(b) {
                    let dark = (i + j).is_multiple_of(2);
                    let base = [
                        60 + 50 * axis as u8,
                        90 + 60 * side as u8,
                        200 - 40 * axis as u8,
                    ];
                    let color = if dark { base.map(|c| c / 2) } else { base };
                    cells.push(Cell {
                        axis,
                        at,
                        lo: [min[a] + 0.5 * i as f32, min[b] + 0.5 * j as f32],
                        hi: [min[a] + 0.5 * (i + 1) as f32, min[b] + 0.5 * (j + 1) as f32],
                        color,
                    });
                }
            }
        }
    }
    cells.push(Cell {
        axis: 0,
        at: 1.0,
        lo: [-0.5, 0.3],
        hi: [0.5, 1.5],
        color: [230, 200, 40],
    });
    cells
}

fn mesh_scene(cells: &[Cell]) -> Scene {
    let mut mesh = Mesh::default();
    for cell in cells {
        let base = mesh.vertices.len() as u32;
        let corners = [
            (cell.lo[0], cell.lo[1]),
            (cell.hi[0], cell.lo[1]),
            (cell.hi[0], cell.hi[1]),
            (cell.lo[0], cell.hi[1]),
        ];
        for (u, v) in corners {
            mesh.vertices.push(Vertex {
                position: cell.point(u, v),
                uv: [0.0; 2],
                color: [cell.color[0], cell.color[1], cell.color[2], 255],
                layer: 0,
            });
        }
        mesh.indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
    }
    Scene {
        name: "cells".into(),
        mesh,
        textures: vec![Texture::white()],
        default_trajectory: None,
        lights: None,
        splats: None,
        floor: None,
    }
}

/// The Gaussians' σ along the surface, metres.
const DISC_WIDTH: f32 = 0.025;

/// Flat Gaussians every 2 cm over each cell, 2.5 cm wide and 1 mm thin, opacity 0.95, coloured
/// with the cell's colour as their degree-0 term.
fn capture(cells: &[Cell]) -> SplatCloud {
    const SPACING: f32 = 0.02;
    let mut cloud = SplatCloud::default();
    for cell in cells {
        let count = |k: usize| ((cell.hi[k] - cell.lo[k]) / SPACING).round() as usize;
        for i in 0..count(0) {
            for j in 0..count(1) {
                let u = cell.lo[0] + SPACING * (i as f32 + 0.5);
                let v = cell.lo[1] + SPACING * (j as f32 + 0.5);
                cloud.means.push(cell.point(u, v));
                let mut scale = [DISC_WIDTH.ln(); 3];
                scale[cell.axis] = 0.001f32.ln();
                cloud.log_scales.push(scale);
                cloud.rotations.push([1.0, 0.0, 0.0, 0.0]);
                cloud.opacity_logits.push((0.95f32 / 0.05).ln());
                let dc = cell.color.map(|c| (c as f32 / 255.0 - 0.5) / 0.282_094_8);
                cloud.sh.push(dc);
            }
        }
    }
    cloud
}

/// From (-1.2, y, 1.2) looking along +x, turned by `yaw` about the vertical.
fn pose(y: f64, yaw: f64) -> Pose {
    let look_x = DQuat::from_mat3(&DMat3::from_cols(
        DVec3::new(0.0, -1.0, 0.0),
        DVec3::new(0.0, 0.0, -1.0),
        DVec3::new(1.0, 0.0, 0.0),
    ));
    Pose::new(
        DQuat::from_rotation_z(yaw) * look_x,
        DVec3::new(-1.2, y, 1.2),
    )
}

#[test]
fn a_capture_of_a_mesh_renders_its_depth_and_colour() {
    let cells = cells();
    let mesh = mesh_scene(&cells);
    let oracle = RayCaster::new(&mesh);
    let capture = Scene {
        mesh: Mesh::default(),
        splats: Some(Arc::new(capture(&cells))),
        ..mesh_scene(&[])
    };
    let ctx = fixtures::gpu();
    let mut rasterizer = Rasterizer::new(ctx, &capture, CAMERA).expect("upload capture");
    // The first view faces the far wall and the panel square on; the others see every wall
    // obliquely.
    let views = [pose(0.0, 0.0), pose(0.4, 0.6), pose(-0.5, -0.9)];
    let rendered = fixtures::render_with(ctx, &mut rasterizer, &views, |_, _| {});
    for (v, (view, (rgb, depth))) in views.iter().zip(rendered).enumerate() {
        let truth = oracle.render(view, &CAMERA);
        let (w, h) = (CAMERA.width as i64, CAMERA.height as i64);
        let at = |x: i64, y: i64| (y.clamp(0, h - 1) * w + x.clamp(0, w - 1)) as usize;
        // Whether the ray-cast frame has no depth step within 5 pixels (a Gaussian's tail
        // reaches 3σ, up to 4 pixels here, past a silhouette).
        let no_step = |x: i64, y: i64| {
            let centre = truth.depth.data[at(x, y)];
            (-5..=5).all(|dy| {
                (-5..=5)
                    .all(|dx| (truth.depth.data[at(x + dx, y + dy)] - centre).abs() < 0.05 * centre)
            })
        };
        // Whether the ray-cast frame is one colour within `r` pixels.
        let one_colour = |x: i64, y: i64, r: i64| {
            let centre = at(x, y);
            (-r..=r).all(|dy| {
                (-r..=r).all(|dx| {
                    let n = at(x + dx, y + dy);
                    (0..3).all(|c| truth.rgb.data[3 * n + c] == truth.rgb.data[3 * centre + c])
                })
            })
        };
        let mut compared = 0;
        let mut square_on_errors = Vec::new();
        let mut colour_errors = Vec::new();
        for y in 0..h {
            for x in 0..w {
                let i = at(x, y);
                let expected = truth.depth.data[i];
                assert!(expected > 0.0, "the room encloses the camera");
                assert!(
                    depth.data[i] > 0.0,
                    "pixel ({x}, {y}) has no depth in a closed room"
                );
                let border = x == 0 || y == 0 || x == w - 1 || y == h - 1;
                if border || !no_step(x, y) {
                    continue;
                }
                compared += 1;
                // Where a wall is seen obliquely, a Gaussian nearer along the wall already
                // covers the pixel, and the depth comes out short by the depth the wall gains
                // over up to that Gaussian's 3σ footprint in pixels (plus the pixel itself).
                let gradient =
                    |a: usize, b: usize| 0.5 * (truth.depth.data[a] - truth.depth.data[b]).abs();
                let per_pixel = gradient(at(x + 1, y), at(x - 1, y))
                    .hypot(gradient(at(x, y + 1), at(x, y - 1)));
                let footprint = 3.0 * DISC_WIDTH * CAMERA.fx as f32 / expected + 1.0;
                let error = (depth.data[i] - expected).abs();
                assert!(
                    error <= footprint * per_pixel + 0.002,
                    "view {v}, pixel ({x}, {y}): depth {} against {expected} m, {per_pixel} m a pixel",
                    depth.data[i]
                );
                if per_pixel < 1e-3 {
                    square_on_errors.push(error);
                }
                // Colour where the cell's colour reaches past every Gaussian that can cover the
                // pixel (3σ, in pixels at this depth) and the surface is seen within 45° of
                // square on (further over, a pixel spans more of the wall than that).
                let reach = (footprint.ceil() as i64).min(12);
                if per_pixel < expected / CAMERA.fx as f32 && one_colour(x, y, reach) {
                    for c in 0..3 {
                        colour_errors.push(rgb.data[3 * i + c].abs_diff(truth.rgb.data[3 * i + c]));
                    }
                }
            }
        }
        assert!(
            compared > (w * h) as usize / 6,
            "{compared} pixels compared"
        );
        // Surfaces seen square on come out exact.
        let square_on_worst = square_on_errors.iter().copied().fold(0.0, f32::max);
        assert!(
            v > 0 || (square_on_errors.len() > 1000 && square_on_worst < 1e-4),
            "{} pixels seen square on, worst depth error {square_on_worst} m",
            square_on_errors.len()
        );
        // Nearly opaque Gaussians of one colour leave a transmittance under 1e-3: the colour
        // comes out within a rounding step.
        let colour_worst = colour_errors.iter().copied().max().unwrap_or(u8::MAX);
        assert!(
            colour_errors.len() > 3000 && colour_worst <= 1,
            "view {v}: {} channels compared, worst colour error {colour_worst} levels",
            colour_errors.len()
        );
    }
}
