#!/usr/bin/env python3
# Times rslam.corrupt / rslam.Perturber against imagecorruptions.corrupt and albumentations' closest
# transforms, in memory, per frame at 1200x680 (the Replica camera), batch 1 and batch 16, for
# every imagecorruptions name at severity 3; prints a Markdown table (ms per frame, median).
# Not a test. Run in a venv with rslam, imagecorruptions and albumentations installed, e.g.
#   target/python-venv/bin/pip install albumentations   # after scripts/test-python.sh
#   target/python-venv/bin/python scripts/bench-python.py
# rslam: batch 1 = rslam.corrupt per frame; batch 16 = Perturber.apply_batch on 16 frames (one
# pass over the GPU, frames in flight overlap). The others have no batch API: batch 16 is a loop,
# timed only where one frame takes under BATCH_LOOP_LIMIT_S (else '-', it would take minutes).
# Warm figures: the first call (GPU context, shader compilation) is run and reported apart.
import statistics
import sys
import time

import numpy as np

import rslam

try:
    from imagecorruptions import corrupt as ic_corrupt
    from reference_corruptions import ALBUMENTATIONS
except ImportError as missing:
    sys.exit(f"bench-python.py: {missing}; install imagecorruptions and albumentations")

WIDTH, HEIGHT, SEVERITY, BATCH = 1200, 680, 3, 16
REPEATS = 3
BATCH_LOOP_LIMIT_S = 0.5


def scene(width, height, shift):
    y, x = np.mgrid[0:height, 0:width].astype(np.float32)
    x = x + shift
    wall = 0.55 + 0.25 * np.sin(x / 53.0) * np.cos(y / 71.0)
    img = np.stack([wall * 0.95, wall * 0.85, wall * 0.7], axis=-1)
    floor = y > height * 0.65
    checker = ((x // 24 + y // 24) % 2)[..., None] * 0.25 + 0.35
    img = np.where(floor[..., None], checker * np.array([0.6, 0.45, 0.3], np.float32), img)
    return (np.clip(img, 0, 1) * 255).astype(np.uint8)


FRAMES = np.stack([scene(WIDTH, HEIGHT, 7 * i) for i in range(BATCH)])

def median_ms(fn, repeats=REPEATS):
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        fn()
        times.append(time.perf_counter() - start)
    return 1000 * statistics.median(times)


def loop_ms(one_frame_ms, fn):
    """Per-frame time of a 16-frame loop, when one frame is cheap enough to loop."""
    if one_frame_ms / 1000 > BATCH_LOOP_LIMIT_S:
        return None
    start = time.perf_counter()
    for frame in FRAMES:
        fn(frame)
    return 1000 * (time.perf_counter() - start) / BATCH


def fmt(ms):
    return "-" if ms is None else (f"{ms:.0f}" if ms >= 10 else f"{ms:.1f}")


def main():
    start = time.perf_counter()
    rslam.gpu_adapter()
    context_s = time.perf_counter() - start
    print(f"# rslam {rslam.__version__} on {rslam.gpu_adapter()}; {WIDTH}x{HEIGHT}, severity "
          f"{SEVERITY}, ms per frame (median of {REPEATS}); GPU context created in "
          f"{context_s:.2f} s", flush=True)
    print("| corruption | rslam first call | rslam b1 | rslam b16 | imagecorruptions b1 | "
          "imagecorruptions b16 | albumentations b1 | albumentations b16 |")
    print("|---|--:|--:|--:|--:|--:|--:|--:|")
    frame = FRAMES[0]
    for name in rslam.get_corruption_names("all"):
        first = time.perf_counter()
        rslam.corrupt(frame, SEVERITY, name)
        first_ms = 1000 * (time.perf_counter() - first)
        ours_1 = median_ms(lambda: rslam.corrupt(frame, SEVERITY, name))
        perturber = rslam.Perturber(f"{name}:{SEVERITY}")
        perturber.apply_batch(FRAMES)  # builds for this size
        ours_16 = median_ms(lambda: perturber.apply_batch(FRAMES)) / BATCH
        theirs_1 = median_ms(lambda: ic_corrupt(frame, SEVERITY, name), repeats=2)
        theirs_16 = loop_ms(theirs_1, lambda f: ic_corrupt(f, SEVERITY, name))
        make = ALBUMENTATIONS[name]
        if make is None:
            album_1 = album_16 = None
        else:
            transform = make()
            transform(image=frame)
            album_1 = median_ms(lambda: transform(image=frame))
            album_16 = loop_ms(album_1, lambda f: transform(image=f))
        print(f"| {name} | {fmt(first_ms)} | {fmt(ours_1)} | {fmt(ours_16)} | {fmt(theirs_1)} | "
              f"{fmt(theirs_16)} | {fmt(album_1)} | {fmt(album_16)} |", flush=True)
    print(f"# total {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    main()
