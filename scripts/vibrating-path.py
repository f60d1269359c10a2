#!/usr/bin/env python3
"""A Replica traj.txt with a MAV-like vibration added to every position, for rig renders that a
visual-inertial system must be able to initialise on (ORB-SLAM3's stereo-inertial mode waits for
a 0.5 m/s² change of mean acceleration between frames, which a smooth hand-held path never gives).

Usage: vibrating-path.py IN_traj.txt OUT_traj.txt [--rate 20] [--amplitude 0.005] [--seed 1]

Per world axis, three sinusoids of 1.7, 2.3 and 2.9 Hz, each of AMPLITUDE metres with a phase
drawn from SEED (numpy's default_rng); orientations are kept. Poses are at RATE Hz.
"""
import argparse

import numpy as np

FREQUENCIES_HZ = (1.7, 2.3, 2.9)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("input")
    ap.add_argument("output")
    ap.add_argument("--rate", type=float, default=20.0)
    ap.add_argument("--amplitude", type=float, default=0.005)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    poses = np.loadtxt(a.input, ndmin=2)
    if poses.shape[1] != 16:
        ap.error(f"{a.input}: {poses.shape[1]} numbers a line, expected 16 (a Replica traj.txt)")
    t = np.arange(len(poses)) / a.rate
    rng = np.random.default_rng(a.seed)
    poses = poses.reshape(-1, 4, 4)
    for axis in range(3):
        for f in FREQUENCIES_HZ:
            poses[:, axis, 3] += a.amplitude * np.sin(2 * np.pi * f * t + rng.uniform(0, 2 * np.pi))
    np.savetxt(a.output, poses.reshape(-1, 16), fmt="%.9f")


if __name__ == "__main__":
    main()
