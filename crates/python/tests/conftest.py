"""Shared fixtures: the repository's paths, the `rslam` binary the Perturber tests compare with,
and the clean test images (the perturb crate's golden input and a larger synthetic scene)."""

import os
import subprocess
from pathlib import Path

import numpy as np
import pytest
from PIL import Image

REPO = Path(__file__).resolve().parents[3]
GOLDENS = REPO / "crates/perturb/tests/goldens"


@pytest.fixture(scope="session")
def rslam_bin():
    """The CLI binary: $RSLAM_BIN, else target/debug/rslam (scripts/test-python.sh builds it).
    Missing is a failure, not a skip."""
    path = Path(os.environ.get("RSLAM_BIN", REPO / "target/debug/rslam"))
    if not path.is_file():
        pytest.fail(f"no rslam binary at {path}: build it with `cargo build -p rslam-cli` "
                    "or set RSLAM_BIN")
    return path


def run_cli(binary, *args):
    """Runs the CLI; a non-zero exit fails the test with its stderr."""
    done = subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True)
    if done.returncode != 0:
        pytest.fail(f"rslam {' '.join(map(str, args))} exited {done.returncode}:\n{done.stderr}")
    return done.stdout


def golden_input():
    """96x64 photo-like image the Rust goldens use (crates/perturb/tests/goldens/input.png)."""
    return np.asarray(Image.open(GOLDENS / "input.png").convert("RGB"))


def synthetic_scene(width=160, height=120):
    """A deterministic indoor-like image: smooth shading, edges, texture and saturated colour."""
    y, x = np.mgrid[0:height, 0:width].astype(np.float64)
    wall = 0.55 + 0.25 * np.sin(x / 23.0) * np.cos(y / 31.0)
    img = np.stack([wall * 0.95, wall * 0.85, wall * 0.7], axis=-1)
    floor = y > height * 0.65
    checker = ((x // 8 + y // 8) % 2)[..., None] * 0.25 + 0.35
    img = np.where(floor[..., None], checker * np.array([0.6, 0.45, 0.3]), img)
    box = (abs(x - width * 0.3) < width * 0.12) & (abs(y - height * 0.55) < height * 0.15)
    img[box] = [0.8, 0.15, 0.1]
    window = (abs(x - width * 0.72) < width * 0.1) & (abs(y - height * 0.3) < height * 0.12)
    img[window] = [0.9, 0.95, 1.0]
    return (np.clip(img, 0, 1) * 255).astype(np.uint8)


@pytest.fixture(scope="session")
def clean_images():
    return {"golden": golden_input(), "scene": synthetic_scene()}
