#!/usr/bin/env bash
# Speed figures on a machine with a real GPU and no Rust toolchain, from release binaries built
# elsewhere (docs/src/performance.md holds what it printed on an H100, with date and driver):
#
#   scripts/bench-gpu.sh BIN_DIR [WORK_DIR [bench_corruptions.py options]]
#
# BIN_DIR holds `rslam`, `png_roundtrip` (cargo build --release -p rslam-core --example
# png_roundtrip), `splat_fps` (cargo build --release -p rslam-render --example splat_fps) and the
# bench binaries `render` and `corruptions` (cargo bench --no-run -p
# rslam-render -p rslam-perturb; copied out of target/release/deps without their hash suffix).
# `rslam` links fontconfig and freetype (plot fonts): a machine without them needs libfontconfig1
# and libfreetype6 unpacked somewhere on LD_LIBRARY_PATH.
# Prints, in order: GPU time per corruption at severity 3 and the readbacks; render only and
# render + readback of room0; a capture of room0 as 0.5 M and 3 M Gaussians; whole `rslam render` of room0's 2000 frames in the Replica and TUM
# layouts (frames/s and bytes per frame, encoding on all cores); shard 0 of 200 of the robust-slam
# matrix (its frames/s times 1,966,000 frames is the whole matrix's time); then, where this python has
# imagecorruptions and albumentations, scripts/bench_corruptions.py over 20 of those frames, 600
# frames per rslam run (with 40, a GPU's few ms a frame drown in the start-up's noise).
set -euo pipefail
bin=$(realpath "$1")
work=${2:-$(mktemp -d)}
root=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$work"
export CRITERION_HOME=$work/criterion

# criterion's report, one line per benchmark: its name and the middle of its time estimate.
summary() {
    awk '/^[A-Za-z_0-9]+\// { name = $1 }
         /time:/ { for (i = 1; i <= NF; i++) if ($i == "time:") print name, $(i + 3), $(i + 4) }'
}

echo "== $(date -u +%F); cores: $(nproc); GPU, driver: $(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null || echo '?')"
echo "== GPU work per corruption (record, submit, wait), severity 3; readbacks"
"$bin/corruptions" --bench 'gpu_1200x680/.*/3$|readback' 2>&1 | tee "$work/corruptions.log" | summary
echo "== room0 render (render bench)"
"$bin/render" --bench 2>&1 | tee "$work/render.log" | summary
echo "== a capture of room0 at 1200x680 (splat_fps)"
"$bin/splat_fps" 500000 100
"$bin/splat_fps" 3000000 50

for layout in replica tum; do
    out=$work/room0-$layout
    rm -rf "$out"
    camera=replica
    echo "== rslam render --scene room0 --format $layout --camera $camera (2000 frames)"
    "$bin/rslam" render --scene room0 --format "$layout" --camera "$camera" --out "$out" 2>&1 | tail -1
done

echo "== the robust-slam matrix: shard 0 of 200 (two sequences), --jobs 4"
rm -rf "$work/matrix"
"$bin/rslam" suite init --out "$work/matrix" | tail -1
start=$(date +%s.%N)
"$bin/rslam" suite run "$work/matrix" --shard 0/200 --jobs 4 2>&1 | tail -3
end=$(date +%s.%N)
"$bin/rslam" suite status "$work/matrix" | tail -1
echo "shard wall: $(python3 -c "print(round($end - $start, 1))") s"
rm -rf "$work/matrix"

if python3 -c 'import imagecorruptions, albumentations' 2>/dev/null; then
    frames=$work/frames
    mkdir -p "$frames"
    find "$work/room0-tum/rgb" -name '*.png' | sort | awk 'NR % 100 == 1' | head -20 \
        | xargs -I{} cp {} "$frames/"
    echo "== file in -> file out per corruption (scripts/bench_corruptions.py)"
    python3 "$root/scripts/bench_corruptions.py" "$bin/rslam" "$bin/png_roundtrip" "$frames" --frames 600 "${@:3}"
fi
