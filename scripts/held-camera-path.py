#!/usr/bin/env python3
"""A held camera, as in TUM's fr3 walking_xyz: one pose of a Replica traj.txt held, and moved
along the camera's own x, y and z axes (sines of 0.15, 0.08 and 0.12 m over 5, 3.7 and 6.3 s).
For `rslam render --traj`, e.g. with scripts/validity-actors.sh (TRAJ=...).

Usage: held-camera-path.py IN_traj.txt OUT_traj.txt [--frame 0] [--frames 400] [--rate 30]
"""
import argparse
import math

AMPLITUDES_M = (0.15, 0.08, 0.12)
PERIODS_S = (5.0, 3.7, 6.3)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input")
    ap.add_argument("output")
    ap.add_argument("--frame", type=int, default=0, help="the pose held (a line of IN)")
    ap.add_argument("--frames", type=int, default=400)
    ap.add_argument("--rate", type=float, default=30.0, help="poses a second (TUM's camera: 30)")
    a = ap.parse_args()
    lines = open(a.input).read().splitlines()
    if not 0 <= a.frame < len(lines):
        ap.error(f"{a.input}: {len(lines)} poses, no line {a.frame}")
    m = [float(x) for x in lines[a.frame].split()]
    if len(m) != 16:
        ap.error(f"{a.input}:{a.frame + 1}: {len(m)} numbers, expected 16 (a Replica traj.txt)")
    rotation = [m[0:3], m[4:7], m[8:11]]
    position = [m[3], m[7], m[11]]
    out = []
    for i in range(a.frames):
        t = i / a.rate
        along = [amp * math.sin(2 * math.pi * t / period) for amp, period in zip(AMPLITUDES_M, PERIODS_S)]
        p = [position[k] + sum(rotation[k][j] * along[j] for j in range(3)) for k in range(3)]
        pose = [*rotation[0], p[0], *rotation[1], p[1], *rotation[2], p[2], 0, 0, 0, 1]
        out.append(" ".join("%.9e" % x for x in pose))
    with open(a.output, "w") as f:
        f.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
