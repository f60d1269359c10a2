#!/usr/bin/env bash
# The real-photograph bands of `rslam scene stats` (crates/eval/src/image_stats/target.rs): runs
# it on the indoor photographs scikit-image ships in skimage/data, no download beyond the wheel.
#
#   scripts/realism-target.sh [RSLAM]      (default: target/release/rslam)
#
# Prints each photograph's statistics and, per statistic, the least and most over them.
set -euo pipefail
rslam=${1:-target/release/rslam}
work=$(mktemp -d)
python3 -m venv "$work/venv"
"$work/venv/bin/pip" install -q scikit-image==0.26.0
data=$("$work/venv/bin/python" -c 'import os, skimage; print(os.path.join(os.path.dirname(skimage.__file__), "data"))')
mkdir "$work/photos"
for name in motorcycle_left motorcycle_right coffee chelsea; do cp "$data/$name.png" "$work/photos/"; done
"$rslam" scene stats "$work/photos" --json "$work/stats.json" | head -5
python3 - "$work/stats.json" <<'PY'
import json, sys
frames = json.load(open(sys.argv[1]))["frames"]
for key in ["weak_corner_density", "corner_strength_p50", "strong_corners",
            "contrast_p10", "contrast_p50", "contrast_p90"]:
    values = [f["stats"][key] for f in frames]
    print(f"{key:22} {min(values):9.4f} {max(values):9.4f}")
PY
rm -rf "$work"
