"""People walking through a scene (`actors`) in rslam.render: seeded, and only ever hiding the
room (depth nearer where they pass), as `rslam render` draws them."""

import numpy as np
import pytest

import rslam

CAMERA = "64,48,40,40,31.5,23.5"


def test_walkers_hide_part_of_the_room_the_same_way_every_time():
    poses = rslam.scene_poses("office2")[:80]
    clean = rslam.render("office2", poses, camera=CAMERA)
    a = rslam.render("office2", poses, camera=CAMERA, perturb="actors:5", seed=4)
    b = rslam.render("office2", poses, camera=CAMERA, perturb="actors:5", seed=4)
    assert np.array_equal(a[1], b[1]) and np.array_equal(a[0], b[0])
    changed = a[1] != clean[1]
    assert changed.any(axis=(1, 2)).sum() >= 5, "walkers seen in a few frames"
    assert (a[1][changed & (clean[1] > 0)] < clean[1][changed & (clean[1] > 0)]).all()


def test_a_mesh_without_a_free_floor_refuses_walkers(tmp_path):
    mesh = tmp_path / "m.ply"
    mesh.write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                    "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    with pytest.raises(ValueError, match="free floor"):
        rslam.render(str(mesh), np.eye(4)[None].repeat(2, axis=0), camera=CAMERA, perturb="actors:1")
