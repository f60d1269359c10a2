"""IMU items on a bag's `sensor_msgs/Imu` topics, read back with the `rosbags` library: drops and
jitter remove and move messages (their log times moving with their stamps) and leave every other
topic message for message; `imu_noise:K` adds noise of (K² − 1) times the variance the messages'
covariances state; what a bag cannot take is refused in one line."""

import json

import numpy as np

from conftest import run_cli
from test_perturb_bag import deserialized, raw_messages, refusal, robot_bag, stamp_ns  # noqa: F401 (a fixture)

IMU = "/imu"
IMU_PERIOD_NS = 33_333_333 // 4


def test_drops_and_jitter_remove_and_move_imu_messages_and_copy_the_rest(robot_bag, rslam_bin, tmp_path):
    out = tmp_path / "perturbed"
    run_cli(rslam_bin, "perturb", "--input", robot_bag, "--perturb", "imu_drop:0.25,imu_jitter:1", "--out", out)
    before, types_before = raw_messages(robot_bag)
    after, types_after = raw_messages(out)
    assert types_after == types_before
    for topic in before:
        if topic != IMU:
            assert after[topic] == before[topic], topic
    report = json.loads((out / "rslam.json").read_text())["extra"]["imu_perturbation"][IMU]
    recorded, perturbed = deserialized(robot_bag, IMU), deserialized(out, IMU)
    assert len(perturbed) == len(recorded) - report["dropped"]["dropped"] < len(recorded)
    recorded_stamps = np.array([stamp_ns(m) for m in recorded])
    stamps = np.array([stamp_ns(m) for m in perturbed])
    assert np.all(np.diff(stamps) > 0)
    nearest = np.abs(stamps[:, None] - recorded_stamps[None, :]).argmin(axis=1)
    assert np.all(np.diff(nearest) > 0)  # each message is a recorded one, in order, none twice
    moved = stamps - recorded_stamps[nearest]
    assert np.abs(moved).max() < IMU_PERIOD_NS / 2 and np.any(moved != 0)
    # The robot logged each reading 1000 ns after its stamp; a moved reading is logged as much later.
    assert [t for t, _ in after[IMU]] == list(stamps + 1000)
    for message in perturbed:
        assert message.header.frame_id == "imu_link"
        assert message.linear_acceleration.y == 9.81


def test_imu_noise_adds_the_scaled_variance_the_covariances_state(rslam_bin, tmp_path):
    bag = tmp_path / "rendered"
    run_cli(rslam_bin, "render", "--scene", "room0", "--frames", "40", "--camera", "64,48,40,40,31.5,23.5",
            "--rig", "rgbd-imu", "--format", "ros2", "--out", bag)
    out = tmp_path / "noisier"
    run_cli(rslam_bin, "perturb", "--input", bag, "--perturb", "imu_noise:3", "--out", out)
    recorded, perturbed = deserialized(bag, "/imu0"), deserialized(out, "/imu0")
    assert len(recorded) == len(perturbed) > 300
    assert [stamp_ns(m) for m in perturbed] == [stamp_ns(m) for m in recorded]
    for name in ("angular_velocity", "linear_acceleration"):
        variance = recorded[0].__getattribute__(name + "_covariance")[0]
        added = np.array([[getattr(getattr(b, name), axis) - getattr(getattr(a, name), axis) for axis in "xyz"]
                          for a, b in zip(recorded, perturbed)])
        expected = np.sqrt((3**2 - 1) * variance)
        assert abs(added.std() / expected - 1) < 0.15, name
        assert abs(added.mean()) < 4 * expected / np.sqrt(added.size)
        assert all(np.array_equal(getattr(b, name + "_covariance"), getattr(a, name + "_covariance"))
                   for a, b in zip(recorded, perturbed))
    before, _ = raw_messages(bag)
    after, _ = raw_messages(out)
    assert after["/camera/color/image_raw"] == before["/camera/color/image_raw"]


def test_what_a_bags_imu_cannot_take_is_refused_in_one_line(robot_bag, rslam_bin, tmp_path):
    line = refusal(rslam_bin, robot_bag, tmp_path, spec="imu_noise:2")
    assert IMU in line and "covariances" in line and "imu_noise:2" in line
    line = refusal(rslam_bin, robot_bag, tmp_path, spec="cam_imu_offset:5")
    assert "cam_imu_offset" in line and "CameraInfo" in line
