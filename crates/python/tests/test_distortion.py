"""`rslam render --perturb distortion:...` through the real binary, undistorted with OpenCV from
the camera files it writes (cam_params.json, orbslam3.yaml): straight edges in the scene come
out straight, and were not straight in the distorted frames."""

import json

import cv2
import numpy as np
import pytest
from PIL import Image

from conftest import run_cli

WIDTH, HEIGHT, F = 320, 240, 250.0
CAMERA = f"{WIDTH},{HEIGHT},{F},{F},{(WIDTH - 1) / 2},{(HEIGHT - 1) / 2}"
PLANE_Z = 2.0
# World x of the vertical edges between black and white bands on the plane.
EDGES_X = (-0.6, -0.2, 0.2, 0.6)


def write_stripes(path):
    """White bands x in [-0.6, -0.2] and [0.2, 0.6] on a black plane at z = 2, as OBJ with
    vertex colours."""
    lines, faces = [], []
    bands = [(-3.0, -0.6, 0), (-0.6, -0.2, 1), (-0.2, 0.2, 0), (0.2, 0.6, 1), (0.6, 3.0, 0)]
    for x0, x1, white in bands:
        base = len(lines) + 1
        for x, y in ((x0, -3.0), (x1, -3.0), (x1, 3.0), (x0, 3.0)):
            lines.append(f"v {x} {y} {PLANE_Z} {white} {white} {white}")
        faces.append(f"f {base} {base + 1} {base + 2} {base + 3}")
    path.write_text("\n".join(lines + faces) + "\n")


def render(tmp_path, rslam_bin, layout, lens):
    mesh = tmp_path / "stripes.obj"
    write_stripes(mesh)
    traj = tmp_path / "traj.txt"
    traj.write_text("".join(f"{t / 20:.6f} 0 0 0 0 0 0 1\n" for t in range(2)))
    out = tmp_path / layout
    run_cli(rslam_bin, "render", "--scene", mesh, "--traj", traj, "--camera", CAMERA,
            "--format", layout, "--perturb", f"distortion:{lens}", "--out", out)
    return out


def edge_bows(grey):
    """For each edge: its sub-pixel column in every row (the centroid of the brightness gradient
    near where a pinhole sees it), and how far those points bow from a straight line: the
    sagitta of a parabola fitted through them over the rows measured. A lens left in the image
    bows the edges smoothly; JPEG and resampling add row-to-row noise the fit averages out."""
    linear = (grey.astype(np.float64) / 255.0) ** 2.2
    gradient = np.abs(np.diff(linear, axis=1))
    rows = np.arange(int(HEIGHT * 0.1), int(HEIGHT * 0.9))
    half_span = (rows[-1] - rows[0]) / 2
    bows = []
    for x in EDGES_X:
        column = F * x / PLANE_Z + (WIDTH - 1) / 2
        lo, hi = int(column) - 12, int(column) + 13
        window = gradient[rows, lo:hi]
        assert (window.sum(axis=1) > 0.5).all(), f"edge at x = {x} not found in every row"
        # Gradient sample i lies between pixels lo + i and lo + i + 1.
        centres = (window * (np.arange(lo, hi) + 0.5)).sum(axis=1) / window.sum(axis=1)
        curvature = np.polyfit(rows - rows.mean(), centres, 2)[0]
        bows.append(abs(curvature) * half_span**2)
    return np.array(bows)


def read_cam_params(out):
    """Intrinsics and lens from the Replica layout's cam_params.json."""
    camera = json.loads((out / "cam_params.json").read_text())["camera"]
    k = np.array([[camera["fx"], 0, camera["cx"]], [0, camera["fy"], camera["cy"]], [0, 0, 1]])
    return k, camera["distortion_model"], np.array(camera["distortion"])


def read_orbslam3(out):
    """Intrinsics and lens from the TUM layout's orbslam3.yaml, read as ORB-SLAM3 reads it
    (cv::FileStorage): PinHole with k1, k2, p1, p2 or KannalaBrandt8 with k1..k4."""
    settings = cv2.FileStorage(str(out / "orbslam3.yaml"), cv2.FILE_STORAGE_READ)
    value = lambda key: settings.getNode(f"Camera1.{key}").real()
    k = np.array([[value("fx"), 0, value("cx")], [0, value("fy"), value("cy")], [0, 0, 1]])
    model = {"PinHole": "radtan", "KannalaBrandt8": "equidistant"}[
        settings.getNode("Camera.type").string()]
    names = ("k1", "k2", "p1", "p2") if model == "radtan" else ("k1", "k2", "k3", "k4")
    return k, model, np.array([value(n) for n in names])


# Replica frames are JPEG (quality 95): its 8x8 blocks bias an edge by up to ~0.2 px depending
# on where in a block it falls, which a bowed edge sweeps through; TUM frames are PNG.
CASES = [
    ("replica", read_cam_params, "results/frame*.jpg", 0.3),
    ("tum", read_orbslam3, "rgb/*.png", 0.1),
]
LENSES = {
    "radtan": ("radtan(-0.3,0.08,0.002,-0.0015)", [-0.3, 0.08, 0.002, -0.0015]),
    "equidistant": ("equidistant(0.08,-0.03,0.01,-0.002)", [0.08, -0.03, 0.01, -0.002]),
}


@pytest.mark.parametrize("model", sorted(LENSES))
@pytest.mark.parametrize("layout,read_camera,frames,tolerance", CASES)
def test_written_lens_undistorts_to_straight_lines(tmp_path, rslam_bin, model, layout,
                                                   read_camera, frames, tolerance):
    lens, coefficients = LENSES[model]
    out = render(tmp_path, rslam_bin, layout, lens)
    k, written_model, written = read_camera(out)
    assert written_model == model
    assert np.array_equal(written, coefficients)
    assert k[0, 2] == (WIDTH - 1) / 2 and k[0, 0] == F
    raw = np.asarray(Image.open(sorted(out.glob(frames))[0]).convert("L"))
    if model == "radtan":
        straight = cv2.undistort(raw, k, written)
    else:
        straight = cv2.fisheye.undistortImage(raw, k, written, Knew=k)
    bent, fixed = edge_bows(raw), edge_bows(straight)
    assert bent.max() > 1.5, f"the distorted edges should bow: {bent} px"
    assert fixed.max() < tolerance, f"undistorted edges bow by {fixed} px"
