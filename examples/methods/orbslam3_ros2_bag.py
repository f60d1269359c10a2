#!/usr/bin/env python3
"""ORB-SLAM3 RGB-D (the pyorbslam3 wheel) over the RGB-D camera of a ROS 2 bag (rosbag2 folder).

Usage: orbslam3_ros2_bag.py --dataset BAG --out ESTIMATE.txt [--vocabulary ORBvoc.txt]
                            [--color-topic T] [--depth-topic T] [--camera-info-topic T]

Frames are the colour images, each with the depth image nearest in header stamp (ros2_bag.py);
the topics default to those of `rslam render --format ros2`. The ORB-SLAM3 settings are written
beside the estimate (ESTIMATE.orbslam3.yaml) from the colour CameraInfo and the colour frame
rate, with depth in metres (RGBD.DepthMapFactor 1). The vocabulary defaults to
$ORBSLAM3_VOCABULARY (ORB-SLAM3's Vocabulary/ORBvoc.txt). Writes ORB-SLAM3's own TUM trajectory
of the camera (SaveTrajectoryTUM), stamped with the colour header stamps, the frame of
/ground_truth/pose; frames it lost are not in it.
"""
import os

from orbslam3_common import StateTally, argument_parser, fail, parse_arguments, shut_down_and_exit
from ros2_bag import COLOR_INFO_TOPIC, COLOR_TOPIC, DEPTH_TOPIC, BagError, RgbdBag

# the keys rslam's orbslam3.yaml (TUM layout) has, but depth in metres
SETTINGS = """%YAML:1.0
# ORB-SLAM3 RGB-D settings written by orbslam3_ros2_bag.py from the bag's colour CameraInfo.
File.version: "1.0"

Camera.type: "{camera_type}"
Camera1.fx: {c.fx:.6f}
Camera1.fy: {c.fy:.6f}
Camera1.cx: {c.cx:.6f}
Camera1.cy: {c.cy:.6f}
{lens}
Camera.width: {c.width}
Camera.height: {c.height}
Camera.fps: {fps}
Camera.RGB: 1

Stereo.ThDepth: 40.0
Stereo.b: 0.07
RGBD.DepthMapFactor: 1.0

ORBextractor.nFeatures: 1000
ORBextractor.scaleFactor: 1.2
ORBextractor.nLevels: 8
ORBextractor.iniThFAST: 20
ORBextractor.minThFAST: 7

Viewer.KeyFrameSize: 0.05
Viewer.KeyFrameLineWidth: 1.0
Viewer.GraphLineWidth: 0.9
Viewer.PointSize: 2.0
Viewer.CameraSize: 0.08
Viewer.CameraLineWidth: 3.0
Viewer.ViewpointX: 0.0
Viewer.ViewpointY: -0.7
Viewer.ViewpointZ: -1.8
Viewer.ViewpointF: 500.0
"""


def orbslam3_settings(camera, rate_hz):
    """The settings text for a ros2_bag.Camera at `rate_hz`: PinHole with k1 k2 p1 p2 k3 for a
    plumb_bob lens (or none), KannalaBrandt8 with k1..k4 for an equidistant one; other lens
    models are a ValueError. Every coefficient is written as a real, as ORB-SLAM3 requires."""
    if camera.distortion_model == "equidistant":
        camera_type, names = "KannalaBrandt8", ("k1", "k2", "k3", "k4")
    elif camera.distortion_model == "plumb_bob" or not any(camera.d):
        camera_type, names = "PinHole", ("k1", "k2", "p1", "p2", "k3")
    else:
        raise ValueError(f"lens model '{camera.distortion_model}': ORB-SLAM3 takes plumb_bob or equidistant")
    d = list(camera.d) + [0.0] * len(names)
    lens = "\n".join(f"Camera1.{name}: {float(value):.9e}" for name, value in zip(names, d))
    return SETTINGS.format(camera_type=camera_type, c=camera, lens=lens, fps=round(rate_hz))


def main():
    ap = argument_parser(__doc__, "ros2", settings=False)
    ap.add_argument("--color-topic", default=COLOR_TOPIC, help="colour: Image or CompressedImage")
    ap.add_argument("--depth-topic", default=DEPTH_TOPIC, help="depth registered to colour")
    ap.add_argument("--camera-info-topic", default=COLOR_INFO_TOPIC, help="the colour camera's CameraInfo")
    a = parse_arguments(ap)
    if not os.path.isfile(os.path.join(a.dataset, "metadata.yaml")):
        fail(f"{a.dataset}: no metadata.yaml (this method reads a ROS 2 bag folder)")
    try:
        bag = RgbdBag(a.dataset, a.color_topic, a.depth_topic, a.camera_info_topic)
        if len(bag.pairs) < 2:
            raise BagError(f"{a.dataset}: {len(bag.pairs)} colour images with a depth image within half a "
                           "frame interval; ORB-SLAM3 needs two or more")
        settings_text = orbslam3_settings(bag.camera, bag.rate_hz)
    except (BagError, OSError, ValueError) as e:
        fail(str(e))
    settings = os.path.splitext(a.out)[0] + ".orbslam3.yaml"
    with open(settings, "w") as f:
        f.write(settings_text)

    import pyorbslam3

    slam = pyorbslam3.Slam(a.vocabulary, settings, pyorbslam3.Sensor.RGBD, use_viewer=False)
    states = StateTally()
    try:
        for frame in bag.frames():
            # RGB, as Camera.RGB: 1 says; depth in metres, as RGBD.DepthMapFactor: 1 says
            states.add(slam.track_rgbd(frame.rgb, frame.depth, frame.t))
    except BagError as e:
        fail(str(e), 1)
    states.report(len(bag.pairs))
    shut_down_and_exit(slam, states, lambda: slam.save_trajectory_tum(a.out))


if __name__ == "__main__":
    main()
