"""`rslam render --format ros2` read by a real reader: the `rosbags` library opens the bag,
deserialises every message by the definitions stored in it (checked field by field against the
ROS 2 Humble definitions rosbags ships), and the frames, stamps, camera and ground truth equal the
TUM layout of the same job; the `mcap` package checks the container."""

import numpy as np
import pytest
import yaml
from mcap.reader import make_reader
from PIL import Image
from rosbags.rosbag2 import Reader
from rosbags.typesys import Stores, get_typestore, get_types_from_msg

from conftest import run_cli

CAMERA = "160,90,80,80,79.5,44.5"
JOB = ["render", "--scene", "room0", "--frames", "12", "--camera", CAMERA, "--perturb", "misalign:5"]


@pytest.fixture(scope="module")
def bag_and_tum(tmp_path_factory, rslam_bin):
    root = tmp_path_factory.mktemp("ros2")
    run_cli(rslam_bin, *JOB, "--format", "ros2", "--out", root / "bag")
    run_cli(rslam_bin, *JOB, "--format", "tum", "--out", root / "tum")
    return root / "bag", root / "tum"


def read_bag(bag):
    """Every message as (topic, log time in ns, message), deserialised by the bag's own
    definitions; and the connections."""
    ours = get_typestore(Stores.EMPTY)
    humble = get_typestore(Stores.ROS2_HUMBLE)
    with Reader(bag) as reader:
        for connection in reader.connections:
            ours.register(get_types_from_msg(connection.msgdef.data, connection.msgtype))
        for name, fields in ours.fielddefs.items():
            assert fields == humble.fielddefs[name], name
        messages = [(c.topic, t, ours.deserialize_cdr(raw, c.msgtype))
                    for c, t, raw in reader.messages()]
        return messages, {c.topic: (c.msgtype, c.msgcount) for c in reader.connections}


def stamp(message):
    return message.header.stamp.sec + 1e-9 * message.header.stamp.nanosec


def tum_list(path):
    rows = [line.split() for line in path.read_text().splitlines() if not line.startswith("#")]
    return [(float(row[0]), row[1:]) for row in rows if row]


def test_every_topic_has_its_type_and_one_message_per_capture(bag_and_tum):
    bag, tum = bag_and_tum
    _, connections = read_bag(bag)
    # Under misalignment several frames carry one depth capture, which the bag holds once.
    depths = len(tum_list(tum / "depth.txt"))
    assert 1 < depths < 12
    assert connections == {
        "/camera/color/image_raw": ("sensor_msgs/msg/Image", 12),
        "/camera/color/camera_info": ("sensor_msgs/msg/CameraInfo", 12),
        "/camera/depth/image_raw": ("sensor_msgs/msg/Image", depths),
        "/camera/depth/camera_info": ("sensor_msgs/msg/CameraInfo", depths),
        "/ground_truth/pose": ("geometry_msgs/msg/PoseStamped", 12),
        "/tf_static": ("tf2_msgs/msg/TFMessage", 1),
    }


def test_colour_equals_the_tum_pngs_and_depth_is_within_a_millimetre_step(bag_and_tum):
    bag, tum = bag_and_tum
    messages, _ = read_bag(bag)
    colours = [m for topic, _, m in messages if topic == "/camera/color/image_raw"]
    depths = {round(stamp(m), 6): m for topic, _, m in messages if topic == "/camera/depth/image_raw"}
    rgb = tum_list(tum / "rgb.txt")
    assert [round(stamp(m), 6) for m in colours] == [t for t, _ in rgb]
    for message, (_, (name,)) in zip(colours, rgb):
        assert (message.encoding, message.height, message.width, message.step) == ("rgb8", 90, 160, 480)
        pixels = message.data.reshape(90, 160, 3)
        assert np.array_equal(pixels, np.asarray(Image.open(tum / name).convert("RGB")))
    depth_rows = tum_list(tum / "depth.txt")
    assert sorted(depths) == [t for t, _ in depth_rows]
    for t, (name,) in depth_rows:
        message = depths[t]
        assert (message.encoding, message.step) == ("16UC1", 320)
        millimetres = message.data.view("<u2").reshape(90, 160).astype(float)
        tum_depth = np.asarray(Image.open(tum / name)).astype(float)  # metres * 5000
        assert np.array_equal(millimetres == 0, tum_depth == 0)
        assert np.abs(millimetres - tum_depth / 5).max() <= 0.6


def test_camera_info_ground_truth_and_tf_match_the_tum_layout(bag_and_tum):
    bag, tum = bag_and_tum
    messages, _ = read_bag(bag)
    fx, fy, cx, cy = 80, 80, 79.5, 44.5
    for topic, _, info in messages:
        if topic.endswith("camera_info"):
            assert (info.width, info.height, info.distortion_model) == (160, 90, "plumb_bob")
            assert np.allclose(info.k, [fx, 0, cx, 0, fy, cy, 0, 0, 1])
            assert np.allclose(info.p, [fx, 0, cx, 0, 0, fy, cy, 0, 0, 0, 1, 0])
            assert info.header.frame_id == "camera_color_optical_frame"
    poses = [m for topic, _, m in messages if topic == "/ground_truth/pose"]
    truth = np.loadtxt(tum / "groundtruth.txt")
    assert len(poses) == len(truth)
    for message, row in zip(poses, truth):
        p, q = message.pose.position, message.pose.orientation
        assert message.header.frame_id == "world"
        assert abs(stamp(message) - row[0]) < 1e-6
        assert np.allclose([p.x, p.y, p.z], row[1:4], atol=1e-6)
        assert np.allclose(np.abs(np.dot([q.x, q.y, q.z, q.w], row[4:8])), 1, atol=1e-6)
    (tf,) = [m for topic, _, m in messages if topic == "/tf_static"]
    (transform,) = tf.transforms
    assert (transform.header.frame_id, transform.child_frame_id) == ("camera_link", "camera_color_optical_frame")
    r = transform.transform.rotation
    assert np.allclose([r.x, r.y, r.z, r.w], [-0.5, 0.5, -0.5, 0.5])


def test_log_times_are_the_stamps_in_order(bag_and_tum):
    messages, _ = read_bag(bag_and_tum[0])
    times = [t for _, t, _ in messages]
    assert times == sorted(times)
    for topic, t, message in messages:
        if topic != "/tf_static":
            assert t == message.header.stamp.sec * 10**9 + message.header.stamp.nanosec


def test_the_container_is_a_ros2_mcap_and_metadata_yaml_agrees(bag_and_tum):
    bag, _ = bag_and_tum
    (mcap_file,) = bag.glob("*.mcap")
    with open(mcap_file, "rb") as f:
        reader = make_reader(f, validate_crcs=True)
        summary = reader.get_summary()
        assert reader.get_header().profile == "ros2"
        assert {s.encoding for s in summary.schemas.values()} == {"ros2msg"}
        assert {c.message_encoding for c in summary.channels.values()} == {"cdr"}
        count = sum(1 for _ in reader.iter_messages())
    info = yaml.safe_load((bag / "metadata.yaml").read_text())["rosbag2_bagfile_information"]
    assert (info["storage_identifier"], info["relative_file_paths"]) == ("mcap", [mcap_file.name])
    assert info["message_count"] == count == summary.statistics.message_count
    topics = {t["topic_metadata"]["name"]: t for t in info["topics_with_message_count"]}
    qos = yaml.safe_load(topics["/tf_static"]["topic_metadata"]["offered_qos_profiles"])
    assert qos[0]["durability"] == 1  # transient local: late subscribers get the transforms
    assert all(t["topic_metadata"]["serialization_format"] == "cdr" for t in topics.values())
