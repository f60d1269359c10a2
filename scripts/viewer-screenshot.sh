#!/usr/bin/env bash
# Takes the screenshot of `rslam view` from the real program in a real window under
# Xvfb (a virtual X server; lavapipe renders when there is no GPU) and writes
# docs/src/images/viewer.png (the picture in the book's viewer chapter).
# Run: scripts/viewer-screenshot.sh [OUT.png]   (needs the xvfb package: apt-get install xvfb)
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-docs/src/images/viewer.png}
command -v xvfb-run >/dev/null || { echo "xvfb-run not found: apt-get install xvfb" >&2; exit 1; }
# The dev profile compiles dependencies at opt-level 3 (root Cargo.toml), enough for a picture.
cargo build -p rslam-cli
rm -f "$out"
# The window's size in pixels is the screen's; -ac: no access control on this private server.
xvfb-run --auto-servernum --server-args="-screen 0 1600x900x24 -ac" \
  target/debug/rslam view --scene room0 --frames 200 \
    --perturb 'fog:3,gaussian_noise:2@dynamic,depth_missing:3,misalign:2' --seed 4 \
    --window 1600 900 --screenshot "$out"
[ -s "$out" ] || { echo "no screenshot was written to $out" >&2; exit 1; }
echo "wrote $out"
