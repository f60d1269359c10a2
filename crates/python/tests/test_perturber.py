"""Perturber.apply / apply_batch give exactly the files `rslam perturb` writes for the same spec,
seed and frame (the real binary runs in the test), for an image folder and for a TUM dataset with
16-bit depth."""

import json

import numpy as np
import pytest
from PIL import Image

import rslam

from conftest import run_cli, synthetic_scene

WIDTH, HEIGHT = 64, 48
CAMERA = f"{WIDTH},{HEIGHT},50,50,31.5,23.5"
TUM_DEPTH_SCALE = 5000.0


def frames(count):
    """Distinct colour frames (shifted crops of the synthetic scene) and depth ramps in metres."""
    scene = synthetic_scene(WIDTH + 8 * count, HEIGHT)
    colors = [np.ascontiguousarray(scene[:, 8 * i:8 * i + WIDTH]) for i in range(count)]
    y, x = np.mgrid[0:HEIGHT, 0:WIDTH]
    depths = [(0.5 + 0.03 * x + 0.02 * y + 0.1 * i).astype(np.float64) for i in range(count)]
    return colors, depths


def test_image_folder(tmp_path, rslam_bin):
    spec, seed = "gaussian_noise:3,fog:4@dynamic,jpeg_compression:2", 5
    colors, _ = frames(4)
    inputs = tmp_path / "in"
    inputs.mkdir()
    for i, color in enumerate(colors):
        Image.fromarray(color).save(inputs / f"img{i:02d}.png")
    run_cli(rslam_bin, "perturb", "--input", inputs, "--out", tmp_path / "out",
            "--perturb", spec, "--seed", seed)
    written = [np.asarray(Image.open(tmp_path / "out" / f"img{i:02d}.png").convert("RGB"))
               for i in range(4)]

    perturber = rslam.Perturber(spec, seed=seed)
    for i in (2, 0, 3, 1):  # any order: randomness is keyed by the frame index
        rgb, depth = perturber.apply(colors[i], frame_index=i)
        assert depth is None
        assert np.array_equal(rgb, written[i]), f"frame {i}"
        assert rgb.flags["C_CONTIGUOUS"]

    order = [3, 1, 0]
    batch, _ = perturber.apply_batch(np.stack([colors[i] for i in order]), frame_indices=order)
    assert batch.shape == (3, HEIGHT, WIDTH, 3)
    for k, i in enumerate(order):
        assert np.array_equal(batch[k], written[i]), f"batch frame {i}"

    # The manifest's per-frame severities are the Perturber's.
    manifest = json.loads((tmp_path / "out" / "rslam.json").read_text())
    text = json.dumps(manifest)
    fog = [perturber.severities(i)["fog"] for i in range(4)]
    assert "".join(map(str, fog)) in text


def write_tum(root, colors, depths):
    (root / "rgb").mkdir(parents=True)
    (root / "depth").mkdir()
    rgb_lines, depth_lines = [], []
    for i, (color, depth) in enumerate(zip(colors, depths)):
        t = f"{1.0 + i / 30:.6f}"
        Image.fromarray(color).save(root / "rgb" / f"{t}.png")
        raw = np.round(depth * TUM_DEPTH_SCALE).astype(np.uint16)
        Image.fromarray(raw).save(root / "depth" / f"{t}.png")
        rgb_lines.append(f"{t} rgb/{t}.png")
        depth_lines.append(f"{t} depth/{t}.png")
    (root / "rgb.txt").write_text("\n".join(rgb_lines) + "\n")
    (root / "depth.txt").write_text("\n".join(depth_lines) + "\n")


def read_tum_frames(root):
    def listed(name):
        return [line.split()[1] for line in (root / name).read_text().splitlines()
                if line.strip() and not line.startswith("#")]
    colors = [np.asarray(Image.open(root / p).convert("RGB")) for p in listed("rgb.txt")]
    depths = [np.asarray(Image.open(root / p)).astype(np.uint16) for p in listed("depth.txt")]
    return colors, depths


def perturbed_by_the_cli(tmp_path, rslam_bin, spec, seed, count):
    """`count` TUM frames written to tmp_path/ds and `rslam perturb` of them into tmp_path/out,
    each read back: (input colours, input depths), (written colours, written depths)."""
    colors, depths = frames(count)
    write_tum(tmp_path / "ds", colors, depths)
    run_cli(rslam_bin, "perturb", "--input", tmp_path / "ds", "--out", tmp_path / "out",
            "--perturb", spec, "--seed", seed, "--camera", CAMERA)
    return read_tum_frames(tmp_path / "ds"), read_tum_frames(tmp_path / "out")


def test_tum_dataset_with_depth(tmp_path, rslam_bin):
    spec, seed = "motion_blur:2,shot_noise:3@dynamic,depth_noise:2,depth_missing:3", 11
    (inputs_rgb, inputs_depth), (written_rgb, written_depth) = perturbed_by_the_cli(
        tmp_path, rslam_bin, spec, seed, 3)
    assert len(written_rgb) == 3 and len(written_depth) == 3

    perturber = rslam.Perturber(spec, seed=seed, camera=CAMERA)
    for i in range(3):
        rgb, depth = perturber.apply(inputs_rgb[i], inputs_depth[i], frame_index=i,
                                     depth_scale=TUM_DEPTH_SCALE)
        assert depth.dtype == np.uint16
        assert np.array_equal(rgb, written_rgb[i]), f"colour of frame {i}"
        assert np.array_equal(depth, written_depth[i]), f"depth of frame {i}"
        assert (depth == 0).sum() > (inputs_depth[i] == 0).sum(), "depth_missing voided nothing"

    rgbs, raw = perturber.apply_batch(np.stack(inputs_rgb), np.stack(inputs_depth),
                                      depth_scale=TUM_DEPTH_SCALE)
    assert np.array_equal(rgbs, np.stack(written_rgb))
    assert np.array_equal(raw, np.stack(written_depth))

    # Metres in, metres out: the same frame, before quantisation.
    metres = inputs_depth[1].astype(np.float32) / np.float32(TUM_DEPTH_SCALE)
    _, depth_m = perturber.apply(inputs_rgb[1], metres.astype(np.float32), frame_index=1)
    assert depth_m.dtype == np.float32
    quantised = np.where(depth_m > 0, np.round(depth_m.astype(np.float64) * TUM_DEPTH_SCALE), 0)
    assert np.abs(quantised - written_depth[1]).max() <= 1


def test_depth_sensor_takes_the_camera_and_gives_what_the_cli_writes(tmp_path, rslam_bin):
    spec, seed = "depth_sensor:kinect", 2
    (inputs_rgb, inputs_depth), (_, written_depth) = perturbed_by_the_cli(
        tmp_path, rslam_bin, spec, seed, 2)

    perturber = rslam.Perturber(spec, seed=seed, camera=CAMERA)
    for i in range(2):
        _, depth = perturber.apply(inputs_rgb[i], inputs_depth[i], frame_index=i,
                                   depth_scale=TUM_DEPTH_SCALE)
        assert np.array_equal(depth, written_depth[i]), f"depth of frame {i}"
        assert not np.array_equal(depth, inputs_depth[i]), "the sensor model changed nothing"

    with pytest.raises(ValueError, match="without a camera"):
        rslam.Perturber(spec, seed=seed).apply(inputs_rgb[0], inputs_depth[0],
                                              depth_scale=TUM_DEPTH_SCALE)


def test_dynamic_severities_follow_the_frame():
    p = rslam.Perturber("fog:5@dynamic", seed=4)
    drawn = [p.severities(i)["fog"] for i in range(60)]
    assert set(drawn) <= set(range(6)) and len(set(drawn)) > 2
    clean = np.full((HEIGHT, WIDTH, 3), 128, np.uint8)
    for i, s in enumerate(drawn[:12]):
        rgb, _ = p.apply(clean, frame_index=i)
        assert np.array_equal(rgb, clean) == (s == 0), f"frame {i} severity {s}"


def test_real_severities_interpolate_the_parameters():
    grey = np.full((HEIGHT, WIDTH, 3), 128, np.uint8)
    p = rslam.Perturber("gaussian_noise:2.5", seed=2)
    assert p.severities(0) == {"gaussian_noise": 2.5}
    rgb, _ = p.apply(grey)
    sigma = (rgb.astype(np.float64) / 255.0).std()
    # Between the table's σ at 2 (0.12) and 3 (0.18): the interpolated 0.15.
    assert abs(sigma - 0.15) < 0.006, sigma
    clean, _ = rslam.Perturber("fog:0,gaussian_noise:0").apply(grey)
    assert np.array_equal(clean, grey)
    drawn = [rslam.Perturber("fog:2.5@dynamic", seed=4).severities(i)["fog"] for i in range(60)]
    assert all(0 <= s <= 2.5 for s in drawn) and any(s != int(s) for s in drawn)


def test_repr_and_properties():
    p = rslam.Perturber("depth_missing:2,fog:1", seed=3, camera="tum")
    assert repr(p) == "Perturber('fog:1,depth_missing:2', seed=3)"
    assert p.spec == "fog:1,depth_missing:2" and p.seed == 3
    assert p.camera == (640, 480, 525.0, 525.0, 319.5, 239.5)
