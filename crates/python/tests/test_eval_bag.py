"""`rslam eval` reading an estimate or a ground truth from a ROS 2 bag written by `rosbags`:
Odometry, PoseWithCovarianceStamped and PoseStamped topics and a TF child frame give the poses
they hold (checked against the same poses in a TUM file), and an ambiguous or missing topic is
refused naming the bag's pose topics."""

import json
import subprocess

import numpy as np
from rosbags.typesys import Stores, get_typestore

from conftest import run_cli
from test_perturb_bag import header, write_bag

T = get_typestore(Stores.ROS2_HUMBLE).types
START_NS = 1_700_000_000_000_000_000
STEP_NS = 50_000_000
N = 40


def path_pose(i):
    """A curving path with a turning heading: position and quaternion (x y z w)."""
    s = i / N
    position = np.array([np.cos(3 * s), np.sin(3 * s), 0.2 * s])
    yaw = 3 * s + 0.3
    return position, np.array([0.0, 0.0, np.sin(yaw / 2), np.cos(yaw / 2)])


def pose_message(i):
    p, q = path_pose(i)
    point = T["geometry_msgs/msg/Point"](x=p[0], y=p[1], z=p[2])
    quaternion = T["geometry_msgs/msg/Quaternion"](x=q[0], y=q[1], z=q[2], w=q[3])
    return T["geometry_msgs/msg/Pose"](position=point, orientation=quaternion)


def with_covariance(i):
    return T["geometry_msgs/msg/PoseWithCovariance"](pose=pose_message(i), covariance=np.arange(36.0))


def odometry(t, i):
    v = T["geometry_msgs/msg/Vector3"](x=0.5, y=0.0, z=0.0)
    twist = T["geometry_msgs/msg/TwistWithCovariance"](
        twist=T["geometry_msgs/msg/Twist"](linear=v, angular=v), covariance=np.zeros(36))
    return T["nav_msgs/msg/Odometry"](header=header(t, "odom"), child_frame_id="base_link",
                                      pose=with_covariance(i), twist=twist)


def tf(t, i):
    pose = pose_message(i)
    translation = T["geometry_msgs/msg/Vector3"](x=pose.position.x, y=pose.position.y, z=pose.position.z)
    to_child = lambda child, tr: T["geometry_msgs/msg/TransformStamped"](
        header=header(t, "odom"), child_frame_id=child,
        transform=T["geometry_msgs/msg/Transform"](translation=tr, rotation=pose.orientation))
    other = T["geometry_msgs/msg/Vector3"](x=9.0, y=9.0, z=9.0)
    return T["tf2_msgs/msg/TFMessage"](transforms=[to_child("camera_link", other), to_child("base_link", translation)])


def robot_trajectories(path):
    """One bag with the same path as Odometry, PoseWithCovarianceStamped and TF to base_link."""
    messages = []
    for i in range(N):
        t = START_NS + i * STEP_NS
        messages.append(("/odom", t, odometry(t, i)))
        covariant = T["geometry_msgs/msg/PoseWithCovarianceStamped"](header=header(t, "map"), pose=with_covariance(i))
        messages.append(("/amcl_pose", t + 1, covariant))
        messages.append(("/tf", t + 2, tf(t, i)))
    write_bag(path, messages)


def write_tum(path, shift=np.zeros(3)):
    rows = []
    for i in range(N):
        p, q = path_pose(i)
        p = p + shift
        rows.append(f"{(START_NS + i * STEP_NS) / 1e9:.9f} " + " ".join(f"{v:.12f}" for v in [*p, *q]))
    path.write_text("\n".join(rows) + "\n")


def ate(rslam_bin, *args):
    return json.loads(run_cli(rslam_bin, "eval", *args, "--json"))["ate"]


def test_every_pose_topic_kind_reads_as_the_same_path(rslam_bin, tmp_path):
    bag = tmp_path / "robot"
    robot_trajectories(bag)
    tum = tmp_path / "path.txt"
    write_tum(tum)
    for topic in ["/odom", "/amcl_pose", "/tf:base_link"]:
        result = ate(rslam_bin, bag, tum, "--est-topic", topic)
        assert result["n"] == N, topic
        assert result["rmse"] < 1e-9, (topic, result)
    # The ground truth side too, and a real difference shows: 5 cm off without alignment.
    shifted = tmp_path / "shifted.txt"
    write_tum(shifted, shift=np.array([0.05, 0.0, 0.0]))
    result = ate(rslam_bin, shifted, bag, "--gt-topic", "/odom", "--align", "none")
    assert abs(result["rmse"] - 0.05) < 1e-9


def refused(rslam_bin, *args):
    done = subprocess.run([str(rslam_bin), "eval", *map(str, args)], capture_output=True, text=True)
    assert done.returncode != 0
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, done.stderr
    return lines[0]


def test_an_ambiguous_or_missing_topic_is_refused_naming_the_bag_and_its_pose_topics(rslam_bin, tmp_path):
    bag = tmp_path / "robot"
    robot_trajectories(bag)
    tum = tmp_path / "path.txt"
    write_tum(tum)
    line = refused(rslam_bin, bag, tum)
    assert "robot" in line and "several pose topics" in line and "/odom" in line and "/amcl_pose" in line
    line = refused(rslam_bin, bag, tum, "--est-topic", "/tf:wheel")
    assert "no transform to frame wheel on /tf" in line and "/tf (tf2_msgs/msg/TFMessage)" in line
    line = refused(rslam_bin, bag, tum, "--est-topic", "/tf")
    assert "/tf:CHILD" in line
    line = refused(rslam_bin, tum, bag, "--gt-topic", "/missing")
    assert "no message on topic /missing" in line and "/odom (nav_msgs/msg/Odometry)" in line


def test_the_python_package_reads_bag_topics_as_the_cli_does(tmp_path):
    import rslam.eval

    bag = tmp_path / "robot"
    robot_trajectories(bag)
    tum = tmp_path / "path.txt"
    write_tum(tum)
    result = rslam.eval.evaluate(str(bag), str(tum), est_topic="/tf:base_link")
    assert result["ate"]["n"] == N and result["ate"]["rmse"] < 1e-9
    result = rslam.eval.evaluate(str(tum), str(bag), gt_topic="/amcl_pose", align="none")
    assert result["ate"]["rmse"] < 1e-9
