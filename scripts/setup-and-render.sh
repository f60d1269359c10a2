#!/usr/bin/env bash
# One-time set-up (system packages, release build) and the main job: the built-in room0 scene
# rendered along its default trajectory into out/room0 (Replica layout).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-system-deps.sh
cargo build --release --bin rslam
target/release/rslam render --scene room0 --out out/room0 "$@"
