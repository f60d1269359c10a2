"""A stand-in SLAM method for `rslam suite search` tests whose failure rule is known: it measures
the noise of the colour frames from their pixels and fails when it exceeds a threshold.

    python3 noise_method.py DATASET ESTIMATE CLEAN THRESHOLD [SPREAD SEQUENCE REPEAT]

The noise level is the MAD-estimated standard deviation (in [0, 1] units) of each frame minus
the same frame of CLEAN (the clean dataset of the same path), over the pixels whose clean value
lies in [0.4, 0.6], where clipping does not reach the median. Above THRESHOLD it exits 1; else it
writes the ground truth as its estimate. With SPREAD > 0 it fails at random near the threshold,
with probability 1 / (1 + exp(-(noise - THRESHOLD) / SPREAD)), seeded by SEQUENCE and REPEAT.
Standard library only (zlib for the PNGs).
"""

import hashlib
import math
import os
import shutil
import struct
import sys
import zlib


def read_png(path):
    """(width, height, channels, bytes) of an 8-bit greyscale, RGB or RGBA PNG."""
    with open(path, "rb") as f:
        data = f.read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    at, idat = 8, b""
    while at < len(data):
        (length,) = struct.unpack(">I", data[at : at + 4])
        kind = data[at + 4 : at + 8]
        body = data[at + 8 : at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            assert depth == 8, f"{path}: bit depth {depth}"
            channels = {0: 1, 2: 3, 6: 4}[colour]
        elif kind == b"IDAT":
            idat += body
        at += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, line = raw[start], bytearray(raw[start + 1 : start + 1 + stride])
        for i in range(stride):
            left = line[i - channels] if i >= channels else 0
            up = previous[i]
            corner = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + left) & 255
            elif kind == 2:
                line[i] = (line[i] + up) & 255
            elif kind == 3:
                line[i] = (line[i] + (left + up) // 2) & 255
            elif kind == 4:
                p = left + up - corner
                pa, pb, pc = abs(p - left), abs(p - up), abs(p - corner)
                predictor = left if pa <= pb and pa <= pc else (up if pb <= pc else corner)
                line[i] = (line[i] + predictor) & 255
        rows.append(bytes(line))
        previous = line
    return width, height, channels, b"".join(rows)


def noise_level(dataset, clean):
    differences = []
    names = sorted(os.listdir(os.path.join(clean, "rgb")))
    assert names == sorted(os.listdir(os.path.join(dataset, "rgb"))), "different frames"
    for name in names:
        _, _, _, a = read_png(os.path.join(dataset, "rgb", name))
        _, _, _, b = read_png(os.path.join(clean, "rgb", name))
        differences += [x - y for x, y in zip(a, b) if 102 <= y <= 153]
    differences.sort()
    centre = differences[len(differences) // 2]
    deviations = sorted(abs(d - centre) for d in differences)
    return 1.4826 * deviations[len(deviations) // 2] / 255.0


def main():
    dataset, estimate, clean, threshold = sys.argv[1:5]
    threshold = float(threshold)
    spread = float(sys.argv[5]) if len(sys.argv) > 5 else 0.0
    noise = noise_level(dataset, clean)
    print(f"noise {noise:.5f}, threshold {threshold}", file=sys.stderr)
    if spread > 0:
        key = f"{sys.argv[6]}/{sys.argv[7]}".encode()
        u = int.from_bytes(hashlib.sha256(key).digest()[:8], "big") / 2.0**64
        fails = u < 1.0 / (1.0 + math.exp(-(noise - threshold) / spread))
    else:
        fails = noise > threshold
    if fails:
        sys.exit(1)
    shutil.copy(os.path.join(dataset, "groundtruth.txt"), estimate)


main()
