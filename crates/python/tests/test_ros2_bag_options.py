"""`rslam render --format ros2` with its bag options, read by the `rosbags` library: `--bag-depth
32FC1` holds the depth in metres (NaN where the TUM layout has 0, within the TUM PNG's step
elsewhere), `--bag-tf` puts `world → body` on /tf so that it and /tf_static compose to the ground
truth, and `--bag-compression zstd` (checked by the `mcap` package) holds the same messages as the
plain bag. A stereo rig's bag carries the body's ground truth on /tf the same way."""

import numpy as np
import pytest
from mcap.reader import make_reader
from PIL import Image
from rosbags.highlevel import AnyReader
from scipy.spatial.transform import Rotation

from conftest import run_cli

CAMERA = "160,90,80,80,79.5,44.5"
JOB = ["render", "--scene", "room0", "--frames", "10", "--camera", CAMERA, "--perturb", "depth_missing:3"]
OPTIONS = ["--bag-depth", "32FC1", "--bag-tf", "--bag-compression", "zstd"]


@pytest.fixture(scope="module")
def bags(tmp_path_factory, rslam_bin):
    root = tmp_path_factory.mktemp("bag_options")
    run_cli(rslam_bin, *JOB, "--format", "ros2", *OPTIONS, "--out", root / "options")
    run_cli(rslam_bin, *JOB, "--format", "ros2", "--out", root / "plain")
    run_cli(rslam_bin, *JOB, "--format", "tum", "--out", root / "tum")
    return root


def read(bag):
    """Every message as (topic, log time, raw CDR, message)."""
    with AnyReader([bag]) as reader:
        return [(c.topic, t, raw, reader.deserialize(raw, c.msgtype)) for c, t, raw in reader.messages()]


def on(messages, topic):
    return [m for t, _, _, m in messages if t == topic]


def matrix(translation, rotation):
    m = np.eye(4)
    m[:3, :3] = Rotation.from_quat([rotation.x, rotation.y, rotation.z, rotation.w]).as_matrix()
    m[:3, 3] = [translation.x, translation.y, translation.z]
    return m


def test_32fc1_depth_is_metres_with_nan_where_there_is_no_measurement(bags):
    depths = on(read(bags / "options"), "/camera/depth/image_raw")
    rows = [line.split() for line in (bags / "tum/depth.txt").read_text().splitlines() if not line.startswith("#")]
    assert len(depths) == len(rows) == 10
    holes = 0
    for message, (_, name) in zip(depths, rows):
        assert (message.encoding, message.step, message.is_bigendian) == ("32FC1", 640, 0)
        metres = message.data.view("<f4").reshape(90, 160)
        tum = np.asarray(Image.open(bags / "tum" / name)).astype(float) / 5000
        assert np.array_equal(np.isnan(metres), tum == 0)
        holes += int((tum == 0).sum())
        seen = tum > 0
        assert np.abs(metres[seen] - tum[seen]).max() <= 0.5 / 5000 + 1e-7
    assert holes > 0  # depth_missing:3 made holes, so NaN was written somewhere


def test_tf_and_tf_static_compose_to_the_ground_truth(bags):
    messages = read(bags / "options")
    (static,) = on(messages, "/tf_static")
    (optical,) = static.transforms
    body_from_optical = matrix(optical.transform.translation, optical.transform.rotation)
    truths = on(messages, "/ground_truth/pose")
    tfs = on(messages, "/tf")
    assert len(tfs) == len(truths) == 10
    for tf, truth in zip(tfs, truths):
        (transform,) = tf.transforms
        assert (transform.header.frame_id, transform.child_frame_id) == ("world", optical.header.frame_id)
        assert transform.header.stamp == truth.header.stamp
        world_from_optical = matrix(transform.transform.translation, transform.transform.rotation) @ body_from_optical
        expected = matrix(truth.pose.position, truth.pose.orientation)
        assert np.allclose(world_from_optical, expected, atol=1e-9)


def test_zstd_chunks_hold_the_plain_bags_messages(bags):
    (compressed,) = (bags / "options").glob("*.mcap")
    with open(compressed, "rb") as f:
        reader = make_reader(f, validate_crcs=True)
        chunks = reader.get_summary().chunk_indexes
        assert chunks and {c.compression for c in chunks} == {"zstd"}
        assert sum(c.compressed_size for c in chunks) < sum(c.uncompressed_size for c in chunks)
    plain = {(t, time, bytes(raw)) for t, time, raw, _ in read(bags / "plain")}
    options = read(bags / "options")
    colour = {(t, time, bytes(raw)) for t, time, raw, _ in options if t == "/camera/color/image_raw"}
    assert len(colour) == 10 and colour <= plain


def test_a_rigs_bag_has_the_bodys_ground_truth_on_tf(tmp_path, rslam_bin):
    run_cli(rslam_bin, "render", "--scene", "room0", "--frames", "6", "--rig", "stereo", "--format", "ros2",
            "--bag-tf", "--out", tmp_path / "rig")
    messages = read(tmp_path / "rig")
    truths = on(messages, "/ground_truth/pose")
    tfs = on(messages, "/tf")
    assert len(tfs) == len(truths) > 0
    for tf, truth in zip(tfs, truths):
        (transform,) = tf.transforms
        assert (transform.header.frame_id, transform.child_frame_id) == ("world", "body")
        assert transform.header.stamp == truth.header.stamp
        assert np.allclose(matrix(transform.transform.translation, transform.transform.rotation),
                           matrix(truth.pose.position, truth.pose.orientation), atol=1e-12)


RIG_FILE = """
[[camera]]
T_BS = [1, 0, 0, 0,  0, 1, 0, 0.05,  0, 0, 1, 0,  0, 0, 0, 1]
rate_hz = 10
resolution = [64, 48]
intrinsics = [40, 40, 31.5, 23.5]

[[camera]]
T_BS = [1, 0, 0, 0,  0, 1, 0, -0.05,  0, 0, 1, 0,  0, 0, 0, 1]
rate_hz = 10
resolution = [64, 48]
intrinsics = [40, 40, 31.5, 23.5]

[imu]
rate_hz = 100
gyroscope_noise_density = 1.7e-4
gyroscope_random_walk = 2e-5
accelerometer_noise_density = 2e-3
accelerometer_random_walk = 3e-3

[ros2]
body_frame = "base_link"
ground_truth_topic = "/vicon/pose"
cam0 = { topic = "/stereo/left/image_raw", frame_id = "left_optical" }
cam1 = { topic = "/stereo/right/image_raw" }
imu0 = { topic = "/imu/data", frame_id = "imu_link" }
"""


def test_a_rig_files_ros2_table_names_the_topics_and_frames(tmp_path, rslam_bin):
    rig = tmp_path / "robot.toml"
    rig.write_text(RIG_FILE)
    run_cli(rslam_bin, "render", "--scene", "room0", "--frames", "4", "--rig", rig, "--format", "ros2",
            "--out", tmp_path / "bag")
    messages = read(tmp_path / "bag")
    assert {t for t, _, _, _ in messages} == {
        "/stereo/left/image_raw", "/stereo/left/camera_info", "/stereo/right/image_raw",
        "/stereo/right/camera_info", "/imu/data", "/vicon/pose", "/tf_static"}
    frames = {t: {m.header.frame_id for m in on(messages, t)} for t in
              ("/stereo/left/image_raw", "/stereo/left/camera_info", "/stereo/right/image_raw", "/imu/data")}
    assert frames == {"/stereo/left/image_raw": {"left_optical"}, "/stereo/left/camera_info": {"left_optical"},
                      "/stereo/right/image_raw": {"cam1"}, "/imu/data": {"imu_link"}}
    (static,) = on(messages, "/tf_static")
    placed = {(t.header.frame_id, t.child_frame_id): t.transform.translation.y for t in static.transforms}
    assert placed == {("base_link", "left_optical"): 0.05, ("base_link", "cam1"): -0.05, ("base_link", "imu_link"): 0.0}
    # The same rig file still writes the EuRoC layout, whose names the table does not touch.
    run_cli(rslam_bin, "render", "--scene", "room0", "--frames", "4", "--rig", rig, "--format", "euroc",
            "--out", tmp_path / "euroc")
    assert (tmp_path / "euroc/mav0/cam1/data.csv").is_file()
