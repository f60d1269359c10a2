"""`rslam render --rig rgbd-imu --format ros2` read by the `rosbags` library: the IMU readings on
/imu0 equal the TUM layout's imu0/data.csv of the same job, with the noise of imu0/sensor.yaml as
covariances; /tf_static places the IMU where ORB-SLAM3's settings do; the frames and the ground
truth equal the TUM layout's; every message is logged in stamp order."""

import numpy as np
import pytest
import yaml
from rosbags.highlevel import AnyReader
from PIL import Image
from scipy.spatial.transform import Rotation

from conftest import run_cli

JOB = ["render", "--scene", "room0", "--frames", "12", "--camera", "160,90,80,80,79.5,44.5", "--rig", "rgbd-imu",
       "--perturb", "imu_noise:2,gaussian_noise:1"]


@pytest.fixture(scope="module")
def bag_and_tum(tmp_path_factory, rslam_bin):
    root = tmp_path_factory.mktemp("rig_bag")
    run_cli(rslam_bin, *JOB, "--format", "ros2", "--out", root / "bag")
    run_cli(rslam_bin, *JOB, "--format", "tum", "--out", root / "tum")
    with AnyReader([root / "bag"]) as reader:
        messages = [(c.topic, t, reader.deserialize(raw, c.msgtype)) for c, t, raw in reader.messages()]
    return messages, root / "tum"


def on(messages, topic):
    return [m for t, _, m in messages if t == topic]


def stamp_ns(message):
    return message.header.stamp.sec * 10**9 + message.header.stamp.nanosec


def test_imu_readings_equal_the_tum_layouts_with_their_noise_as_covariance(bag_and_tum):
    messages, tum = bag_and_tum
    imu = on(messages, "/imu0")
    rows = np.loadtxt(tum / "imu0/data.csv", delimiter=",", comments="#")
    assert len(imu) == len(rows) > 50
    for message, row in zip(imu, rows):
        assert stamp_ns(message) == int(row[0])
        assert message.header.frame_id == "imu0"
        w, a = message.angular_velocity, message.linear_acceleration
        assert [w.x, w.y, w.z, a.x, a.y, a.z] == list(row[1:])
        assert message.orientation_covariance[0] == -1
    sensor = yaml.safe_load((tum / "imu0/sensor.yaml").read_text())
    gyro = sensor["gyroscope_noise_density"] ** 2 * sensor["rate_hz"]
    accel = sensor["accelerometer_noise_density"] ** 2 * sensor["rate_hz"]
    assert np.allclose(imu[0].angular_velocity_covariance, np.diag([gyro] * 3).ravel(), rtol=1e-12)
    assert np.allclose(imu[0].linear_acceleration_covariance, np.diag([accel] * 3).ravel(), rtol=1e-12)


def pose_matrix(transform):
    q = transform.rotation
    m = np.eye(4)
    m[:3, :3] = Rotation.from_quat([q.x, q.y, q.z, q.w]).as_matrix()
    m[:3, 3] = [transform.translation.x, transform.translation.y, transform.translation.z]
    return m


def test_tf_static_places_the_imu_where_orbslam3s_settings_do(bag_and_tum):
    messages, tum = bag_and_tum
    (tf,) = on(messages, "/tf_static")
    in_link = {t.child_frame_id: pose_matrix(t.transform) for t in tf.transforms}
    assert {t.header.frame_id for t in tf.transforms} == {"camera_link"}
    optical_from_imu = np.linalg.inv(in_link["camera_color_optical_frame"]) @ in_link["imu0"]
    settings = (tum / "orbslam3_rgbd_inertial.yaml").read_text().split("\n", 1)[1]
    settings = settings.replace("!!opencv-matrix", "")
    body_from_camera = np.array(yaml.safe_load(settings)["IMU.T_b_c1"]["data"]).reshape(4, 4)
    assert np.allclose(optical_from_imu, np.linalg.inv(body_from_camera), atol=1e-6)


def test_frames_and_ground_truth_equal_the_tum_layout_and_logs_follow_stamps(bag_and_tum):
    messages, tum = bag_and_tum
    rgb_times = [float(line.split()[0]) for line in (tum / "rgb.txt").read_text().splitlines()
                 if line and not line.startswith("#")]
    colours = on(messages, "/camera/color/image_raw")
    assert [round(stamp_ns(m) / 1e9, 6) for m in colours] == rgb_times
    truth = np.loadtxt(tum / "groundtruth.txt", comments="#")
    poses = on(messages, "/ground_truth/pose")
    assert len(poses) == len(truth)
    for message, row in zip(poses, truth):
        p = message.pose.position
        assert np.allclose([p.x, p.y, p.z], row[1:4], atol=1e-6)
    log_times = [t for _, t, _ in messages]
    assert log_times == sorted(log_times)
    assert [stamp_ns(m) for m in colours] == [t for topic, t, _ in messages if topic == "/camera/color/image_raw"]


STEREO_JOB = ["render", "--scene", "room0", "--frames", "10", "--rig", "stereo-imu", "--perturb", "cam1:fog:2,imu_noise:2"]


@pytest.fixture(scope="module")
def stereo_bag_and_euroc(tmp_path_factory, rslam_bin):
    root = tmp_path_factory.mktemp("stereo_bag")
    run_cli(rslam_bin, *STEREO_JOB, "--format", "ros2", "--out", root / "bag")
    run_cli(rslam_bin, *STEREO_JOB, "--format", "euroc", "--out", root / "euroc")
    with AnyReader([root / "bag"]) as reader:
        messages = [(c.topic, t, reader.deserialize(raw, c.msgtype)) for c, t, raw in reader.messages()]
    return messages, root / "bag", root / "euroc/mav0"


def sensor_yaml(path):
    return yaml.safe_load(path.read_text().split("\n", 1)[1] if path.read_text().startswith("%YAML") else path.read_text())


def test_a_stereo_rigs_cameras_equal_the_euroc_layouts_frame_for_frame(stereo_bag_and_euroc):
    messages, bag, mav = stereo_bag_and_euroc
    assert sorted(p.name for p in bag.iterdir()) == ["bag_0.mcap", "metadata.yaml", "rslam.b3sum", "rslam.json"]
    for camera in ["cam0", "cam1"]:
        rows = [line.split(",") for line in (mav / camera / "data.csv").read_text().splitlines()[1:]]
        images = on(messages, f"/{camera}/image_raw")
        assert [stamp_ns(m) for m in images] == [int(t) for t, _ in rows]
        for message, (_, name) in zip(images, rows):
            assert (message.encoding, message.header.frame_id) == ("mono8", camera)
            png = np.asarray(Image.open(mav / camera / "data" / name.strip()))
            assert np.array_equal(message.data.reshape(message.height, message.width), png)
        sensor = sensor_yaml(mav / camera / "sensor.yaml")
        (info, *_) = on(messages, f"/{camera}/camera_info")
        fu, fv, cu, cv = sensor["intrinsics"]
        assert [info.k[0], info.k[4], info.k[2], info.k[5]] == [fu, fv, cu, cv]
        assert list(info.d[:4]) == sensor["distortion_coefficients"]
        (tf,) = on(messages, "/tf_static")
        (placed,) = [t for t in tf.transforms if t.child_frame_id == camera]
        assert placed.header.frame_id == "body"
        t_bs = np.array(sensor["T_BS"]["data"]).reshape(4, 4)
        assert np.allclose(pose_matrix(placed.transform), t_bs, atol=1e-9)


def test_a_stereo_rigs_imu_and_body_ground_truth_equal_the_euroc_layouts(stereo_bag_and_euroc):
    messages, _, mav = stereo_bag_and_euroc
    imu_rows = np.loadtxt(mav / "imu0/data.csv", delimiter=",", comments="#")
    imu = on(messages, "/imu0")
    assert len(imu) == len(imu_rows)
    for message, row in zip(imu, imu_rows):
        w, a = message.angular_velocity, message.linear_acceleration
        assert [stamp_ns(message), w.x, w.y, w.z, a.x, a.y, a.z] == [int(row[0]), *row[1:]]
    truth = np.loadtxt(mav / "state_groundtruth_estimate0/data.csv", delimiter=",", comments="#")
    poses = on(messages, "/ground_truth/pose")
    assert len(poses) == len(truth)
    for message, row in zip(poses, truth):
        p, q = message.pose.position, message.pose.orientation
        assert stamp_ns(message) == int(row[0])
        assert np.allclose([p.x, p.y, p.z, q.w, q.x, q.y, q.z], row[1:8], atol=1e-12)
    log_times = [t for _, t, _ in messages]
    assert log_times == sorted(log_times)
