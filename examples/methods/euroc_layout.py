"""Reading the EuRoC (ASL) layout for the stereo(-inertial) example, and turning ORB-SLAM3's
EuRoC-style trajectory into a TUM estimate of the body frame (the frame of
mav0/state_groundtruth_estimate0, which `rslam eval` compares against).

Pure Python and numpy: no OpenCV, no ORB-SLAM3, so it can be tested without them.
"""
import os

import numpy as np


class LayoutError(Exception):
    """A file of the layout that is missing or does not read; the message names it."""


def _data_rows(path, columns):
    """The comma-separated rows of a EuRoC data.csv (comments and blank lines skipped), each
    with its line number, checked to have `columns` fields."""
    if not os.path.isfile(path):
        raise LayoutError(f"{path}: no such file")
    rows = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            fields = [field.strip() for field in line.split(",")]
            if len(fields) != columns:
                raise LayoutError(f"{path}:{number}: {len(fields)} fields, expected {columns}")
            rows.append((number, fields))
    if not rows:
        raise LayoutError(f"{path}: no rows")
    return rows


def _nanoseconds(path, number, text):
    try:
        return int(text)
    except ValueError:
        raise LayoutError(f"{path}:{number}: timestamp '{text}' is not integer nanoseconds") from None


def camera_frames(camera_dir):
    """[(t_ns, image path)] of `mav0/camN/`, from its data.csv."""
    path = os.path.join(camera_dir, "data.csv")
    return [(_nanoseconds(path, number, t), os.path.join(camera_dir, "data", name))
            for number, (t, name) in _data_rows(path, 2)]


def stereo_frames(mav_dir):
    """[(t_ns, cam0 image, cam1 image)] for the timestamps both cameras have, in time order."""
    right = dict(camera_frames(os.path.join(mav_dir, "cam1")))
    pairs = [(t, left, right[t]) for t, left in camera_frames(os.path.join(mav_dir, "cam0")) if t in right]
    if not pairs:
        raise LayoutError(f"{mav_dir}: cam0 and cam1 share no timestamp")
    return sorted(pairs)


def imu_samples(mav_dir):
    """imu0/data.csv as an (N, 7) array [t (s), gx, gy, gz (rad/s), ax, ay, az (m/s²)]."""
    path = os.path.join(mav_dir, "imu0", "data.csv")
    samples = []
    for number, fields in _data_rows(path, 7):
        t = _nanoseconds(path, number, fields[0]) * 1e-9
        try:
            samples.append([t] + [float(x) for x in fields[1:]])
        except ValueError:
            raise LayoutError(f"{path}:{number}: expected six numbers after the timestamp") from None
    return np.array(samples)


def imu_between_frames(frame_times_s, imu, tolerance_s=0.0):
    """The IMU rows given with each frame, as ORB-SLAM3's stereo_inertial_euroc example gives
    them: none with the first frame; with each later frame, the rows not given yet up to its
    time, starting from the last row at or before the first frame. A row within `tolerance_s`
    after a frame counts as at its time (TUM frame stamps keep 6 decimals, the IMU's whole
    nanoseconds)."""
    times = imu[:, 0]
    if len(frame_times_s) and (times[0] > frame_times_s[0] + tolerance_s
                               or times[-1] < frame_times_s[-1] - tolerance_s):
        raise LayoutError(
            f"imu0 covers {times[0]:.3f}-{times[-1]:.3f} s, the frames {frame_times_s[0]:.3f}-{frame_times_s[-1]:.3f} s")
    first = (max(int(np.searchsorted(times, frame_times_s[0] + tolerance_s, side="right")) - 1, 0)
             if len(frame_times_s) else 0)
    batches = []
    for i, t in enumerate(frame_times_s):
        if i == 0:
            batches.append(imu[:0])
            continue
        end = int(np.searchsorted(times, t + tolerance_s, side="right"))
        batches.append(imu[first:end])
        first = max(first, end)
    return batches


def sensor_t_bs(sensor_yaml):
    """The 4x4 `T_BS` (sensor-to-body) of a EuRoC sensor.yaml."""
    with open(sensor_yaml) as f:
        text = f.read()
    at = text.find("T_BS:")
    start = text.find("[", at)
    end = text.find("]", start)
    if at < 0 or start < 0 or end < 0:
        raise LayoutError(f"{sensor_yaml}: no T_BS with a data: [...] list")
    try:
        values = [float(v) for v in text[start + 1:end].split(",")]
    except ValueError:
        raise LayoutError(f"{sensor_yaml}: T_BS data holds something other than numbers") from None
    if len(values) != 16:
        raise LayoutError(f"{sensor_yaml}: T_BS has {len(values)} numbers, expected 16")
    return np.array(values).reshape(4, 4)


def _rotation(qx, qy, qz, qw):
    q = np.array([qw, qx, qy, qz]) / np.linalg.norm([qw, qx, qy, qz])
    w, x, y, z = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def _quaternion(r):
    """(qx, qy, qz, qw) of a rotation matrix, qw ≥ 0."""
    k = np.array([
        [r[0, 0] - r[1, 1] - r[2, 2], r[1, 0] + r[0, 1], r[2, 0] + r[0, 2], r[2, 1] - r[1, 2]],
        [r[1, 0] + r[0, 1], r[1, 1] - r[0, 0] - r[2, 2], r[2, 1] + r[1, 2], r[0, 2] - r[2, 0]],
        [r[2, 0] + r[0, 2], r[2, 1] + r[1, 2], r[2, 2] - r[0, 0] - r[1, 1], r[1, 0] - r[0, 1]],
        [r[2, 1] - r[1, 2], r[0, 2] - r[2, 0], r[1, 0] - r[0, 1], r[0, 0] + r[1, 1] + r[2, 2]],
    ]) / 3.0
    values, vectors = np.linalg.eigh(k)
    q = vectors[:, np.argmax(values)]
    return q if q[3] >= 0 else -q


def body_trajectory_tum(euroc_lines, body_from_frame):
    """TUM lines `t tx ty tz qx qy qz qw` (seconds, world-from-body) from the lines ORB-SLAM3's
    SaveTrajectoryEuRoC writes (`t_ns tx ty tz qx qy qz qw`, world-from-frame, the frame being
    cam0 or the IMU): each pose is multiplied by `inverse(body_from_frame)`."""
    frame_from_body = np.linalg.inv(body_from_frame)
    out = []
    for number, line in enumerate(euroc_lines, 1):
        fields = line.split()
        if not fields or fields[0].startswith("#"):
            continue
        if len(fields) != 8:
            raise LayoutError(f"ORB-SLAM3 trajectory line {number}: {len(fields)} fields, expected 8")
        t_ns, tx, ty, tz, qx, qy, qz, qw = (float(v) for v in fields)
        world_from_frame = np.eye(4)
        world_from_frame[:3, :3] = _rotation(qx, qy, qz, qw)
        world_from_frame[:3, 3] = (tx, ty, tz)
        world_from_body = world_from_frame @ frame_from_body
        p = world_from_body[:3, 3]
        q = _quaternion(world_from_body[:3, :3])
        out.append(f"{t_ns * 1e-9:.9f} {p[0]:.9f} {p[1]:.9f} {p[2]:.9f} {q[0]:.9f} {q[1]:.9f} {q[2]:.9f} {q[3]:.9f}")
    return out
