"""Tests of ros2_bag.py and the settings of orbslam3_ros2_bag.py (no ORB-SLAM3 needed):
python3 -m unittest discover -s examples/methods. The bags are written here with rosbags' own
writer (MCAP storage); with RSLAM_BIN=/path/to/rslam, a bag `rslam render --format ros2` writes
is read too."""
import json
import os
import subprocess
import tempfile
import unittest
from pathlib import Path

import cv2
import numpy as np
from rosbags.rosbag2 import StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore

from orbslam3_ros2_bag import orbslam3_settings
from ros2_bag import BagError, Camera, RgbdBag, pair_by_stamp

TYPES = get_typestore(Stores.ROS2_HUMBLE)
MS = 1_000_000  # nanoseconds


def header(t_ns):
    time = TYPES.types["builtin_interfaces/msg/Time"](sec=t_ns // 10**9, nanosec=t_ns % 10**9)
    return TYPES.types["std_msgs/msg/Header"](stamp=time, frame_id="camera_color_optical_frame")


def image(t_ns, encoding, pixels, step=None, bigendian=False):
    """An Image of HxW(xC) `pixels`, rows padded to `step` bytes."""
    height, width = pixels.shape[:2]
    ordered = pixels.astype(pixels.dtype.newbyteorder(">" if bigendian else "<"))
    rows = ordered.reshape(height, -1).view(np.uint8)
    step = step or rows.shape[1]
    data = np.zeros((height, step), np.uint8)
    data[:, :rows.shape[1]] = rows
    return TYPES.types["sensor_msgs/msg/Image"](header=header(t_ns), height=height, width=width, encoding=encoding,
                                                 is_bigendian=int(bigendian), step=step, data=data.ravel())


def compressed_png(t_ns, rgb):
    _, png = cv2.imencode(".png", cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR))
    return TYPES.types["sensor_msgs/msg/CompressedImage"](header=header(t_ns), format="png", data=png.ravel())


def camera_info(t_ns, width, height):
    info = TYPES.types["sensor_msgs/msg/CameraInfo"]
    roi = TYPES.types["sensor_msgs/msg/RegionOfInterest"](x_offset=0, y_offset=0, height=0, width=0, do_rectify=False)
    return info(header=header(t_ns), height=height, width=width, distortion_model="plumb_bob",
                d=np.array([-0.1, 0.01, 0.001, -0.002, 0.0]), k=np.array([50.0, 0, 31.5, 0, 51.0, 23.5, 0, 0, 1]),
                r=np.eye(3).ravel(), p=np.zeros(12), binning_x=0, binning_y=0, roi=roi)


def write_bag(path, messages):
    """A rosbag2 folder in MCAP storage of [(topic, message)], each logged at its header stamp,
    in this order."""
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        connections = {}
        for topic, message in messages:
            if topic not in connections:
                connections[topic] = writer.add_connection(topic, message.__msgtype__, typestore=TYPES)
            stamp = message.header.stamp
            raw = TYPES.serialize_cdr(message, message.__msgtype__)
            writer.write(connections[topic], stamp.sec * 10**9 + stamp.nanosec, raw)


def colour(seed, width=8, height=6):
    return np.random.default_rng(seed).integers(0, 256, (height, width, 3), dtype=np.uint8)


class Pairing(unittest.TestCase):
    def test_each_colour_stamp_takes_the_nearest_depth_within_half_the_median_interval(self):
        # colour every 50 ms: 25 ms tolerance; 100 ms is 40 ms from either depth, 200 ms 60 ms
        pairs = pair_by_stamp([t * MS for t in (200, 0, 50, 100, 150)], [t * MS for t in (10, 60, 140, 260)])
        self.assertEqual(pairs, [(0, 10 * MS), (50 * MS, 60 * MS), (150 * MS, 140 * MS)])

    def test_one_depth_may_serve_two_colour_images(self):
        pairs = pair_by_stamp([t * MS for t in (0, 10, 60, 110, 160)], [5 * MS])
        self.assertEqual(pairs, [(0, 5 * MS), (10 * MS, 5 * MS)])


class Reading(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.bag = Path(self.dir.name, "bag")

    def tearDown(self):
        self.dir.cleanup()

    def test_rgb8_and_16uc1_millimetres_with_padded_rows_and_a_colour_image_without_depth(self):
        depth_mm = np.array([[0, 1500, 65535, 1]] * 3, dtype=np.uint16)
        write_bag(self.bag, [
            ("/camera/color/camera_info", camera_info(0, 4, 3)),
            ("/camera/color/image_raw", image(0, "rgb8", colour(0, 4, 3), step=16)),
            ("/camera/depth/image_raw", image(2 * MS, "16UC1", depth_mm, bigendian=True)),
            ("/camera/color/image_raw", image(50 * MS, "rgb8", colour(1, 4, 3), step=16)),
            ("/camera/depth/image_raw", image(48 * MS, "16UC1", depth_mm[::-1, ::-1])),
            ("/camera/color/image_raw", image(100 * MS, "rgb8", colour(2, 4, 3), step=16)),
            ("/camera/depth/image_raw", image(130 * MS, "16UC1", depth_mm)),
        ])
        bag = RgbdBag(self.bag)
        lens = ("plumb_bob", (-0.1, 0.01, 0.001, -0.002, 0.0))
        self.assertEqual(bag.camera, Camera(50.0, 51.0, 31.5, 23.5, 4, 3, *lens))
        self.assertAlmostEqual(bag.rate_hz, 20.0)
        frames = list(bag.frames())
        self.assertEqual([f.t for f in frames], [0.0, 0.05])  # 100 ms: the nearest depth is 30 ms away
        np.testing.assert_array_equal(frames[1].rgb, colour(1, 4, 3))
        self.assertEqual((frames[0].rgb.dtype, frames[0].depth.dtype), (np.uint8, np.float32))
        np.testing.assert_array_equal(frames[0].depth[0], np.float32([0, 1.5, 65.535, 0.001]))
        np.testing.assert_array_equal(frames[1].depth, frames[0].depth[::-1, ::-1])

    def test_bgr8_and_32fc1_metres_on_other_topics_logged_out_of_stamp_order(self):
        depth_m = np.array([[np.nan, 0.75, np.inf, 2.0]] * 3, dtype=np.float32)
        topics = {"color_topic": "/rgb", "depth_topic": "/aligned_depth", "info_topic": "/rgb_info"}
        write_bag(self.bag, [("/rgb_info", camera_info(0, 4, 3))]
                  # depth first, newest first; colour stamps 0, 10, 60, 110 ms (50 ms median interval)
                  + [("/aligned_depth", image(t * MS, "32FC1", depth_m * t)) for t in (140, 62, 5)]
                  + [("/rgb", image(t * MS, "bgr8", colour(t, 4, 3)[..., ::-1])) for t in (0, 10, 60, 110)])
        frames = list(RgbdBag(self.bag, **topics).frames())
        self.assertEqual([round(f.t, 9) for f in frames], [0.0, 0.01, 0.06])  # 110 ms: 30 ms from 140
        np.testing.assert_array_equal(frames[2].rgb, colour(60, 4, 3))
        # NaN and Inf are no depth; the 5 ms depth serves the colour images at 0 and 10 ms
        np.testing.assert_array_equal(frames[0].depth[0], np.float32([0, 0.75 * 5, 0, 2.0 * 5]))
        np.testing.assert_array_equal(frames[1].depth, frames[0].depth)
        np.testing.assert_array_equal(frames[2].depth[0], np.float32([0, 0.75 * 62, 0, 2.0 * 62]))

    def test_compressed_png_and_mono8_colour(self):
        write_bag(self.bag, [
            ("/camera/color/camera_info", camera_info(0, 8, 6)),
            ("/camera/color/image_raw", compressed_png(0, colour(0))),
            ("/camera/depth/image_raw", image(0, "16UC1", np.full((6, 8), 900, np.uint16))),
            ("/camera/color/image_raw", compressed_png(50 * MS, colour(1))),
            ("/camera/depth/image_raw", image(50 * MS, "16UC1", np.full((6, 8), 1000, np.uint16))),
        ])
        frames = list(RgbdBag(self.bag).frames())
        np.testing.assert_array_equal(frames[1].rgb, colour(1))
        np.testing.assert_array_equal(frames[0].depth, np.full((6, 8), 0.9, np.float32))

        grey = colour(2)[..., 0]
        write_bag(Path(self.dir.name, "mono"), [
            ("/camera/color/camera_info", camera_info(0, 8, 6)),
            ("/camera/color/image_raw", image(0, "mono8", grey)),
            ("/camera/depth/image_raw", image(0, "16UC1", np.zeros((6, 8), np.uint16))),
        ])
        frame, = RgbdBag(Path(self.dir.name, "mono")).frames()
        np.testing.assert_array_equal(frame.rgb, np.stack([grey] * 3, axis=2))

    def test_an_unknown_encoding_or_topic_is_named(self):
        write_bag(self.bag, [
            ("/camera/color/camera_info", camera_info(0, 4, 3)),
            ("/camera/color/image_raw", image(0, "yuv422", colour(0, 4, 3)[..., :2])),
            ("/camera/depth/image_raw", image(0, "16UC1", np.zeros((3, 4), np.uint16))),
        ])
        with self.assertRaisesRegex(BagError, "/camera/color/image_raw: encoding 'yuv422' is not one this reader"):
            list(RgbdBag(self.bag).frames())
        with self.assertRaisesRegex(BagError, "/camera/aligned_depth: not a topic of the bag"):
            RgbdBag(self.bag, depth_topic="/camera/aligned_depth")


class Settings(unittest.TestCase):
    def test_orbslam3_reads_the_camera_and_depth_in_metres_as_reals(self):
        camera = Camera(50.0, 51.0, 31.5, 23.5, 64, 48, "plumb_bob", (-0.1, 0.0, 0.001, -0.002, 0.0))
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "orbslam3.yaml")
            with open(path, "w") as f:
                f.write(orbslam3_settings(camera, 19.8))
            # ORB-SLAM3 reads its settings with cv::FileStorage and wants reals where it reads floats
            settings = cv2.FileStorage(path, cv2.FILE_STORAGE_READ)
            self.assertEqual(settings.getNode("Camera.type").string(), "PinHole")
            for key, value in [("Camera1.fy", 51.0), ("Camera1.k1", -0.1), ("Camera1.k2", 0.0),
                               ("Camera1.p2", -0.002), ("RGBD.DepthMapFactor", 1.0)]:
                self.assertTrue(settings.getNode(key).isReal(), key)
                self.assertAlmostEqual(settings.getNode(key).real(), value)
            integers = [settings.getNode(k).real() for k in ("Camera.width", "Camera.fps", "Camera.RGB")]
            self.assertEqual(integers, [64, 20, 1])
        with self.assertRaisesRegex(ValueError, "lens model 'rational_polynomial'"):
            orbslam3_settings(Camera(50, 50, 32, 24, 64, 48, "rational_polynomial", (0.1,) * 8), 20)


@unittest.skipUnless(os.environ.get("RSLAM_BIN"), "set RSLAM_BIN to an rslam binary to read a bag it renders")
class RenderedBag(unittest.TestCase):
    def test_a_rendered_bag_reads_as_the_tum_layout_of_the_same_job(self):
        job = ["render", "--scene", "room0", "--frames", "30", "--camera", "64,48,50,50,31.5,23.5"]
        with tempfile.TemporaryDirectory() as d:
            for layout in ("ros2", "tum"):
                subprocess.run([os.environ["RSLAM_BIN"], *job, "--format", layout, "--out", os.path.join(d, layout)],
                               check=True, capture_output=True)
            bag = RgbdBag(os.path.join(d, "ros2"))
            frames = list(bag.frames())
            tum = Path(d, "tum")
            rows = [line.split() for line in (tum / "associations.txt").read_text().splitlines()
                    if line and not line.startswith("#")]
            camera = json.loads((tum / "rslam.json").read_text())["camera"]
            self.assertEqual((bag.camera.fx, bag.camera.fy, bag.camera.cx, bag.camera.cy, bag.camera.width,
                              bag.camera.height), tuple(camera[k] for k in ("fx", "fy", "cx", "cy", "width", "height")))
            self.assertEqual(len(frames), 30)
            self.assertEqual([round(f.t, 6) for f in frames], [float(row[0]) for row in rows])
            for frame, (_, rgb, _, depth) in zip(frames, rows):
                png = cv2.cvtColor(cv2.imread(str(tum / rgb)), cv2.COLOR_BGR2RGB)
                np.testing.assert_array_equal(frame.rgb, png)
                # TUM depth is in 1/5000 m, the bag's in millimetres
                tum_depth = cv2.imread(str(tum / depth), cv2.IMREAD_UNCHANGED) / 5000.0
                np.testing.assert_allclose(frame.depth, tum_depth, atol=0.0006)


if __name__ == "__main__":
    unittest.main()
