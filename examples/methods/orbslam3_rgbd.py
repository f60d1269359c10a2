#!/usr/bin/env python3
"""ORB-SLAM3 RGB-D (the pyorbslam3 wheel) over an rslam dataset in the TUM layout.

Usage: orbslam3_rgbd.py --dataset DIR --settings DIR/orbslam3.yaml --out ESTIMATE.txt [--vocabulary ORBvoc.txt]

The vocabulary defaults to $ORBSLAM3_VOCABULARY: ORB-SLAM3's Vocabulary/ORBvoc.txt (unpack
ORBvoc.txt.tar.gz from the ORB-SLAM3 repository). Writes ORB-SLAM3's own TUM trajectory
(SaveTrajectoryTUM), stamped with the rgb.txt times; frames it lost are not in it.
"""
import os

import cv2
import numpy as np

from orbslam3_common import StateTally, argument_parser, fail, parse_arguments, shut_down_and_exit


def main():
    a = parse_arguments(argument_parser(__doc__, "TUM"))
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
    states = StateTally()
    for t, rgb_path, depth_path in frames:
        bgr = cv2.imread(rgb_path, cv2.IMREAD_COLOR)
        depth = cv2.imread(depth_path, cv2.IMREAD_UNCHANGED)
        if bgr is None or depth is None:
            fail(f"cannot read {rgb_path} or {depth_path}", 1)
        image = cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB) if rgb_order else bgr
        # raw depth units as float32: ORB-SLAM3 divides by RGBD.DepthMapFactor itself
        states.add(slam.track_rgbd(image, depth.astype(np.float32), t))
    states.report(len(frames))
    shut_down_and_exit(slam, states, lambda: slam.save_trajectory_tum(a.out))


if __name__ == "__main__":
    main()
