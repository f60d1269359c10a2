"""People walking through a scene (`actors`) and things moved (`objects`) in rslam.render:
seeded, and only ever hiding the room (depth nearer where they pass, and only where their
instance masks say), as `rslam render` draws them; the masks `rslam render` writes, read by
Pillow and rosbags."""

import json

import numpy as np
import pytest

import rslam

CAMERA = "64,48,40,40,31.5,23.5"


def test_walkers_hide_part_of_the_room_the_same_way_every_time():
    poses = rslam.scene_poses("office2")[:80]
    clean = rslam.render("office2", poses, camera=CAMERA)
    a = rslam.render("office2", poses, camera=CAMERA, perturb="actors:5", seed=4, masks=True)
    b = rslam.render("office2", poses, camera=CAMERA, perturb="actors:5", seed=4)
    assert np.array_equal(a[1], b[1]) and np.array_equal(a[0], b[0])
    mask = a[2]
    assert mask.dtype == np.uint16 and mask.shape == a[1].shape
    changed = a[1] != clean[1]
    assert changed.any(axis=(1, 2)).sum() >= 5, "walkers seen in a few frames"
    assert not (changed & (mask == 0)).any(), "depth changed only where a mask says a walker is"
    assert (a[1][changed & (clean[1] > 0)] < clean[1][changed & (clean[1] > 0)]).all()
    assert set(np.unique(mask)) == {0, 1, 2, 3}
    assert not rslam.render("office2", poses[:2], camera=CAMERA, masks=True)[2].any()


def test_objects_move_the_door_and_chairs_where_their_masks_say():
    poses = rslam.scene_poses("office2")[:300]
    clean = rslam.render("office2", poses, camera=CAMERA)
    rgb, depth, mask = rslam.render("office2", poses, camera=CAMERA, perturb="objects:3", seed=2,
                                    masks=True)
    assert set(np.unique(mask)) == {0, 1, 2}, "the door and a chair"
    changed = depth != clean[1]
    nearer = changed & (depth < clean[1])
    assert not (nearer & (mask == 0)).any(), "only an object comes nearer, where its mask says"
    # Outside the masks depth changes only where the open door stood: farther, and little of it.
    gone = changed & (mask == 0)
    assert (depth[gone] > clean[1][gone]).all() and gone.mean() < 0.01
    assert (nearer & (mask == 2)).any(), "the chair hides part of the room"


def test_a_mesh_without_a_free_floor_refuses_walkers(tmp_path):
    mesh = tmp_path / "m.ply"
    mesh.write_text("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
                    "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")
    with pytest.raises(ValueError, match="free floor"):
        rslam.render(str(mesh), np.eye(4)[None].repeat(2, axis=0), camera=CAMERA, perturb="actors:1")


def test_masks_read_by_pillow_and_rosbags_say_where_the_walkers_are(rslam_bin, tmp_path):
    """The same job as a TUM dataset and as a ROS 2 bag: Pillow reads each 16-bit mask PNG,
    `rosbags` each mono16 mask message, stamped as its colour frame; they hold the same ids, and
    where an id is set the depth is the walker's (nearer than the TUM dataset's clean depth)."""
    from PIL import Image
    from rosbags.rosbag2 import Reader
    from rosbags.typesys import Stores, get_typestore
    from conftest import run_cli

    common = ["render", "--scene", "office2", "--camera", CAMERA, "--frames", "60", "--seed", "4"]
    run_cli(rslam_bin, *common, "--format", "tum", "--out", tmp_path / "clean")
    for fmt in ["tum", "ros2"]:
        run_cli(rslam_bin, *common, "--perturb", "actors:5", "--format", fmt, "--out", tmp_path / fmt)
    listed = [line.split() for line in (tmp_path / "tum/mask.txt").read_text().splitlines()
              if not line.startswith("#")]
    masks = []
    for stamp, name in listed:
        image = Image.open(tmp_path / "tum" / name)
        assert image.mode in ("I;16", "I;16B", "I")
        masks.append((stamp, np.asarray(image).astype(np.uint16)))
    types = get_typestore(Stores.ROS2_HUMBLE)
    with Reader(tmp_path / "ros2") as reader:
        wanted = [c for c in reader.connections if c.topic == "/camera/mask/image_raw"]
        messages = [types.deserialize_cdr(raw, c.msgtype) for c, _, raw in reader.messages(connections=wanted)]
    assert len(messages) == len(masks) == 60
    seen = set()
    for (stamp, mask), message in zip(masks, messages):
        assert message.encoding == "mono16"
        t = message.header.stamp.sec + message.header.stamp.nanosec * 1e-9
        assert f"{t:.6f}" == stamp
        dtype = ">u2" if message.is_bigendian else "<u2"
        from_bag = np.frombuffer(bytes(message.data), dtype).reshape(message.height, message.width)
        assert np.array_equal(from_bag, mask)
        seen.update(np.unique(mask).tolist())
        clean = np.asarray(Image.open(tmp_path / f"clean/depth/{stamp}.png")).astype(np.int64)
        walkers = np.asarray(Image.open(tmp_path / f"tum/depth/{stamp}.png")).astype(np.int64)
        on = (mask > 0) & (clean > 0)
        assert (walkers[on] <= clean[on]).all()
        assert (walkers[mask == 0] == clean[mask == 0]).all()
    assert seen == {0, 1, 2, 3}, f"ids seen {seen}"
    fractions = [json.loads((tmp_path / fmt / "rslam.json").read_text())["extra"]["masks"]["dynamic_fraction"]
                 for fmt in ["tum", "ros2"]]
    assert fractions[0] == fractions[1]
    # The manifest rounds to 6 decimals, a half away from zero (Python's round() keeps it even).
    assert fractions[0] == pytest.approx([float((m > 0).mean()) for _, m in masks], abs=5e-7 + 1e-12)


BOX_PLY = """ply
format ascii 1.0
element vertex 8
property float x
property float y
property float z
property uchar red
property uchar green
property uchar blue
element face 12
property list uchar int vertex_indices
end_header
-0.18 -0.18 0 200 80 40
0.18 -0.18 0 200 80 40
0.18 0.18 0 200 80 40
-0.18 0.18 0 200 80 40
-0.18 -0.18 0.8 200 80 40
0.18 -0.18 0.8 200 80 40
0.18 0.18 0.8 200 80 40
-0.18 0.18 0.8 200 80 40
3 0 2 1
3 0 3 2
3 4 5 6
3 4 6 7
3 0 1 5
3 0 5 4
3 1 2 6
3 1 6 5
3 2 3 7
3 2 7 6
3 3 0 4
3 3 4 7
"""


def test_a_users_actor_is_drawn_where_its_mask_says_and_a_bad_path_is_refused(rslam_bin, tmp_path):
    """rslam.render(..., actors=[(mesh, path)]) as `rslam render --actor`: a box carried along a
    walker's path (from a render's manifest) hides the room only where its mask (id 1) is; a path
    out of the room is refused naming the file and lines."""
    from conftest import run_cli

    run_cli(rslam_bin, "render", "--scene", "office1", "--camera", CAMERA, "--frames", "120",
            "--seed", "3", "--perturb", "actors:1/1/1.2", "--format", "tum", "--out", tmp_path / "walkers")
    walker = [frame[0] for frame in json.loads((tmp_path / "walkers/rslam.json").read_text())["extra"]["actors"]["frames"]]
    path = tmp_path / "path.txt"
    path.write_text("".join(f"{j * 0.05:.6f} {x} {y} 0 0 0 0 1\n" for j, (x, y, *_) in enumerate(walker)))
    mesh = tmp_path / "box.ply"
    mesh.write_text(BOX_PLY)
    poses = rslam.scene_poses("office1")[:120]
    clean = rslam.render("office1", poses, camera=CAMERA)
    rgb, depth, mask = rslam.render("office1", poses, camera=CAMERA, actors=[(str(mesh), str(path))], masks=True)
    assert set(np.unique(mask)) == {0, 1}
    assert np.array_equal(depth[mask == 0], clean[1][mask == 0])
    on = (mask == 1) & (clean[1] > 0)
    assert (depth[on] <= clean[1][on]).all() and (depth[on] < clean[1][on]).mean() > 0.95
    far = tmp_path / "far.txt"
    far.write_text("0 20 20 0 0 0 0 1\n")
    with pytest.raises(ValueError, match="far.txt: line 1"):
        rslam.render("office1", poses[:4], camera=CAMERA, actors=[(str(mesh), str(far))])
