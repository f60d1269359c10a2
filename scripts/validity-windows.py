#!/usr/bin/env python3
"""Where along the path a corruption costs ORB-SLAM3: for each run of SETTING in a validity.sh work
folder, the ATE (RMSE, cm) of each stretch of WINDOW frames over the clean runs' median of the
same stretch, each run aligned once over all its frames (SE3, the alignment `rslam eval` reports),
so a stretch's error is its share of the whole run's. A by-hand look for the book
(docs/src/validity.md), not part of the protocol.

Usage: validity-windows.py WORK/SCENE SETTING [WINDOW]   (WINDOW: 250; RSLAM: target/release/rslam)
  WORK/SCENE: a folder written by scripts/validity-ranking.sh (runs/SETTING_full/runN.*)
  SETTING: as the table names it, e.g. jpeg_compression:3
"""
import json
import math
import os
import statistics
import subprocess
import sys
from pathlib import Path

RSLAM = os.environ.get("RSLAM", str(Path(__file__).resolve().parent.parent / "target/release/rslam"))
# rslam eval's default --max-diff: the largest timestamp difference of an associated pair.
MAX_DIFF_S = 0.01


def positions(path: Path) -> list[tuple[float, tuple[float, float, float]]]:
    """(timestamp, position) of each pose of a TUM trajectory file."""
    poses = []
    for line in path.read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            v = [float(x) for x in line.split()]
            poses.append((v[0], (v[1], v[2], v[3])))
    return poses


def stretch_ates_cm(est: Path, gt: Path, window: int) -> list[float | None] | None:
    """The ATE RMSE in cm of each stretch of `window` ground-truth poses (None where the run
    left no pose in it); None where `rslam eval` finds nothing to align."""
    out = subprocess.run([RSLAM, "eval", str(est), str(gt), "--json"], capture_output=True, text=True)
    if out.returncode != 0:
        return None
    report = json.loads(out.stdout)
    rotation, translation = report["alignment"]["rotation"], report["alignment"]["translation"]
    scale = report["alignment"]["scale"]
    truth = positions(gt)
    squares: list[list[float]] = [[] for _ in range(math.ceil(len(truth) / window))]
    j = 0
    for t, p in positions(est):
        while j + 1 < len(truth) and abs(truth[j + 1][0] - t) <= abs(truth[j][0] - t):
            j += 1
        if abs(truth[j][0] - t) > MAX_DIFF_S:
            continue
        moved = [scale * sum(rotation[r][c] * p[c] for c in range(3)) + translation[r] for r in range(3)]
        squares[j // window].append(sum((m - q) ** 2 for m, q in zip(moved, truth[j][1])))
    whole = [s for stretch in squares for s in stretch]
    if abs(math.sqrt(sum(whole) / len(whole)) - report["ate"]["rmse"]) > 1e-6:
        sys.exit(f"{est}: the stretches do not add up to rslam eval's ATE (association differs)")
    return [100 * math.sqrt(sum(s) / len(s)) if s else None for s in squares]


def runs(folder: Path, window: int) -> list[tuple[str, list[float | None]]]:
    """(runN, its stretches) of each run in `folder` that saved a trajectory, found by its log as
    validity-loops.py finds them."""
    found = []
    for log in sorted(folder.glob("run*.log")):
        run = log.with_suffix("")
        est, gt = Path(f"{run}.txt"), Path(f"{run}.gt.txt")
        if not est.is_file() or est.stat().st_size == 0:
            continue
        stretches = stretch_ates_cm(est, gt, window)
        if stretches is not None:
            found.append((run.name, stretches))
    return found


def main() -> None:
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    root = Path(sys.argv[1]) / "runs"
    setting = sys.argv[2].replace(":", "-") + "_full"
    window = int(sys.argv[3]) if len(sys.argv) == 4 else 250
    for folder in (root / "clean_full", root / setting):
        if not folder.is_dir():
            sys.exit(f"{folder}: not a folder (expected the runs of a whole-path validity work folder)")
    clean = runs(root / "clean_full", window)
    if not clean:
        sys.exit(f"{root / 'clean_full'}: no clean run finished")
    baseline = [
        statistics.median(v for v in column if v is not None) for column in zip(*(s for _, s in clean))
    ]
    print(f"clean median per stretch of {window} frames (cm): " + " ".join(f"{b:.2f}" for b in baseline))
    print("| run | × clean, stretch by stretch | median stretch |\n|---|---|---|")
    for name, stretches in runs(root / setting, window):
        ratios = [s / b if s is not None else None for s, b in zip(stretches, baseline)]
        known = [r for r in ratios if r is not None]
        cells = " ".join("—" if r is None else f"{r:.1f}" for r in ratios)
        print(f"| {name} | {cells} | {statistics.median(known):.2f} |")


if __name__ == "__main__":
    main()
