"""`rslam perturb --input BAG` on bags written by the `rosbags` library, standing in for a robot's
recording: the camera's images come back perturbed in their own encodings and headers, every other
topic (IMU, odometry, /tf, camera info) comes back message for message, and bags rslam cannot read
are refused in one line naming the bag and the topic."""

import subprocess

import numpy as np
import pytest
from PIL import Image
from io import BytesIO
from rosbags.rosbag2 import Reader, StoragePlugin, Writer
from rosbags.typesys import Stores, get_typestore

from conftest import run_cli

TYPES = get_typestore(Stores.ROS2_HUMBLE)
T = TYPES.types
WIDTH, HEIGHT, FRAMES = 64, 48, 8
START_NS = 1_700_000_000_123_456_789  # stamps of a real clock, not representable in f64 seconds
FRAME_NS = 33_333_333
COLOUR = "/camera/color/image_raw"
DEPTH = "/camera/aligned_depth_to_color/image_raw"


def header(t_ns, frame="camera_color_optical_frame"):
    time = T["builtin_interfaces/msg/Time"](sec=t_ns // 10**9, nanosec=t_ns % 10**9)
    return T["std_msgs/msg/Header"](stamp=time, frame_id=frame)


def image(t_ns, encoding, pixels):
    height, width = pixels.shape[:2]
    data = np.ascontiguousarray(pixels).view(np.uint8).ravel()
    return T["sensor_msgs/msg/Image"](header=header(t_ns), height=height, width=width, encoding=encoding,
                                      is_bigendian=0, step=data.size // height, data=data)


def compressed(t_ns, rgb, fmt):
    out = BytesIO()
    Image.fromarray(rgb).save(out, format="PNG")
    return T["sensor_msgs/msg/CompressedImage"](header=header(t_ns), format=fmt,
                                                data=np.frombuffer(out.getvalue(), np.uint8))


def camera_info(t_ns):
    roi = T["sensor_msgs/msg/RegionOfInterest"](x_offset=0, y_offset=0, height=0, width=0, do_rectify=False)
    k = np.array([50.0, 0, 31.5, 0, 51.0, 23.5, 0, 0, 1])
    return T["sensor_msgs/msg/CameraInfo"](header=header(t_ns), height=HEIGHT, width=WIDTH,
                                           distortion_model="plumb_bob", d=np.zeros(5), k=k,
                                           r=np.eye(3).ravel(), p=np.zeros(12), binning_x=0, binning_y=0, roi=roi)


def imu(t_ns):
    v = T["geometry_msgs/msg/Vector3"]
    q = T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0)
    return T["sensor_msgs/msg/Imu"](header=header(t_ns, "imu_link"), orientation=q,
                                    orientation_covariance=np.zeros(9), angular_velocity=v(x=0.01, y=0.02, z=0.03),
                                    angular_velocity_covariance=np.zeros(9),
                                    linear_acceleration=v(x=0.1, y=9.81, z=0.2),
                                    linear_acceleration_covariance=np.zeros(9))


def tf(t_ns):
    transform = T["geometry_msgs/msg/Transform"](
        translation=T["geometry_msgs/msg/Vector3"](x=t_ns % 1000 * 1e-3, y=0.0, z=0.0),
        rotation=T["geometry_msgs/msg/Quaternion"](x=0.0, y=0.0, z=0.0, w=1.0))
    stamped = T["geometry_msgs/msg/TransformStamped"](header=header(t_ns, "odom"), child_frame_id="base_link",
                                                      transform=transform)
    return T["tf2_msgs/msg/TFMessage"](transforms=[stamped])


def rng_colour(i):
    return np.random.default_rng(i).integers(0, 256, (HEIGHT, WIDTH, 3), dtype=np.uint8)


def rng_depth(i):
    depth = np.random.default_rng(100 + i).uniform(0.5, 4.0, (HEIGHT, WIDTH)).astype(np.float32)
    depth[::7, ::5] = np.nan
    return depth


def write_bag(path, messages):
    """A rosbag2 folder in MCAP storage of [(topic, log time ns, message)], in that order."""
    with Writer(path, version=9, storage_plugin=StoragePlugin.MCAP) as writer:
        connections = {}
        for topic, t_ns, message in messages:
            if topic not in connections:
                connections[topic] = writer.add_connection(topic, message.__msgtype__, typestore=TYPES)
            writer.write(connections[topic], t_ns, TYPES.serialize_cdr(message, message.__msgtype__))


def robot_messages(colour_message=lambda t, i: image(t, "bgr8", rng_colour(i)[..., ::-1]),
                   colour_topic=COLOUR, with_info=True):
    """A RealSense-like recording: bgr8 colour, aligned 32FC1 depth in metres, each with camera
    info, an IMU at four times the frame rate and /tf; log times a little after the stamps."""
    messages = []
    for i in range(FRAMES):
        t = START_NS + i * FRAME_NS
        for k in range(4):
            messages.append(("/imu", t + k * FRAME_NS // 4 + 1000, imu(t + k * FRAME_NS // 4)))
        messages.append((colour_topic, t + 2_000_000, colour_message(t, i)))
        if with_info:
            messages.append(("/camera/color/camera_info", t + 2_000_001, camera_info(t)))
        messages.append((DEPTH, t + 2_500_000, image(t, "32FC1", rng_depth(i))))
        messages.append(("/camera/aligned_depth_to_color/camera_info", t + 2_500_001, camera_info(t)))
        messages.append(("/tf", t + 3_000_000, tf(t)))
    return messages


def raw_messages(bag):
    """{topic: [(log time, raw CDR bytes)]} and {topic: type}."""
    topics, types = {}, {}
    with Reader(bag) as reader:
        for connection in reader.connections:
            types[connection.topic] = connection.msgtype
        for connection, t, raw in reader.messages():
            topics.setdefault(connection.topic, []).append((t, bytes(raw)))
    return topics, types


def deserialized(bag, topic):
    with Reader(bag) as reader:
        connections = [c for c in reader.connections if c.topic == topic]
        return [TYPES.deserialize_cdr(raw, c.msgtype) for c, _, raw in reader.messages(connections=connections)]


def stamp_ns(message):
    return message.header.stamp.sec * 10**9 + message.header.stamp.nanosec


@pytest.fixture(scope="module")
def robot_bag(tmp_path_factory):
    root = tmp_path_factory.mktemp("robot")
    write_bag(root / "recorded", robot_messages())
    return root / "recorded"


def test_depth_items_leave_colour_bit_for_bit_and_every_other_topic_message_for_message(robot_bag, rslam_bin, tmp_path):
    out = tmp_path / "perturbed"
    run_cli(rslam_bin, "perturb", "--input", robot_bag, "--perturb", "depth_missing:3", "--out", out)
    before, types_before = raw_messages(robot_bag)
    after, types_after = raw_messages(out)
    assert types_after == types_before
    for topic in before:
        if topic != DEPTH:
            assert after[topic] == before[topic], topic
    assert [t for t, _ in after[DEPTH]] == [t for t, _ in before[DEPTH]]
    recorded, perturbed = deserialized(robot_bag, DEPTH), deserialized(out, DEPTH)
    new_holes = 0
    for a, b in zip(recorded, perturbed):
        assert (b.encoding, b.width, b.height, b.header.frame_id) == ("32FC1", WIDTH, HEIGHT, a.header.frame_id)
        assert stamp_ns(b) == stamp_ns(a)
        za = a.data.view(np.float32).reshape(HEIGHT, WIDTH)
        zb = b.data.view(np.float32).reshape(HEIGHT, WIDTH)
        kept = ~np.isnan(zb)
        assert np.array_equal(za[kept], zb[kept])
        assert np.isnan(za).sum() <= np.isnan(zb).sum()
        new_holes += int(np.isnan(zb).sum() - np.isnan(za).sum())
    assert new_holes > FRAMES * WIDTH * HEIGHT // 100


def test_colour_items_change_bgr8_colour_in_its_own_encoding_and_keep_its_stamps(robot_bag, rslam_bin, tmp_path):
    out = tmp_path / "noisy"
    run_cli(rslam_bin, "perturb", "--input", robot_bag, "--perturb", "gaussian_noise:3", "--out", out)
    recorded, perturbed = deserialized(robot_bag, COLOUR), deserialized(out, COLOUR)
    assert len(perturbed) == FRAMES
    for i, (a, b) in enumerate(zip(recorded, perturbed)):
        assert (b.encoding, b.step, b.header.frame_id) == ("bgr8", 3 * WIDTH, a.header.frame_id)
        assert stamp_ns(b) == stamp_ns(a) == START_NS + i * FRAME_NS
        clean = a.data.reshape(HEIGHT, WIDTH, 3).astype(float)
        noisy = b.data.reshape(HEIGHT, WIDTH, 3).astype(float)
        # Gaussian noise at severity 3 (sigma 0.18 of full scale): a large spread, no bias.
        spread = np.std(noisy - clean)
        assert 20 < spread < 60, spread
        assert abs(np.mean(noisy - clean)) < 5
    after, _ = raw_messages(out)
    before, _ = raw_messages(robot_bag)
    assert after[DEPTH] == before[DEPTH]


def test_misalignment_moves_the_depth_stamps_and_log_times_by_its_delay(robot_bag, rslam_bin, tmp_path):
    out = tmp_path / "late"
    run_cli(rslam_bin, "perturb", "--input", robot_bag, "--perturb", "misalign:2", "--out", out)
    colour = [stamp_ns(m) for m in deserialized(out, COLOUR)]
    depth = [stamp_ns(m) for m in deserialized(out, DEPTH)]
    assert colour == [START_NS + i * FRAME_NS for i in range(FRAMES)]
    assert depth and set(depth) <= {START_NS + i * FRAME_NS for i in range(FRAMES)}
    assert len(depth) < FRAMES


def test_compressed_png_colour_is_written_back_compressed_in_its_format(rslam_bin, tmp_path):
    topic = COLOUR + "/compressed"
    fmt = "rgb8; png compressed rgb8"
    bag = tmp_path / "compressed"
    write_bag(bag, robot_messages(lambda t, i: compressed(t, rng_colour(i), fmt), topic))
    out = tmp_path / "compressed_out"
    run_cli(rslam_bin, "perturb", "--input", bag, "--perturb", "gaussian_noise:2", "--out", out)
    recorded, perturbed = deserialized(bag, topic), deserialized(out, topic)
    assert len(perturbed) == FRAMES
    for a, b in zip(recorded, perturbed):
        assert b.format == fmt
        image = np.asarray(Image.open(BytesIO(b.data.tobytes())))
        clean = np.asarray(Image.open(BytesIO(a.data.tobytes())))
        assert image.shape == clean.shape == (HEIGHT, WIDTH, 3)
        assert 10 < np.std(image.astype(float) - clean) < 60


def refusal(rslam_bin, bag, tmp_path, spec="gaussian_noise:1"):
    done = subprocess.run([str(rslam_bin), "perturb", "--input", str(bag), "--perturb", spec,
                           "--out", str(tmp_path / "refused")], capture_output=True, text=True)
    assert done.returncode != 0
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    assert len(lines) == 1, done.stderr
    assert not (tmp_path / "refused").exists() or not any((tmp_path / "refused").glob("*.mcap"))
    return lines[0]


def test_bags_rslam_cannot_perturb_are_refused_in_one_line_naming_bag_and_topic(robot_bag, rslam_bin, tmp_path):
    unknown = tmp_path / "bayer"
    write_bag(unknown, robot_messages(lambda t, i: image(t, "bayer_rggb8", rng_colour(i)[..., 0])))
    line = refusal(rslam_bin, unknown, tmp_path)
    assert "bayer" in line and COLOUR in line and "bayer_rggb8" in line

    no_info = tmp_path / "no_info"
    write_bag(no_info, robot_messages(with_info=False))
    line = refusal(rslam_bin, no_info, tmp_path)
    assert "no_info" in line and "/camera/color/camera_info" in line and COLOUR in line

    depth_png = tmp_path / "compressed_depth"
    cdepth = T["sensor_msgs/msg/CompressedImage"](header=header(START_NS), format="16UC1; compressedDepth png",
                                                  data=np.zeros(16, np.uint8))
    write_bag(depth_png, robot_messages() + [(DEPTH + "/compressedDepth", START_NS + 9 * FRAME_NS, cdepth)])
    line = refusal(rslam_bin, depth_png, tmp_path)
    assert "compressedDepth" in line and DEPTH + "/compressedDepth" in line

    truncated = tmp_path / "truncated"
    write_bag(truncated, robot_messages())
    storage = next(truncated.glob("*.mcap"))
    storage.write_bytes(storage.read_bytes()[: storage.stat().st_size // 2])
    line = refusal(rslam_bin, truncated, tmp_path)
    assert storage.name in line and "MCAP" in line

    line = refusal(rslam_bin, robot_bag, tmp_path, spec="fast:2")
    assert "fast" in line and "copied with their times" in line


def test_each_camera_of_a_stereo_bag_is_perturbed_and_the_rest_copied(rslam_bin, tmp_path):
    stereo = tmp_path / "stereo"
    run_cli(rslam_bin, "render", "--scene", "room0", "--frames", "8", "--rig", "stereo-imu", "--format", "ros2",
            "--out", stereo)
    out = tmp_path / "stereo_noisy"
    run_cli(rslam_bin, "perturb", "--input", stereo, "--perturb", "gaussian_noise:3", "--out", out)
    before, types_before = raw_messages(stereo)
    after, types_after = raw_messages(out)
    assert types_after == types_before
    cameras = ["/cam0/image_raw", "/cam1/image_raw"]
    for topic in before:
        if topic not in cameras:
            assert after[topic] == before[topic], topic
    for topic in cameras:
        assert [t for t, _ in after[topic]] == [t for t, _ in before[topic]]
        for a, b in zip(deserialized(stereo, topic), deserialized(out, topic)):
            assert (b.encoding, b.header.frame_id, stamp_ns(b)) == ("mono8", a.header.frame_id, stamp_ns(a))
            spread = np.std(b.data.astype(float) - a.data.astype(float))
            assert 20 < spread < 60, (topic, spread)
    with Reader(out) as reader:
        log_times = [t for _, t, _ in reader.messages()]
    assert log_times == sorted(log_times)
    assert sorted(p.name for p in out.iterdir()) == ["metadata.yaml", "rslam.b3sum", "rslam.json", "stereo_noisy_0.mcap"]
    line = refusal(rslam_bin, stereo, tmp_path, spec="depth_missing:2")
    assert "stereo" in line and "no depth topic" in line
