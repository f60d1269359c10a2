#!/usr/bin/env python3
"""ORB-SLAM3 stereo or stereo-inertial (the pyorbslam3 wheel) over a dataset in the EuRoC layout.

Usage: orbslam3_stereo.py --dataset DIR --settings DIR/orbslam3_stereo.yaml --out ESTIMATE.txt
                          [--inertial] [--vocabulary ORBvoc.txt]

Stereo pairs are mav0/cam0 and cam1 frames with the same timestamp (data.csv, nanoseconds).
With --inertial (settings: orbslam3_stereo_inertial.yaml) each pair comes with the imu0 samples
since the previous one, as ORB-SLAM3's stereo_inertial_euroc example feeds them. The vocabulary
defaults to $ORBSLAM3_VOCABULARY (ORB-SLAM3's Vocabulary/ORBvoc.txt).

Writes a TUM estimate of the **body** frame (the frame of mav0/state_groundtruth_estimate0): ORB-SLAM3's
SaveTrajectoryEuRoC gives cam0's poses (stereo) or the IMU's (stereo-inertial), which are moved
to the body with cam0's or imu0's T_BS. Times are the data.csv ones in seconds; frames of maps
other than ORB-SLAM3's largest, and frames it lost, are not in it.
"""
import os

import cv2

from euroc_layout import LayoutError, body_trajectory_tum, imu_between_frames, imu_samples, sensor_t_bs, stereo_frames
from orbslam3_common import StateTally, argument_parser, fail, parse_arguments, shut_down_and_exit


def main():
    ap = argument_parser(__doc__, "EuRoC")
    ap.add_argument("--inertial", action="store_true", help="stereo-inertial: feed imu0 too")
    a = parse_arguments(ap)
    needed = ["Stereo.T_c1_c2"] + (["IMU.T_b_c1"] if a.inertial else [])
    settings = cv2.FileStorage(a.settings, cv2.FILE_STORAGE_READ)
    for key in needed:
        if settings.getNode(key).empty():
            fail(f"{a.settings}: no {key} (expected the dataset's orbslam3_stereo{'_inertial' if a.inertial else ''}.yaml)")
    mav = os.path.join(a.dataset, "mav0")
    if not os.path.isdir(mav):
        fail(f"{a.dataset}: no mav0/ (this method reads the EuRoC layout)")
    try:
        frames = stereo_frames(mav)
        times = [t * 1e-9 for t, _, _ in frames]
        imu = imu_between_frames(times, imu_samples(mav)) if a.inertial else [None] * len(frames)
        tracked = "imu0" if a.inertial else "cam0"
        body_from_tracked = sensor_t_bs(os.path.join(mav, tracked, "sensor.yaml"))
    except (LayoutError, OSError) as e:
        fail(str(e))

    import pyorbslam3

    sensor = pyorbslam3.Sensor.IMU_STEREO if a.inertial else pyorbslam3.Sensor.STEREO
    slam = pyorbslam3.Slam(a.vocabulary, a.settings, sensor, use_viewer=False)
    states = StateTally()
    for (_, left_path, right_path), t, samples in zip(frames, times, imu):
        left = cv2.imread(left_path, cv2.IMREAD_UNCHANGED)
        right = cv2.imread(right_path, cv2.IMREAD_UNCHANGED)
        if left is None or right is None:
            fail(f"cannot read {left_path} or {right_path}", 1)
        states.add(slam.track_stereo(left, right, t, samples))
    states.report(len(frames))

    def save():
        raw = a.out + ".orbslam3-euroc"
        slam.save_trajectory_euroc(raw)
        with open(raw) as f:
            lines = body_trajectory_tum(f, body_from_tracked)
        os.remove(raw)
        with open(a.out, "w") as f:
            f.writelines(line + "\n" for line in lines)

    # ORB-SLAM3 starts stereo-inertial tracking only once the mean acceleration of two
    # consecutive frames' IMU samples differs by 0.5 m/s² (Tracking::StereoInitialization)
    hint = ": stereo-inertial starts only once the mean acceleration changes by 0.5 m/s² between two frames"
    shut_down_and_exit(slam, states, save, hint if a.inertial else "")


if __name__ == "__main__":
    main()
