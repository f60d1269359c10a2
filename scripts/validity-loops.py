#!/usr/bin/env python3
"""What loop closure does to a validity run: for each setting of a validity.sh work folder, how
many ORB-SLAM3 runs closed a loop ("Loop detected" in the run's log), and the ATE (RMSE, SE3,
`rslam eval`) of the first FRAMES frames twice: as tracked (the pose each track call returned,
runN.online.txt) and in the trajectory saved at the end (runN.txt, after any loop correction and
global bundle adjustment), each aligned over those frames alone, beside the saved trajectory's ATE
over all its frames. A by-hand look for the book (docs/src/validity.md), not part of the protocol.

Usage: validity-loops.py WORK/SCENE [FRAMES]     (FRAMES: 400; RSLAM: target/release/rslam)
  WORK/SCENE: a folder written by scripts/validity-ranking.sh (runs/SETTING/runN.*)
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

RSLAM = os.environ.get("RSLAM", str(Path(__file__).resolve().parent.parent / "target/release/rslam"))


def ate_cm(est: Path, gt: Path, frames: int | None) -> float | None:
    """ATE RMSE in cm of est against gt over gt's first `frames` poses (all when None); None where
    `rslam eval` finds nothing to align (a run that lost tracking at the start)."""
    with tempfile.TemporaryDirectory() as tmp:
        if frames is not None:
            gt_lines = gt.read_text().splitlines(keepends=True)[:frames]
            last_t = float(gt_lines[-1].split()[0])
            est_lines = [line for line in est.read_text().splitlines(keepends=True) if float(line.split()[0]) <= last_t]
            est, gt = Path(tmp, "est.txt"), Path(tmp, "gt.txt")
            est.write_text("".join(est_lines))
            gt.write_text("".join(gt_lines))
        out = subprocess.run([RSLAM, "eval", str(est), str(gt), "--json"], capture_output=True, text=True)
    if out.returncode != 0:
        return None
    return 100 * json.loads(out.stdout)["ate"]["rmse"]


def cell(values: list[float | None]) -> str:
    known = [v for v in values if v is not None]
    if not known:
        return "no estimate"
    runs = " / ".join("no estimate" if v is None else f"{v:.2f}" for v in values)
    return f"{statistics.median(known):.2f} ({runs})"


def main() -> None:
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    root = Path(sys.argv[1]) / "runs"
    frames = int(sys.argv[2]) if len(sys.argv) == 3 else 400
    if not root.is_dir():
        sys.exit(f"{root}: not a folder (expected the runs of a validity.sh work folder)")
    print(f"| setting | runs that closed a loop | first {frames} frames as tracked (cm) "
          f"| first {frames} frames, saved (cm) | all frames, saved (cm) |")
    print("|---|---|---|---|---|")
    for setting in sorted(root.iterdir(), key=lambda d: (not d.name.startswith("clean"), d.name)):
        tracked, saved, whole, closed, finished = [], [], [], 0, 0
        for log in sorted(setting.glob("run*.log")):
            run = log.with_suffix("")
            est, online, gt = Path(f"{run}.txt"), Path(f"{run}.online.txt"), Path(f"{run}.gt.txt")
            if not est.is_file() or est.stat().st_size == 0:
                continue
            finished += 1
            closed += "Loop detected" in log.read_text(errors="replace")
            tracked.append(ate_cm(online, gt, frames))
            saved.append(ate_cm(est, gt, frames))
            whole.append(ate_cm(est, gt, None))
        if finished:
            name = setting.name.removesuffix("_full").replace("-", ":")
            print(f"| {name} | {closed} of {finished} | {cell(tracked)} | {cell(saved)} | {cell(whole)} |")


if __name__ == "__main__":
    main()
