"""Depth that is not registered to a colour topic (its own lens, as a RealSense's raw
`/camera/depth/image_rect_raw`) or that comes at another rate is a camera of its own when
`rslam perturb` reads a bag: depth items change it in its own encoding and stamps, image items
change the colour, and each topic's CameraInfo is copied; a bag with only depth refuses image
items in one line."""

import json

import numpy as np

from conftest import run_cli
from test_perturb_bag import (FRAME_NS, FRAMES, HEIGHT, START_NS, WIDTH, camera_info, deserialized, header, image,
                              raw_messages, refusal, rng_colour, rng_depth, stamp_ns, write_bag)

COLOUR = "/camera/color/image_raw"
RAW_DEPTH = "/camera/depth/image_rect_raw"
DEPTH_W, DEPTH_H = 40, 30


def depth_info(t_ns):
    info = camera_info(t_ns)
    info.width, info.height = DEPTH_W, DEPTH_H
    info.k = np.array([30.0, 0, 19.5, 0, 30.0, 14.5, 0, 0, 1])
    return info


def raw_depth(i):
    millimetres = (rng_depth(i)[:DEPTH_H, :DEPTH_W] * 1000)
    return np.nan_to_num(millimetres, nan=0).astype(np.uint16)


def realsense_raw(depth_every=1, with_colour=True):
    """Colour and the depth camera's own depth (16UC1, its own size and intrinsics), the depth
    at the colour's rate or every `depth_every` frames."""
    messages = []
    for i in range(FRAMES):
        t = START_NS + i * FRAME_NS
        if with_colour:
            messages.append((COLOUR, t + 2_000_000, image(t, "rgb8", rng_colour(i))))
            messages.append(("/camera/color/camera_info", t + 2_000_001, camera_info(t)))
        if i % depth_every == 0:
            depth = image(t, "16UC1", raw_depth(i))
            depth.header = header(t, "camera_depth_optical_frame")
            messages.append((RAW_DEPTH, t + 2_500_000, depth))
            messages.append(("/camera/depth/camera_info", t + 2_500_001, depth_info(t)))
    return messages


def check_depth_camera(bag, out, spec_changes_colour):
    before, types_before = raw_messages(bag)
    after, types_after = raw_messages(out)
    assert types_after == types_before
    for topic in ("/camera/color/camera_info", "/camera/depth/camera_info"):
        assert after[topic] == before[topic], topic
    assert [t for t, _ in after[RAW_DEPTH]] == [t for t, _ in before[RAW_DEPTH]]
    holes = 0
    for a, b in zip(deserialized(bag, RAW_DEPTH), deserialized(out, RAW_DEPTH)):
        assert (b.encoding, b.width, b.height, b.header.frame_id) == ("16UC1", DEPTH_W, DEPTH_H,
                                                                        "camera_depth_optical_frame")
        assert stamp_ns(b) == stamp_ns(a)
        za, zb = a.data.view("<u2"), b.data.view("<u2")
        kept = zb > 0
        assert np.array_equal(za[kept], zb[kept])
        holes += int((zb == 0).sum() - (za == 0).sum())
    assert holes > 0
    colour_changed = before[COLOUR] != after[COLOUR]
    assert colour_changed == spec_changes_colour
    return json.loads((out / "rslam.json").read_text())["extra"]["cameras"]


def test_unregistered_depth_is_a_camera_of_its_own(rslam_bin, tmp_path):
    bag = tmp_path / "raw"
    write_bag(bag, realsense_raw())
    out = tmp_path / "perturbed"
    run_cli(rslam_bin, "perturb", "--input", bag, "--perturb", "gaussian_noise:2,depth_missing:3", "--out", out)
    cameras = check_depth_camera(bag, out, spec_changes_colour=True)
    assert [(c["colour_topic"], c["depth_topic"]) for c in cameras] == [(COLOUR, None), (None, RAW_DEPTH)]


def test_depth_at_another_rate_is_a_camera_of_its_own(rslam_bin, tmp_path):
    bag = tmp_path / "half_rate"
    messages = realsense_raw(depth_every=2)
    # Registered to colour (its size and intrinsics), but at half its rate.
    registered = [("/camera/aligned_depth_to_color/image_raw", t + 1,
                   image(stamp_ns(m), "16UC1", np.full((HEIGHT, WIDTH), 1500, np.uint16)))
                  for topic, t, m in messages if topic == RAW_DEPTH]
    infos = [("/camera/aligned_depth_to_color/camera_info", t + 1, camera_info(stamp_ns(m)))
             for _, t, m in registered]
    write_bag(bag, sorted(messages + registered + infos, key=lambda m: m[1]))
    out = tmp_path / "perturbed"
    run_cli(rslam_bin, "perturb", "--input", bag, "--perturb", "depth_missing:3", "--out", out)
    cameras = json.loads((out / "rslam.json").read_text())["extra"]["cameras"]
    assert [(c["colour_topic"], c["depth_topic"], c["frames"]) for c in cameras] == [
        (COLOUR, None, FRAMES), (None, RAW_DEPTH, FRAMES // 2),
        (None, "/camera/aligned_depth_to_color/image_raw", FRAMES // 2)]
    aligned = deserialized(out, "/camera/aligned_depth_to_color/image_raw")
    assert len(aligned) == FRAMES // 2
    assert sum(int((m.data.view("<u2") == 0).sum()) for m in aligned) > 0


def test_a_bag_of_depth_alone_refuses_image_items(rslam_bin, tmp_path):
    bag = tmp_path / "depth_only"
    write_bag(bag, realsense_raw(with_colour=False))
    line = refusal(rslam_bin, bag, tmp_path, spec="fog:2")
    assert "fog" in line and "no colour topic" in line and "depth_only" in line
    out = tmp_path / "perturbed"
    run_cli(rslam_bin, "perturb", "--input", bag, "--perturb", "depth_noise:2", "--out", out)
    assert len(deserialized(out, RAW_DEPTH)) == FRAMES
