#!/usr/bin/env python3
# Makes the reference images of crates/perturb/tests/goldens.rs with the Python library
# imagecorruptions: a small deterministic photo-like input (input.png, 96x64) and, for every
# image corruption with a deterministic reference, <name>-<severity>.png at severities 1, 3, 5,
# exactly as `imagecorruptions.corrupt(image, severity, name)` returns it (np.uint8 of the
# clipped float result: truncation).
#
# Two corruptions draw random numbers; here they get rslam's draws for seed 0, frame 0 (the
# counter-based hash of crates/perturb/src/rng.rs, re-stated below), so the reference code runs
# on the same randomness as the GPU:
#   motion_blur: `np.random.uniform(-45, 45)` (the angle) returns rslam's angle.
#   fog: inside imagecorruptions' own `plasma_fractal`, every `np.random.uniform(-w, w, shape)`
#        returns rslam's draw for each point being filled, so the reference diamond-square and
#        the reference fog formula both run on rslam's random numbers.
# Left out: glass_blur (random pixel swaps in a sequential sweep; rslam gathers in parallel),
# the noises, snow, frost, spatter, elastic_transform (statistically matched, not pixel-wise).
#
# Exact versions used (old pins: scikit-image >= 0.20 no longer takes the `multichannel=`
# argument imagecorruptions 1.1.2 passes, and 0.18/0.19 have no wheels for Python >= 3.10):
#   Python 3.9.18, imagecorruptions 1.1.2, numpy 1.19.5, scipy 1.5.4, scikit-image 0.18.3,
#   opencv-python-headless 4.5.1.48, Pillow 11.3.0 (its wheel's JPEG codec: libjpeg-turbo 3.1.1)
# Pillow's JPEG codec matters: wheels before Pillow 9 bundle IJG libjpeg 9, whose DCT-scaled
# chroma upsampling differs from libjpeg-turbo's fancy upsampling (27 dB apart on this input);
# rslam follows libjpeg-turbo, what every current Pillow wheel ships.
# Run from the repository root:
#   python3.9 -m venv /tmp/goldens-venv
#   /tmp/goldens-venv/bin/pip install --only-binary=:all: numpy==1.19.5 scipy==1.5.4 \
#       scikit-image==0.18.3 opencv-python-headless==4.5.1.48 Pillow==11.3.0
#   /tmp/goldens-venv/bin/pip install --no-deps imagecorruptions==1.1.2
#   /tmp/goldens-venv/bin/python scripts/make_goldens.py
# (--no-deps: imagecorruptions asks for opencv-python; the headless build is the same library.)
# Any other version, or any failure, stops the script with an error.

import sys
from importlib.metadata import version
from pathlib import Path

EXPECTED = {
    "imagecorruptions": "1.1.2",
    "numpy": "1.19.5",
    "scipy": "1.5.4",
    "scikit-image": "0.18.3",
    "opencv-python-headless": "4.5.1.48",
    "Pillow": "11.3.0",
}
wrong = {p: version(p) for p in EXPECTED if version(p) != EXPECTED[p]}
if wrong:
    sys.exit(f"make_goldens.py: wrong package versions {wrong}; expected {EXPECTED}")

import numpy as np  # noqa: E402
from PIL import Image, features  # noqa: E402
import imagecorruptions  # noqa: E402
import imagecorruptions.corruptions as reference  # noqa: E402

if not features.check_feature("libjpeg_turbo"):
    sys.exit(f"make_goldens.py: Pillow's JPEG codec is libjpeg {features.version('jpg')}, not libjpeg-turbo")

OUT = Path(__file__).resolve().parent.parent / "crates/perturb/tests/goldens"
WIDTH, HEIGHT = 96, 64
SEVERITIES = (1, 3, 5)
DETERMINISTIC = (
    "gaussian_blur", "defocus_blur", "zoom_blur", "pixelate", "contrast", "brightness",
    "saturate", "jpeg_compression",
)
SEED, FRAME = 0, 0
MAX_PNG_BYTES = 40_000


# ---- rslam's counter-based RNG (crates/perturb/src/rng.rs), on uint32 arrays -----------------

def pcg4d(v):
    v = [np.asarray(x, dtype=np.uint32) * np.uint32(1664525) + np.uint32(1013904223) for x in v]

    def mix(v):
        v[0] = v[0] + v[1] * v[3]
        v[1] = v[1] + v[2] * v[0]
        v[2] = v[2] + v[0] * v[1]
        v[3] = v[3] + v[1] * v[2]

    mix(v)
    v = [x ^ (x >> np.uint32(16)) for x in v]
    mix(v)
    return v


def name_hash(name):
    h = 0x811C9DC5
    for b in name.encode():
        h = ((h ^ b) * 0x01000193) & 0xFFFFFFFF
    return h


def rng_key(seed, name, frame, purpose):
    one = lambda x: np.array([x], dtype=np.uint32)  # noqa: E731
    k = pcg4d([one(seed & 0xFFFFFFFF), one(seed >> 32), one(name_hash(name)), one(frame)])
    return pcg4d([k[0] ^ np.uint32(purpose), k[1], k[2], k[3]])


def draw(key, counter):
    return pcg4d([np.asarray(c, dtype=np.uint32) ^ k for c, k in zip(counter, key)])


def uniform24(bits):
    """`rng::uniform`: the top 24 bits, in [0, 1)."""
    return (bits >> np.uint32(8)).astype(np.float64) / 16777216.0


def uniform_f64(key, counter):
    u = draw(key, counter)
    bits = (int(u[0][0]) << 21) ^ (int(u[1][0]) >> 11)
    return (bits & ((1 << 53) - 1)) / float(1 << 53)


# ---- the input image -----------------------------------------------------------------------

def make_input():
    """Smooth gradients, hard edges, saturated and grey areas, pure black and white, fine
    texture (1-px checker, stripes, hashed speckle); integer-exact, no randomness."""
    y, x = np.mgrid[0:HEIGHT, 0:WIDTH].astype(np.float64)
    u, v = x / WIDTH, y / HEIGHT
    img = np.stack([0.15 + 0.7 * u, 0.2 + 0.6 * v, 0.5 + 0.35 * np.sin(7 * u + 4 * v)], -1)
    disc = (u - 0.3) ** 2 + ((v - 0.4) * HEIGHT / WIDTH) ** 2 < 0.018
    img[disc] = (0.95, 0.1, 0.08)
    img[(u > 0.05) & (u < 0.2) & (v > 0.65) & (v < 0.9)] = (0.1, 0.25, 0.9)
    img[(u > 0.5) & (u < 0.58) & (v > 0.1) & (v < 0.6)] = (0.2, 0.85, 0.3)
    checker = (u >= 0.62) & (u < 0.8) & (v >= 0.1) & (v < 0.45)
    img[checker] = np.where(((x + y) % 2 == 0)[checker, None], (0.85, 0.85, 0.8), (0.15, 0.1, 0.2))
    stripes = (u >= 0.82) & (v >= 0.1) & (v < 0.6)
    img[stripes] = np.where(((x // 2) % 2 == 0)[stripes, None], (0.9, 0.7, 0.2), (0.3, 0.2, 0.5))
    speckle = (u >= 0.62) & (u < 0.8) & (v >= 0.5) & (v < 0.75)
    hashed = ((x * 73 + y * 151 + x * y * 29) % 97) / 96.0
    img[speckle] = (0.4 + 0.4 * hashed[speckle, None]) * np.array([1.0, 0.95, 0.85])
    grey = v >= 0.8
    img[grey & (u >= 0.25)] = np.floor((u[grey & (u >= 0.25), None] - 0.25) / 0.75 * 8) / 7
    img[grey & (u >= 0.25) & (u < 0.35)] = 0.0
    img[grey & (u >= 0.9)] = 1.0
    return np.round(np.clip(img, 0, 1) * 255).astype(np.uint8)


# ---- rslam's randomness fed to the reference -----------------------------------------------

class FedUniform:
    """Stands in for np.random.uniform while the reference code runs."""

    def __init__(self, answer):
        self.answer = answer
        self.calls = 0

    def __call__(self, low=0.0, high=1.0, size=None):
        self.calls += 1
        return self.answer(low, high, size, self.calls - 1)


def motion_angle():
    """`motion_blur::frame_angle`: −45 + 90·u, u = uniform_f64 of (seed, "motion_blur", frame, 0)."""
    return -45.0 + 90.0 * uniform_f64(rng_key(SEED, "motion_blur", FRAME, 0), [0, 0, 0, 0])


def plasma_draws(mapsize):
    """Answers the three `np.random.uniform(-w, w, shape)` calls per level of the reference
    `plasma_fractal` (squares at (s·i+h, s·j+h), then diamonds at (s·i+h, s·j), then at
    (s·i, s·j+h), arrays indexed [row j, column i]) with rslam's draw for each filled point:
    u = uniform(draw(key, [x, y, 0, 0])[0]) (`fog::plasma`)."""
    key = rng_key(SEED, "fog", FRAME, 0)

    def answer(low, high, size, call):
        level, kind = divmod(call, 3)
        step = mapsize >> level
        half = step // 2
        cells = mapsize // step
        if size != (cells, cells) or -low != high:
            raise RuntimeError(f"plasma_fractal call {call}: unexpected uniform({low}, {high}, {size})")
        j, i = np.mgrid[0:cells, 0:cells].astype(np.uint32)
        x, y = [(step * i + half, step * j + half), (step * i + half, step * j),
                (step * i, step * j + half)][kind]
        zeros = np.zeros_like(x)
        u = uniform24(draw(key, [x, y, zeros, zeros])[0])
        return low + (high - low) * u

    return answer


def corrupt_fed(image, severity, name):
    real = np.random.uniform
    if name == "motion_blur":
        angle = motion_angle()
        fed = FedUniform(lambda low, high, size, call: angle)
        expected_calls = 1
    elif name == "fog":
        mapsize = reference.next_power_of_2(int(max(image.shape)))
        fed = FedUniform(plasma_draws(mapsize))
        expected_calls = 3 * int(np.log2(mapsize))
    else:
        raise ValueError(name)
    np.random.uniform = fed
    try:
        out = imagecorruptions.corrupt(image, severity=severity, corruption_name=name)
    finally:
        np.random.uniform = real
    if fed.calls != expected_calls:
        raise RuntimeError(f"{name}: np.random.uniform called {fed.calls} times, expected {expected_calls}")
    return out


def save(array, name):
    path = OUT / f"{name}.png"
    Image.fromarray(array).save(path, optimize=True)
    size = path.stat().st_size
    if size >= MAX_PNG_BYTES:
        raise RuntimeError(f"{path}: {size} bytes, over {MAX_PNG_BYTES}")
    return size


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    image = make_input()
    total = save(image, "input")
    np.random.seed(0)  # nothing below should draw from it; fixed all the same
    for name in DETERMINISTIC + ("motion_blur", "fog"):
        for severity in SEVERITIES:
            if name in DETERMINISTIC:
                out = imagecorruptions.corrupt(image, severity=severity, corruption_name=name)
            else:
                out = corrupt_fed(image, severity, name)
            if out.dtype != np.uint8 or out.shape != image.shape:
                raise RuntimeError(f"{name}-{severity}: got {out.dtype} {out.shape}")
            total += save(out, f"{name}-{severity}")
    print(f"motion_blur angle (seed {SEED}, frame {FRAME}): {motion_angle():.6f} degrees")
    print(f"wrote {OUT}: {total} bytes of PNG")


if __name__ == "__main__":
    main()
