#!/usr/bin/env bash
# Do the sensor effects hurt a real odometry, and how do they compare with the 2-D motion_blur at
# the same visual strength? Renders room0 clean, with `exposure` and `rolling_shutter` at
# hand-held values and with `motion_blur:1..5`, runs the OpenCV RGB-D odometry of
# examples/methods/ on each, and prints per setting the mean PSNR against the clean frames (the
# visual strength) and the ATE (`rslam eval`, SE(3) alignment).
#
#   scripts/validity-sensor-effects.sh [WORK_DIR]
#
# env: FRAMES=300 (first poses of room0's default path), CAMERA=tum (640x480; `replica` for
#      1200x680), PY=python3 with opencv-python-headless 5 and numpy (examples/methods/requirements.txt),
#      SETTINGS="clean exposure:10 exposure:20 rolling_shutter:30 motion_blur:1 ... motion_blur:5"
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
work=${1:-$(mktemp -d)}
frames=${FRAMES:-300}
camera=${CAMERA:-tum}
py=${PY:-python3}
settings=${SETTINGS:-"clean exposure:10 exposure:20 rolling_shutter:30 motion_blur:1 motion_blur:2 motion_blur:3 motion_blur:4 motion_blur:5"}
cargo build --release -q -p rslam-cli --manifest-path "$root/Cargo.toml"
rslam=$root/target/release/rslam
mkdir -p "$work"

echo "| setting | mean PSNR vs clean (dB) | ATE RMSE (cm) | odometry failures |"
echo "|---|--:|--:|--:|"
for setting in $settings; do
    name=$(echo "$setting" | tr ':@' '--')
    data=$work/$name
    args=(render --scene room0 --frames "$frames" --camera "$camera" --rate 20 --out "$data")
    [ "$setting" = clean ] || args+=(--perturb "$setting")
    [ -f "$data/rslam.b3sum" ] || "$rslam" "${args[@]}" > "$work/$name.render.log" 2>&1
    "$py" "$root/examples/methods/opencv_rgbd_odometry.py" --dataset "$data" \
        --out "$work/$name.est.txt" > "$work/$name.odometry.log" 2>&1
    "$rslam" eval "$work/$name.est.txt" "$data/traj.txt" --json > "$work/$name.eval.json"
    "$py" - "$work/clean" "$data" "$work/$name.eval.json" "$work/$name.odometry.log" "$setting" <<'EOF'
import glob, json, os, sys
import cv2
import numpy as np
clean, data, evaluation, log, setting = sys.argv[1:]
psnrs = []
for a in sorted(glob.glob(os.path.join(clean, "results", "frame*.jpg"))):
    b = os.path.join(data, "results", os.path.basename(a))
    x, y = cv2.imread(a).astype(np.float64), cv2.imread(b).astype(np.float64)
    mse = np.mean((x - y) ** 2)
    psnrs.append(float("inf") if mse == 0 else 10 * np.log10(255.0 ** 2 / mse))
finite = [p for p in psnrs if np.isfinite(p)]
psnr = f"{np.mean(finite):.1f}" if finite else "identical"
ate = 100 * json.load(open(evaluation))["ate"]["rmse"]
failures = sum("odometry failed" in line for line in open(log))
print(f"| {setting} | {psnr} | {ate:.2f} | {failures} |")
EOF
done
