#!/usr/bin/env python3
"""Frame-to-frame RGB-D odometry (OpenCV 5: dense ICP + photometric) over an rslam dataset.

Usage: opencv_rgbd_odometry.py --dataset DIR --out ESTIMATE.txt [--map MAP.ply]

Reads the Replica layout (cam_params.json, results/) or the TUM layout (associations.txt,
orbslam3.yaml) and writes one camera-to-world pose per frame in TUM format, starting at identity.
A frame whose odometry fails keeps the previous pose (an identity step) and tracking goes on from
that frame, as a real VO does; the failures are logged.

With --map, it also writes the dense map: every frame's depth (every MAP_STRIDE-th pixel)
back-projected at its estimated pose and thinned to one point per MAP_VOXEL_M cube, as a PLY
point cloud. The map is in the scene's world frame, as NICE-SLAM and Co-SLAM write theirs: they
start at the ground truth's first pose, the one thing of the ground truth read here.
"""
import argparse
import glob
import json
import os
import sys
import time

import cv2
import numpy as np


def fail(msg, code=2):
    print(f"opencv_rgbd_odometry: {msg}", file=sys.stderr)
    sys.exit(code)


def replica(d):
    """-> (K, depth_scale, [(t, rgb, depth)]): frame i at i / rate_hz, as rslam eval stamps traj.txt."""
    with open(os.path.join(d, "cam_params.json")) as f:
        c = json.load(f)["camera"]
    rate = 20.0  # rslam eval's default for a traj.txt without a manifest
    manifest = os.path.join(d, "rslam.json")
    if os.path.isfile(manifest):
        with open(manifest) as f:
            rate = float(json.load(f)["rate_hz"])
    rgbs = sorted(glob.glob(os.path.join(d, "results", "frame*.jpg")) + glob.glob(os.path.join(d, "results", "frame*.png")))
    frames = []
    for i, rgb in enumerate(rgbs):
        n = os.path.basename(rgb)[len("frame"):].rsplit(".", 1)[0]
        frames.append((i / rate, rgb, os.path.join(d, "results", f"depth{n}.png")))
    return (c["fx"], c["fy"], c["cx"], c["cy"]), float(c["scale"]), frames


def tum(d):
    fs = cv2.FileStorage(os.path.join(d, "orbslam3.yaml"), cv2.FILE_STORAGE_READ)
    K = tuple(fs.getNode(k).real() for k in ("Camera1.fx", "Camera1.fy", "Camera1.cx", "Camera1.cy"))
    scale = fs.getNode("RGBD.DepthMapFactor").real()
    if not all(K) or not scale:
        fail(f"{d}/orbslam3.yaml lacks Camera1.fx/fy/cx/cy or RGBD.DepthMapFactor")
    frames = []
    with open(os.path.join(d, "associations.txt")) as f:
        for line in f:
            r = line.split()
            if r and not r[0].startswith("#"):
                frames.append((float(r[0]), os.path.join(d, r[1]), os.path.join(d, r[3])))
    return K, scale, frames


MAP_STRIDE = 8
MAP_VOXEL_M = 0.01


def first_ground_truth_pose(d):
    """Camera-to-world 4x4 of the first line of traj.txt (Replica, row-major) or groundtruth.txt
    (TUM: t tx ty tz qx qy qz qw)."""
    replica_traj = os.path.join(d, "traj.txt")
    tum_gt = os.path.join(d, "groundtruth.txt")
    path = replica_traj if os.path.isfile(replica_traj) else tum_gt
    if not os.path.isfile(path):
        fail(f"{d}: neither traj.txt nor groundtruth.txt, needed for the map's first pose")
    with open(path) as f:
        rows = [line.split() for line in f if line.strip() and not line.startswith("#")]
    if not rows:
        fail(f"{path}: no pose")
    v = [float(x) for x in rows[0]]
    if path == replica_traj:
        return np.array(v, np.float64).reshape(4, 4)
    (tx, ty, tz, qx, qy, qz, qw) = v[1:8]
    R = np.array([
        [1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
        [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
        [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)],
    ])
    pose = np.eye(4)
    pose[:3, :3], pose[:3, 3] = R, (tx, ty, tz)
    return pose


class PointMap:
    """Depth back-projected at the estimated poses, one point per voxel."""

    def __init__(self, K, shape):
        fx, fy, cx, cy = K
        h, w = shape
        v, u = np.mgrid[0:h:MAP_STRIDE, 0:w:MAP_STRIDE]
        self.rays = np.stack([(u - cx) / fx, (v - cy) / fy, np.ones_like(u, np.float64)], -1).reshape(-1, 3)
        self.pixels = (v.ravel(), u.ravel())
        self.voxels = {}

    def add(self, depth_m, world_from_camera):
        z = depth_m[self.pixels]
        seen = z > 0
        points = self.rays[seen] * z[seen, None]
        world = points @ world_from_camera[:3, :3].T + world_from_camera[:3, 3]
        for key, p in zip(map(tuple, np.floor(world / MAP_VOXEL_M).astype(np.int64)), world):
            self.voxels.setdefault(key, p)

    def write(self, path):
        points = np.array(list(self.voxels.values()), np.float32).reshape(-1, 3)
        header = (
            "ply\nformat binary_little_endian 1.0\n"
            f"element vertex {len(points)}\nproperty float x\nproperty float y\nproperty float z\nend_header\n"
        )
        with open(path, "wb") as f:
            f.write(header.encode())
            f.write(points.astype("<f4").tobytes())
        return len(points)


def quaternion(R):
    """Rotation matrix -> (qx, qy, qz, qw) through the axis-angle vector."""
    r = cv2.Rodrigues(R)[0].ravel()
    angle = np.linalg.norm(r)
    axis = r / angle if angle > 0 else r
    return (*(axis * np.sin(angle / 2)), np.cos(angle / 2))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dataset", required=True, help="dataset folder (Replica or TUM layout)")
    ap.add_argument("--out", required=True, help="estimate to write (TUM trajectory)")
    ap.add_argument("--map", help="dense map to write (PLY point cloud, scene world frame)")
    a = ap.parse_args()  # exits 2 on bad arguments

    if os.path.isfile(os.path.join(a.dataset, "cam_params.json")):
        (fx, fy, cx, cy), scale, frames = replica(a.dataset)
    elif os.path.isfile(os.path.join(a.dataset, "associations.txt")):
        (fx, fy, cx, cy), scale, frames = tum(a.dataset)
    else:
        fail(f"{a.dataset}: neither cam_params.json (Replica layout) nor associations.txt (TUM layout)")
    if not frames:
        fail(f"{a.dataset}: no frames")

    settings = cv2.OdometrySettings()
    settings.setCameraMatrix(np.array([[fx, 0, cx], [0, fy, cy], [0, 0, 1]], np.float32))
    odometry = cv2.Odometry(cv2.OdometryType_RGB_DEPTH, settings, cv2.OdometryAlgoType_COMMON)

    start = time.time()
    anchor = first_ground_truth_pose(a.dataset) if a.map else None
    point_map = None
    pose = np.eye(4)
    prev = None
    lost = 0
    with open(a.out, "w") as out:
        for i, (t, rgb_path, depth_path) in enumerate(frames):
            bgr = cv2.imread(rgb_path, cv2.IMREAD_COLOR)
            depth = cv2.imread(depth_path, cv2.IMREAD_UNCHANGED)
            if bgr is None or depth is None:
                fail(f"cannot read {rgb_path} or {depth_path}", 1)
            # the frame takes depth in metres (float32) and converts BGR to gray itself
            frame = cv2.OdometryFrame(depth.astype(np.float32) / scale, bgr)
            odometry.prepareFrame(frame)
            if prev is not None:
                # compute(src, dst) gives Rt with Rt * p_src = p_dst: the current camera in the previous one
                ok, Rt = odometry.compute(frame, prev)
                if ok:
                    pose = pose @ Rt
                else:
                    lost += 1
                    print(f"frame {i} (t={t:.6f}): odometry failed, pose kept", file=sys.stderr)
            prev = frame
            if anchor is not None:
                point_map = point_map or PointMap((fx, fy, cx, cy), depth.shape)
                point_map.add(depth.astype(np.float64) / scale, anchor @ pose)
            out.write("%.6f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n" % (t, *pose[:3, 3], *quaternion(pose[:3, :3])))
    if point_map is not None:
        print(f"map: {point_map.write(a.map)} points", file=sys.stderr)
    secs = time.time() - start
    print(f"{len(frames)} frames, {lost} failed steps, {secs:.1f} s ({secs / len(frames):.3f} s/frame)", file=sys.stderr)


if __name__ == "__main__":
    main()
