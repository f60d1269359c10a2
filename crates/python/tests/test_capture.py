"""rslam.render of a Gaussian-splat capture written here in the 3DGS PLY layout."""

import math
import struct

import numpy as np
import pytest

import rslam

CAMERA = "64,48,40,40,31.5,23.5"
C0 = 0.28209479177387814
NAMES = "x y z f_dc_0 f_dc_1 f_dc_2 opacity scale_0 scale_1 scale_2 rot_0 rot_1 rot_2 rot_3".split()


def write_wall(path, distance, spacing=0.05):
    """A 4 x 4 m wall of flat grey Gaussians `distance` m down the camera's +z axis."""
    rows = []
    steps = round(4.0 / spacing)
    for i in range(steps):
        for j in range(steps):
            x, y = -2.0 + spacing * (i + 0.5), -2.0 + spacing * (j + 0.5)
            scale = [math.log(spacing), math.log(spacing), math.log(0.001)]
            rows.append([x, y, distance] + [(0.6 - 0.5) / C0] * 3 + [5.0] + scale + [1, 0, 0, 0])
    header = ("ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(rows)
              + "".join("property float %s\n" % n for n in NAMES) + "end_header\n")
    with open(path, "wb") as f:
        f.write(header.encode())
        for row in rows:
            f.write(struct.pack("<14f", *row))


def test_a_capture_renders_its_depth_and_colour(tmp_path):
    write_wall(tmp_path / "wall.ply", 2.0)
    poses = np.stack([np.eye(4)] * 2)
    rgb, depth = rslam.render(str(tmp_path / "wall.ply"), poses, camera=CAMERA)
    assert rgb.shape == (2, 48, 64, 3) and depth.shape == (2, 48, 64)
    assert np.abs(depth - 2.0).max() < 1e-4
    # Grey 0.6 in display values: 153 of 255.
    assert np.abs(rgb.astype(int) - 153).max() <= 1


def test_the_capture_scale_scales_depth_and_items_in_metres_need_it(tmp_path):
    write_wall(tmp_path / "wall.ply", 2.0)
    poses = np.eye(4)[None]
    _, depth = rslam.render(str(tmp_path / "wall.ply"), poses, camera=CAMERA, capture_scale=0.5)
    assert np.abs(depth - 1.0).max() < 1e-4
    with pytest.raises(ValueError, match="capture"):
        rslam.render(str(tmp_path / "wall.ply"), poses, camera=CAMERA, perturb="depth_noise:2")
    with pytest.raises(ValueError, match="capture_depth"):
        rslam.render(str(tmp_path / "wall.ply"), poses, camera=CAMERA, capture_depth="mean")
