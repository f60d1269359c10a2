#!/usr/bin/env bash
# File in -> file out speed of `rslam perturb` on a folder of PNG frames, beside imagecorruptions
# on the same frames (PNG read, corrupt, PNG write, per frame, with PIL as its users do).
#
#   crates/perturb/benches/imagecorruptions_compare.sh FRAME_DIR [CORRUPTIONS] [SEVERITY]
#
# FRAME_DIR holds PNG frames (e.g. 1200x680 renders); CORRUPTIONS is a comma list (default: all
# 19 image corruptions); SEVERITY defaults to 3. FRAMES (default 100) frames are perturbed,
# cycling through FRAME_DIR. rslam's figure is its steady state: (time for FRAMES frames - time
# for 1 frame) / (FRAMES - 1), so start-up (adapter, shader compilation, frost's per-seed texture)
# is left out; the 1-frame time is shown beside it. With IC_PYTHON set to a Python that can
# `import imagecorruptions` (1.1.2 needs small fixes for numpy 2 / scikit-image 0.26), the median
# of IC_FRAMES (default 3) frames of imagecorruptions is timed too, without its import time.
set -euo pipefail
frame_dir=$(realpath "$1")
corruptions=${2:-gaussian_noise,shot_noise,impulse_noise,speckle_noise,defocus_blur,glass_blur,motion_blur,gaussian_blur,snow,frost,fog,spatter,brightness,contrast,jpeg_compression,pixelate,zoom_blur,saturate,elastic_transform}
severity=${3:-3}
frames=${FRAMES:-100}
ic_frames=${IC_FRAMES:-3}
root=$(cd "$(dirname "$0")/../../.." && pwd)
cargo build --release -q -p rslam-cli --manifest-path "$root/Cargo.toml"
rslam=$root/target/release/rslam
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mapfile -t sources < <(find "$frame_dir" -maxdepth 1 -name '*.png' | sort)
[ ${#sources[@]} -gt 0 ] || { echo "$frame_dir: no .png frames" >&2; exit 2; }
mkdir "$work/many" "$work/one"
for ((i = 0; i < frames; i++)); do
    ln -s "${sources[i % ${#sources[@]}]}" "$(printf '%s/many/%05d.png' "$work" "$i")"
done
ln -s "${sources[0]}" "$work/one/00000.png"

seconds() {
    local start end
    rm -rf "$work/out"
    start=$(date +%s.%N)
    "$rslam" perturb --input "$1" --out "$work/out" --perturb "$2" > /dev/null 2>&1
    end=$(date +%s.%N)
    echo "$end - $start" | bc -l
}

reference_ms() {
    [ -n "${IC_PYTHON:-}" ] || { echo "-"; return; }
    "$IC_PYTHON" - "$1" "$severity" "$work/ic" "${sources[@]:0:$ic_frames}" <<'PY'
import os, sys, time
import numpy as np
from PIL import Image
from imagecorruptions import corrupt
name, severity, out, files = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4:]
os.makedirs(out, exist_ok=True)
times = []
for f in files:
    start = time.perf_counter()
    x = np.array(Image.open(f).convert("RGB"))
    y = corrupt(x, severity=severity, corruption_name=name)
    Image.fromarray(np.uint8(y)).save(os.path.join(out, os.path.basename(f)))
    times.append(time.perf_counter() - start)
print(f"{1e3 * np.median(times):.0f}")
PY
}

echo "| corruption | rslam ms/frame | rslam 1 frame, ms | imagecorruptions ms/frame | speed-up |"
echo "|---|---|---|---|---|"
ratios=()
for name in ${corruptions//,/ }; do
    one=$(seconds "$work/one" "$name:$severity")
    many=$(seconds "$work/many" "$name:$severity")
    steady=$(echo "1000 * ($many - $one) / ($frames - 1)" | bc -l)
    reference=$(reference_ms "$name")
    ratio="-"
    if [ "$reference" != "-" ]; then
        ratio=$(echo "$reference / $steady" | bc -l)
        ratios+=("$ratio")
        ratio=$(printf '%.1f×' "$ratio")
    fi
    printf '| %s | %.1f | %.0f | %s | %s |\n' "$name" "$steady" "$(echo "1000 * $one" | bc -l)" "$reference" "$ratio"
done
if [ ${#ratios[@]} -gt 0 ]; then
    printf '%s\n' "${ratios[@]}" | sort -g | awk '{r[NR] = $1} END {
        m = (NR % 2) ? r[(NR + 1) / 2] : (r[NR / 2] + r[NR / 2 + 1]) / 2
        printf "median speed-up %.1f×, slowest %.1f× (%d corruptions)\n", m, r[1], NR }'
fi
