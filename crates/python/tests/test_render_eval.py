"""rslam.render against the files `rslam render` writes, and rslam.eval against `rslam eval
--json`, both through the real binary."""

import json

import numpy as np
from PIL import Image

import rslam

from conftest import run_cli

CAMERA = "64,48,40,40,31.5,23.5"
REPLICA_DEPTH_SCALE = 6553.5


def test_render_matches_rslam_render_depth(tmp_path, rslam_bin):
    poses = rslam.scene_poses("room0")[:3]
    assert poses.shape[1:] == (4, 4) and len(rslam.scene_poses("room0")) > 3
    rgb, depth = rslam.render("room0", poses, camera=CAMERA)
    assert rgb.shape == (3, 48, 64, 3) and rgb.dtype == np.uint8
    assert depth.shape == (3, 48, 64) and depth.dtype == np.float32
    assert rgb.std() > 5 and (depth > 0).mean() > 0.9

    run_cli(rslam_bin, "render", "--scene", "room0", "--frames", 3, "--camera", CAMERA,
            "--out", tmp_path / "r")
    for i in range(3):
        written = np.asarray(Image.open(tmp_path / "r" / "results" / f"depth{i:06d}.png"))
        ours = np.where(depth[i] > 0, np.round(depth[i].astype(np.float64) * REPLICA_DEPTH_SCALE),
                        0)
        ours = np.minimum(ours, 65535).astype(np.uint16)
        assert np.array_equal(ours, written.astype(np.uint16)), f"depth of frame {i}"
        # Colour is stored as JPEG: compare loosely.
        jpeg = np.asarray(Image.open(tmp_path / "r" / "results" / f"frame{i:06d}.jpg"))
        assert np.abs(jpeg.astype(int) - rgb[i]).mean() < 6


def test_render_with_perturbations_is_deterministic():
    poses = rslam.scene_poses("office0")[:2]
    a = rslam.render("office0", poses, camera=CAMERA, perturb="fog:3,depth_missing:4", seed=2)
    b = rslam.render("office0", poses, camera=CAMERA, perturb="fog:3,depth_missing:4", seed=2)
    clean = rslam.render("office0", poses, camera=CAMERA)
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])
    assert not np.array_equal(a[0], clean[0])
    assert (a[1] == 0).sum() > (clean[1] == 0).sum()


def write_tum(path, rows):
    path.write_text("".join(" ".join(f"{v:.9f}" for v in r) + "\n" for r in rows))


def test_eval_matches_the_cli(tmp_path, rslam_bin):
    rng = np.random.default_rng(7)
    t = np.arange(60) / 30.0
    gt = np.zeros((60, 8))
    gt[:, 0] = t
    gt[:, 1] = np.cos(t)
    gt[:, 2] = np.sin(1.3 * t)
    gt[:, 3] = 0.2 * t
    angle = 0.3 * t
    gt[:, 6] = np.sin(angle / 2)
    gt[:, 7] = np.cos(angle / 2)
    est = gt.copy()
    est[:, 1:4] += rng.normal(0, 0.01, (60, 3)) + [0.5, -0.2, 0.1]
    write_tum(tmp_path / "gt.txt", gt)
    write_tum(tmp_path / "est.txt", est)
    cli = json.loads(run_cli(rslam_bin, "eval", tmp_path / "est.txt", tmp_path / "gt.txt",
                             "--json"))
    for align in ("se3", "sim3", "none"):
        cli = json.loads(run_cli(rslam_bin, "eval", tmp_path / "est.txt", tmp_path / "gt.txt",
                                 "--json", "--align", align))
        from_files = rslam.eval.evaluate(str(tmp_path / "est.txt"), tmp_path / "gt.txt",
                                         align=align)
        assert from_files == cli, align
        ate = rslam.eval.ate(tmp_path / "est.txt", tmp_path / "gt.txt", align=align)
        assert {k: ate[k] for k in cli["ate"]} == cli["ate"]
        assert ate["alignment"] == cli["alignment"]
    # Arrays: the same numbers as the files (written with 9 decimals).
    rounded = lambda a: np.array([[float(f"{v:.9f}") for v in r] for r in a])
    assert rslam.eval.ate(rounded(est), rounded(gt))["rmse"] == rslam.eval.ate(
        tmp_path / "est.txt", tmp_path / "gt.txt")["rmse"]
    assert rslam.eval.ate(est, gt)["rmse"] < 0.03
