#!/usr/bin/env python3
"""Frame-to-frame RGB-D odometry (OpenCV 5: dense ICP + photometric) over an rslam dataset.

Usage: opencv_rgbd_odometry.py --dataset DIR --out ESTIMATE.txt

Reads the Replica layout (cam_params.json, results/) or the TUM layout (associations.txt,
orbslam3.yaml) and writes one camera-to-world pose per frame in TUM format, starting at identity.
Ground truth is never read. A frame whose odometry fails keeps the previous pose (an identity
step) and tracking goes on from that frame, as a real VO does; the failures are logged.
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
            out.write("%.6f %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n" % (t, *pose[:3, 3], *quaternion(pose[:3, :3])))
    secs = time.time() - start
    print(f"{len(frames)} frames, {lost} failed steps, {secs:.1f} s ({secs / len(frames):.3f} s/frame)", file=sys.stderr)


if __name__ == "__main__":
    main()
