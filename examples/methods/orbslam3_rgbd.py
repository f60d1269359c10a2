#!/usr/bin/env python3
"""ORB-SLAM3 RGB-D or RGB-D-inertial (the pyorbslam3 wheel) over an rslam dataset in the TUM layout.

Usage: orbslam3_rgbd.py --dataset DIR --settings DIR/orbslam3.yaml --out ESTIMATE.txt
                        [--inertial] [--vocabulary ORBvoc.txt]

With --inertial (settings: orbslam3_rgbd_inertial.yaml, a `render --rig rgbd-imu --format tum`
dataset) ORB-SLAM3 runs as IMU_RGBD and each frame comes with the imu0/data.csv samples since
the previous one, as the stereo-inertial example feeds them. The vocabulary defaults to
$ORBSLAM3_VOCABULARY: ORB-SLAM3's Vocabulary/ORBvoc.txt (unpack ORBvoc.txt.tar.gz from the
ORB-SLAM3 repository). Writes ORB-SLAM3's own TUM trajectory of the camera (SaveTrajectoryTUM),
stamped with the rgb.txt times, the frame of groundtruth.txt; frames it lost are not in it.
"""
import os

import cv2
import numpy as np

from euroc_layout import LayoutError, imu_between_frames, imu_samples
from orbslam3_common import StateTally, argument_parser, fail, parse_arguments, shut_down_and_exit


def main():
    ap = argument_parser(__doc__, "TUM")
    ap.add_argument("--inertial", action="store_true", help="RGB-D-inertial: feed imu0/data.csv too")
    a = parse_arguments(ap)
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
    imu = [None] * len(frames)
    if a.inertial:
        if settings.getNode("IMU.T_b_c1").empty():
            fail(f"{a.settings}: no IMU.T_b_c1 (expected the dataset's orbslam3_rgbd_inertial.yaml)")
        try:
            # the dataset root holds imu0/ as a EuRoC mav0/ does; rgb.txt stamps keep 6 decimals
            imu = imu_between_frames([t for t, _, _ in frames], imu_samples(a.dataset), tolerance_s=1e-6)
        except (LayoutError, OSError) as e:
            fail(str(e))

    import pyorbslam3

    sensor = pyorbslam3.Sensor.IMU_RGBD if a.inertial else pyorbslam3.Sensor.RGBD
    slam = pyorbslam3.Slam(a.vocabulary, a.settings, sensor, use_viewer=False)
    states = StateTally()
    for (t, rgb_path, depth_path), samples in zip(frames, imu):
        bgr = cv2.imread(rgb_path, cv2.IMREAD_COLOR)
        depth = cv2.imread(depth_path, cv2.IMREAD_UNCHANGED)
        if bgr is None or depth is None:
            fail(f"cannot read {rgb_path} or {depth_path}", 1)
        image = cv2.cvtColor(bgr, cv2.COLOR_BGR2RGB) if rgb_order else bgr
        # raw depth units as float32: ORB-SLAM3 divides by RGBD.DepthMapFactor itself
        states.add(slam.track_rgbd(image, depth.astype(np.float32), t, samples))
    states.report(len(frames))
    shut_down_and_exit(slam, states, lambda: slam.save_trajectory_tum(a.out))


if __name__ == "__main__":
    main()
