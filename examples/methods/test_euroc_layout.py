"""Tests of euroc_layout.py (no ORB-SLAM3 needed): python3 -m unittest discover -s examples/methods"""
import math
import os
import tempfile
import unittest

import numpy as np

from euroc_layout import (LayoutError, body_trajectory_tum, imu_between_frames, sensor_t_bs,
                          stereo_frames)


def write(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


class ImuBetweenFrames(unittest.TestCase):
    def test_samples_go_with_the_frame_that_ends_their_interval_as_orbslam3s_example_gives_them(self):
        imu = np.array([[t, 0, 0, 0, 0, 0, 9.81] for t in (0.040, 0.045, 0.050, 0.055, 0.100, 0.105, 0.150)])
        batches = imu_between_frames([0.050, 0.100, 0.150], imu)
        times = [list(b[:, 0]) for b in batches]
        # none with the first frame; from the last sample at or before it up to each frame's time
        self.assertEqual(times, [[], [0.050, 0.055, 0.100], [0.105, 0.150]])

    def test_a_tolerance_takes_a_row_just_after_a_rounded_frame_stamp_as_at_it(self):
        # TUM stamps keep 6 decimals: frames at 1/30 s multiples, IMU rows at whole nanoseconds
        imu = np.array([[t, 0, 0, 0, 0, 0, 9.81] for t in (0.0333333, 0.0383333, 0.0666667)])
        frames = [0.033333, 0.066667]
        with self.assertRaises(LayoutError):
            imu_between_frames(frames, imu)
        batches = imu_between_frames(frames, imu, tolerance_s=1e-6)
        self.assertEqual([list(b[:, 0]) for b in batches], [[], [0.0333333, 0.0383333, 0.0666667]])

    def test_an_imu_that_does_not_cover_the_frames_is_refused(self):
        imu = np.array([[t, 0, 0, 0, 0, 0, 9.81] for t in (0.06, 0.07, 0.2)])
        with self.assertRaisesRegex(LayoutError, "imu0 covers 0.060-0.200 s, the frames 0.050-0.100 s"):
            imu_between_frames([0.05, 0.10], imu)


class BodyTrajectory(unittest.TestCase):
    def test_poses_move_to_the_body_and_times_to_seconds(self):
        # the tracked frame sits 1 m along the body's x axis, turned 90° about z
        body_from_frame = np.array([[0.0, -1, 0, 1], [1, 0, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]])
        s = math.sqrt(0.5)
        # world-from-frame: at (2, 3, 4), turned 90° about z (q = (0, 0, s, s))
        lines = body_trajectory_tum([f"1500000000.000000 2 3 4 0 0 {s} {s}\n"], body_from_frame)
        t, x, y, z, qx, qy, qz, qw = (float(v) for v in lines[0].split())
        # world_from_body = world_from_frame · frame_from_body: the turns cancel, and the body
        # is 1 m behind the frame along its own x axis, which is then the world's
        self.assertAlmostEqual(t, 1.5)
        np.testing.assert_allclose([x, y, z], [1, 3, 4], atol=1e-9)
        np.testing.assert_allclose([qx, qy, qz, qw], [0, 0, 0, 1], atol=1e-9)

    def test_a_short_line_names_its_number(self):
        with self.assertRaisesRegex(LayoutError, "line 2: 7 fields, expected 8"):
            body_trajectory_tum(["0 0 0 0 0 0 0 1", "0 0 0 0 0 0 1"], np.eye(4))


class Files(unittest.TestCase):
    def test_t_bs_is_read_from_a_euroc_sensor_yaml(self):
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "sensor.yaml")
            write(path, "sensor_type: camera\nT_BS:\n  cols: 4\n  rows: 4\n  data: [0.0, -1.0, 0.0, 0.1,\n"
                        "         1.0, 0.0, 0.0, 0.2,\n         0.0, 0.0, 1.0, 0.3,\n         0.0, 0.0, 0.0, 1.0]\n"
                        "intrinsics: [458.6, 457.3, 367.2, 248.4]\n")
            np.testing.assert_array_equal(sensor_t_bs(path)[:3, 3], [0.1, 0.2, 0.3])
            write(path, "T_BS:\n  data: [1.0, 0.0, 0.0]\n")
            with self.assertRaisesRegex(LayoutError, "T_BS has 3 numbers, expected 16"):
                sensor_t_bs(path)

    def test_stereo_pairs_are_the_timestamps_both_cameras_have(self):
        with tempfile.TemporaryDirectory() as mav:
            header = "#timestamp [ns],filename\n"
            write(os.path.join(mav, "cam0", "data.csv"), header + "200,200.png\n100,100.png\n300,300.png\n")
            write(os.path.join(mav, "cam1", "data.csv"), header + "100,100.png\n200,200.png\n")
            pairs = stereo_frames(mav)
            self.assertEqual([t for t, _, _ in pairs], [100, 200])
            self.assertEqual(pairs[0][2], os.path.join(mav, "cam1", "data", "100.png"))
            write(os.path.join(mav, "cam1", "data.csv"), header + "100,100.png\n2e2,200.png\n")
            with self.assertRaisesRegex(LayoutError, r"cam1/data.csv:3: timestamp '2e2' is not integer nanoseconds"):
                stereo_frames(mav)


if __name__ == "__main__":
    unittest.main()
