#!/usr/bin/env bash
# One run, one table: every image corruption file in -> file out with `rslam perturb` beside
# imagecorruptions and albumentations (ms/frame, ratios, medians) and beside rslam's own PNG
# decode + encode, the I/O limit. Takes about 15 minutes on 2 cores.
#
#   scripts/bench-corruptions.sh [FRAME_DIR] [-- bench_corruptions.py options]
#
# FRAME_DIR holds PNG frames; without it, 20 frames of room0 are rendered at 1200x680 (the
# Replica camera). The references are installed into target/bench-venv on the first run
# (imagecorruptions-imaug 1.1.5, the maintained fork of imagecorruptions; albumentations 2.0.8;
# OpenCV and Pillow). Options (scripts/bench_corruptions.py --help): --corruptions a,b,
# --severity, --frames, --ref-frames, --repeats.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
frame_dir=""
if [ $# -gt 0 ] && [ "$1" != "--" ]; then
    frame_dir=$(realpath "$1")
    shift
fi
[ "${1:-}" != "--" ] || shift

cargo build --release -q -p rslam-cli --manifest-path "$root/Cargo.toml"
cargo build --release -q -p rslam-core --example png_roundtrip --manifest-path "$root/Cargo.toml"
release=$root/target/release

venv=$root/target/bench-venv
if ! "$venv/bin/python" -c 'import imagecorruptions, albumentations, cv2, PIL' 2>/dev/null; then
    python3 -m venv --clear "$venv"
    pip=("$venv/bin/python" -m pip --disable-pip-version-check -q)
    "${pip[@]}" install opencv-python-headless scikit-image scipy numba Pillow albumentations==2.0.8
    # Its requirement opencv-python needs libGL; the headless build is the same library.
    "${pip[@]}" install --no-deps imagecorruptions-imaug==1.1.5
fi

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
if [ -z "$frame_dir" ]; then
    "$release/rslam" render --scene room0 --frames 20 --format tum --camera replica \
        --out "$work/room0" > /dev/null 2>&1
    frame_dir=$work/room0/rgb
fi
"$venv/bin/python" "$root/scripts/bench_corruptions.py" "$release/rslam" \
    "$release/examples/png_roundtrip" "$frame_dir" "$@"
