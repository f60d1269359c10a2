#!/usr/bin/env python3
"""ORB-SLAM3 RGB-D (the pyorbslam3 wheel) over an rslam dataset in the TUM layout.

Usage: orbslam3_rgbd.py --dataset DIR --settings DIR/orbslam3.yaml --out ESTIMATE.txt [--vocabulary ORBvoc.txt]

The vocabulary defaults to $ORBSLAM3_VOCABULARY: ORB-SLAM3's Vocabulary/ORBvoc.txt (unpack
ORBvoc.txt.tar.gz from the ORB-SLAM3 repository). Writes ORB-SLAM3's own TUM trajectory
(SaveTrajectoryTUM), stamped with the rgb.txt times; frames it lost are not in it.
"""
import argparse
import os
import sys

import cv2
import numpy as np


def fail(msg, code=2):
    print(f"orbslam3_rgbd: {msg}", file=sys.stderr)
    sys.exit(code)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dataset", required=True, help="dataset folder (TUM layout)")
    ap.add_argument("--settings", required=True, help="ORB-SLAM3 settings (the dataset's orbslam3.yaml)")
    ap.add_argument("--out", required=True, help="estimate to write (TUM trajectory)")
    ap.add_argument("--vocabulary", default=os.environ.get("ORBSLAM3_VOCABULARY"),
                    help="ORBvoc.txt (default: $ORBSLAM3_VOCABULARY)")
    a = ap.parse_args()  # exits 2 on bad arguments

    if not a.vocabulary or not os.path.isfile(a.vocabulary):
        fail(f"no ORB vocabulary at {a.vocabulary!r}: set ORBSLAM3_VOCABULARY or --vocabulary to ORBvoc.txt")
    if not os.path.isfile(a.settings):
        fail(f"no settings file {a.settings}")
    assoc = os.path.join(a.dataset, "associations.txt")
    if not os.path.isfile(assoc):
        fail(f"{a.dataset}: no associations.txt (this method reads the TUM layout)")
    frames = []
    with open(assoc) as f:
        for line in f:
            r = line.split()
            if r and not r[0].startswith("#"):
                frames.append((float(r[0]), os.path.join(a.dataset, r[1]), os.path.join(a.dataset, r[3])))
    if not frames:
        fail(f"{assoc}: no frames")
    # Camera.RGB: 1 (what rslam writes) says the colour images come in RGB order
    settings = cv2.FileStorage(a.settings, cv2.FILE_STORAGE_READ)
    rgb_order = settings.getNode("Camera.RGB").real() == 1

    import pyorbslam3

    slam = pyorbslam3.Slam(a.vocabulary, a.settings, pyorbslam3.Sensor.RGBD, use_viewer=False)
    states = {}
    for t, rgb_path, depth_path in frames:
        bgr = cv2.imread(rgb_path, cv2.IMREAD_COLOR)
        depth = cv2.imread(depth_path, cv2.IMREAD_UNCHANGED)
        if bgr is None or depth is None:
            fail(f"cannot read {rgb_path} or {depth_path}", 1)
        image = cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB) if rgb_order else bgr
        # raw depth units as float32: ORB-SLAM3 divides by RGBD.DepthMapFactor itself
        state = slam.track_rgbd(image, depth.astype(np.float32), t).state
        states[state.name] = states.get(state.name, 0) + 1
    slam.shutdown()
    slam.save_trajectory_tum(a.out)
    print(f"{len(frames)} frames, tracking states {states}", file=sys.stderr)
    sys.stderr.flush()
    # ORB-SLAM3's threads can hang at interpreter exit
    os._exit(0)


if __name__ == "__main__":
    main()
