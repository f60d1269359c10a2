#!/usr/bin/env python3
"""Is there floor for a walker in front of the camera? Along a camera path, the share of frames
with walkable floor within 0.5 rad of the camera's axis (over the floor) at each band of
distances from the camera to a walker's body edge. Walkable: 5 cm cells 0.3 m or more from
anything 5 cm to 1.9 m high in the scene's mesh (a walker's radius and the planner's margin),
in the largest such region. A rough, independent look at the planner's floor map, for the book
(docs/src/validity.md), not its exact rule. Needs NumPy and SciPy (validity.sh's venv has them).

Usage: floor-in-view.py SCENE.ply groundtruth.txt
  SCENE.ply:       rslam scene export SCENE --out SCENE.ply
  groundtruth.txt: a TUM trajectory, e.g. from rslam render --scene SCENE --camera tum
                   --frames 400 --format tum --out D (D/groundtruth.txt)
"""
import sys

import numpy as np
from scipy import ndimage
from scipy.spatial.transform import Rotation

CELL_M = 0.05
HEIGHTS_M = (0.05, 1.9)
CLEARANCE_M = 0.30
BODY_RADIUS_M = 0.25
HALF_ANGLE = 0.5
# Body-edge distances from the camera, metres: each band's near end; bands are 0.3 m wide.
BANDS_M = (0.4, 0.7, 1.0, 1.5, 2.0)
BAND_WIDTH_M = 0.3
SAMPLE_SPACING_M = 0.02


def read_ply(path):
    """Vertices and triangles of a binary little-endian PLY as rslam scene export writes it."""
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            line = f.readline()
            if not line:
                sys.exit(f"{path}: no end_header: not a PLY file")
            header += line
        text = header.decode()
        vertices = int(text.split("element vertex ")[1].split()[0])
        faces = int(text.split("element face ")[1].split()[0])
        types = {"float": "<f4", "double": "<f8", "uchar": "u1"}
        props = [l.split()[1:] for l in text.splitlines() if l.startswith("property") and "list" not in l]
        vertex = np.dtype([(name, types[kind]) for kind, name in props])
        v = np.frombuffer(f.read(vertices * vertex.itemsize), dtype=vertex)
        face = np.dtype([("n", "u1"), ("i", "<i4", 3)])
        triangles = np.frombuffer(f.read(faces * face.itemsize), dtype=face)["i"]
    return np.stack([v["x"], v["y"], v["z"]], 1).astype(np.float64), triangles


def walkable_cells(vertices, triangles):
    """Centres of the walkable cells (x, y), metres."""
    low = vertices.min(0)[:2] - 2 * CELL_M
    size = np.ceil((vertices.max(0)[:2] + 2 * CELL_M - low) / CELL_M).astype(int) + 1
    occupied = np.zeros(size, bool)
    corners = vertices[triangles]
    for start in range(0, len(corners), 20000):
        t = corners[start : start + 20000]
        longest = np.linalg.norm(t[:, [1, 2, 2]] - t[:, [0, 0, 1]], axis=2).max()
        n = int(np.ceil(longest / SAMPLE_SPACING_M)) + 1
        a, b = np.meshgrid(np.linspace(0, 1, n), np.linspace(0, 1, n))
        inside = a + b <= 1
        a, b = a[inside], b[inside]
        points = (t[:, None, 0] + a[None, :, None] * (t[:, 1] - t[:, 0])[:, None]
                  + b[None, :, None] * (t[:, 2] - t[:, 0])[:, None]).reshape(-1, 3)
        points = points[(points[:, 2] > HEIGHTS_M[0]) & (points[:, 2] < HEIGHTS_M[1])]
        cells = np.floor((points[:, :2] - low) / CELL_M).astype(int)
        occupied[cells[:, 0], cells[:, 1]] = True
    free = ndimage.distance_transform_edt(~occupied) * CELL_M >= CLEARANCE_M
    regions, _ = ndimage.label(free)
    sizes = np.bincount(regions.ravel())
    sizes[0] = 0
    return np.argwhere(regions == sizes.argmax()) * CELL_M + low + CELL_M / 2


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    cells = walkable_cells(*read_ply(sys.argv[1]))
    path = np.loadtxt(sys.argv[2], comments="#", ndmin=2)
    if path.shape[1] != 8:
        sys.exit(f"{sys.argv[2]}: expected TUM lines 'timestamp tx ty tz qx qy qz qw'")
    seen = []
    for row in path:
        axis = Rotation.from_quat(row[4:8]).as_matrix()[:2, 2]
        axis /= np.linalg.norm(axis)
        to = cells - row[1:3]
        distance = np.linalg.norm(to, axis=1)
        ahead = to @ axis >= distance * np.cos(HALF_ANGLE)
        edge = distance - BODY_RADIUS_M
        seen.append([(ahead & (edge >= b) & (edge < b + BAND_WIDTH_M)).any() for b in BANDS_M])
    shares = np.mean(seen, axis=0)
    print("body edge (m)   " + "".join(f"{b:.1f}-{b + BAND_WIDTH_M:.1f}".rjust(9) for b in BANDS_M))
    print("share of frames " + "".join(f"{s:9.2f}" for s in shares))


if __name__ == "__main__":
    main()
