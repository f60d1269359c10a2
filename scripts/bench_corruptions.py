#!/usr/bin/env python3
# File in -> file out per corruption: `rslam perturb` over a folder of PNG frames beside
# imagecorruptions (PIL read, corrupt, PIL write, as its users do) and albumentations' closest
# transform (cv2 read, transform, cv2 write); ms per frame, the ratios, their medians, and
# rslam's own PNG decode + encode (the I/O limit). Run through scripts/bench-corruptions.sh,
# which builds rslam, makes the venv and the frames; directly:
#   python scripts/bench_corruptions.py RSLAM ROUNDTRIP FRAME_DIR [--corruptions a,b] ...
# rslam's figure is its steady state, (time of FRAMES frames - time of 1 frame) / (FRAMES - 1)
# for whole `rslam perturb` processes (start-up, shader builds and frost's per-seed texture left
# out), the median of REPEATS such pairs; the I/O limit is measured the same way right before
# each of them, and its column is the median of the paired ratios. The references' figure is the
# median over their per-frame loop in this process (imports left out), REF_FRAMES frames per
# repeat. Each corruption's figures are taken one right after the other, so a load change on a
# shared machine moves all of them.
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

try:
    import cv2
    import numpy as np
    from imagecorruptions import corrupt as ic_corrupt
    from imagecorruptions import get_corruption_names
    from PIL import Image

    from reference_corruptions import ALBUMENTATIONS
except ImportError as missing:
    sys.exit(f"bench_corruptions.py: {missing}; run it through scripts/bench-corruptions.sh")


def arguments():
    parser = argparse.ArgumentParser(prog="bench_corruptions.py")
    parser.add_argument("rslam", help="the rslam binary (release build)")
    parser.add_argument("roundtrip", help="the png_roundtrip example binary (release build)")
    parser.add_argument("frames_dir", help="a folder of PNG frames, all of one size")
    parser.add_argument("--corruptions", default=",".join(get_corruption_names("all")))
    parser.add_argument("--severity", type=int, default=3)
    parser.add_argument("--frames", type=int, default=40, help="frames per rslam run")
    parser.add_argument("--ref-frames", type=int, default=3, help="frames per reference loop")
    parser.add_argument("--repeats", type=int, default=3)
    return parser.parse_args()


def seconds(command):
    start = time.perf_counter()
    done = subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    elapsed = time.perf_counter() - start
    if done.returncode != 0:
        sys.exit(f"bench_corruptions.py: {' '.join(command)} failed:\n{done.stderr}")
    return elapsed


class Folders:
    """FRAMES links to the source frames (cycled) and a one-frame folder, under one temp dir."""

    def __init__(self, sources, frames):
        self.root = tempfile.mkdtemp(prefix="rslam-bench-")
        self.many = os.path.join(self.root, "many")
        self.one = os.path.join(self.root, "one")
        self.out = os.path.join(self.root, "out")
        os.makedirs(self.many)
        os.makedirs(self.one)
        for i in range(frames):
            os.symlink(sources[i % len(sources)], os.path.join(self.many, f"{i:05d}.png"))
        os.symlink(sources[0], os.path.join(self.one, "00000.png"))
        self.frames = frames

    def steady_ms(self, command):
        """Per-frame time of `command(input, out)` in steady state, from one pair of runs."""
        times = []
        for folder in (self.one, self.many):
            shutil.rmtree(self.out, ignore_errors=True)
            times.append(seconds(command(folder, self.out)))
        if times[1] <= times[0]:
            sys.exit(f"bench_corruptions.py: {' '.join(command(self.many, self.out))}: "
                     f"{self.frames} frames took {times[1]:.3f} s, 1 frame {times[0]:.3f} s; the "
                     f"start-up's noise hides the per-frame time: raise --frames (a fast GPU "
                     f"needs several hundred)")
        return 1000 * (times[1] - times[0]) / (self.frames - 1), 1000 * times[0]


def imagecorruptions_ms(name, severity, sources, out):
    def once(path):
        x = np.array(Image.open(path).convert("RGB"))
        y = ic_corrupt(x, severity=severity, corruption_name=name)
        Image.fromarray(np.uint8(y)).save(os.path.join(out, os.path.basename(path)))
    return per_frame_ms(once, sources)


def albumentations_ms(name, sources, out):
    make = ALBUMENTATIONS[name]
    if make is None:
        return []
    transform = make()

    def once(path):
        x = cv2.cvtColor(cv2.imread(path, cv2.IMREAD_COLOR), cv2.COLOR_BGR2RGB)
        y = transform(image=x)["image"]
        cv2.imwrite(os.path.join(out, os.path.basename(path)), cv2.cvtColor(y, cv2.COLOR_RGB2BGR))
    return per_frame_ms(once, sources)


def per_frame_ms(once, sources):
    times = []
    for path in sources:
        start = time.perf_counter()
        once(path)
        times.append(1000 * (time.perf_counter() - start))
    return times


def fmt(ms):
    return "-" if ms is None else (f"{ms:.0f}" if ms >= 10 else f"{ms:.1f}")


def ratio(theirs, ours):
    return None if theirs is None else theirs / ours


def median_or_none(values):
    return statistics.median(values) if values else None


def main():
    args = arguments()
    sources = sorted(os.path.join(args.frames_dir, f) for f in os.listdir(args.frames_dir)
                     if f.endswith(".png"))
    if not sources:
        sys.exit(f"bench_corruptions.py: {args.frames_dir}: no .png frames")
    size = Image.open(sources[0]).size
    folders = Folders([os.path.abspath(s) for s in sources], args.frames)
    reference_out = os.path.join(folders.root, "reference")
    os.makedirs(reference_out)
    try:
        load = os.getloadavg()[0]
        print(f"# {size[0]}x{size[1]} PNG frames from {args.frames_dir}, severity "
              f"{args.severity}; rslam: {args.frames} frames per run, median of {args.repeats} "
              f"runs; references: median of {args.ref_frames} frames x {args.repeats}; "
              f"{os.cpu_count()} CPU cores, load average {load:.1f} at the start")
        print("| corruption | rslam ms/frame | rslam, 1 frame (ms) | imagecorruptions ms/frame | "
              "albumentations ms/frame | × vs imagecorruptions | × vs albumentations | "
              "I/O limit ms/frame | rslam / I/O limit |")
        print("|---|--:|--:|--:|--:|--:|--:|--:|--:|")
        columns = {"ic": [], "album": [], "io": []}
        for name in args.corruptions.split(","):
            ours, first, theirs, album, io, io_ratios = [], [], [], [], [], []
            refs = sources[:args.ref_frames]
            for _ in range(args.repeats):
                io.append(folders.steady_ms(lambda i, o: [args.roundtrip, i, o])[0])
                steady, one = folders.steady_ms(lambda i, o: [
                    args.rslam, "perturb", "--input", i, "--out", o,
                    "--perturb", f"{name}:{args.severity}"])
                ours.append(steady)
                io_ratios.append(steady / io[-1])
                first.append(one)
                theirs += imagecorruptions_ms(name, args.severity, refs, reference_out)
                album += albumentations_ms(name, refs, reference_out)
            ours_ms = statistics.median(ours)
            ic_ms, album_ms = median_or_none(theirs), median_or_none(album)
            row = [ratio(ic_ms, ours_ms), ratio(album_ms, ours_ms), statistics.median(io_ratios)]
            for key, value in zip(columns, row):
                if value is not None:
                    columns[key].append(value)
            shown = [f"{v:.1f}×" if v is not None else "-" for v in row]
            print(f"| {name} | {fmt(ours_ms)} | {fmt(statistics.median(first))} | {fmt(ic_ms)} "
                  f"| {fmt(album_ms)} | {shown[0]} | {shown[1]} | {fmt(statistics.median(io))} "
                  f"| {shown[2]} |", flush=True)
        for key, what in (("ic", "faster than imagecorruptions"),
                          ("album", "faster than albumentations"),
                          ("io", "rslam / I/O limit")):
            values = sorted(columns[key])
            print(f"# {what}: median {statistics.median(values):.1f}×, lowest {values[0]:.1f}×, "
                  f"highest {values[-1]:.1f}× ({len(values)} corruptions)")
        print(f"# load average {os.getloadavg()[0]:.1f} at the end")
    finally:
        shutil.rmtree(folders.root, ignore_errors=True)


if __name__ == "__main__":
    main()
