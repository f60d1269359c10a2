#!/usr/bin/env bash
# Times rslam's eval beside evo 1.38.1 on the same 100 000-pose TUM pair.
#
#   crates/eval/benches/evo_compare.sh [EVO_BIN_DIR]
#
# EVO_BIN_DIR holds evo_ape / evo_rpe (default: on PATH), e.g. from
#   python3 -m venv /tmp/evo && /tmp/evo/bin/pip install evo==1.38.1
# The pair is written with the Python next to evo (numpy), then rslam is timed by the criterion
# bench `eval_throughput` (from-files case: parsing + association + SE(3) + ATE + RPE) and evo by
# wall-clock time of `evo_ape -a` plus `evo_rpe` (translation and angle), which together compute
# what one `rslam eval` prints.
set -euo pipefail
evo_bin=${1:-$(dirname "$(command -v evo_ape)")}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
"$evo_bin/python" - "$dir" <<'PY'
import sys, numpy as np
d = sys.argv[1]
n, rate = 100_000, 100.0
rng = np.random.default_rng(0)
def write(path, t, wobble):
    s = t
    xyz = np.stack([3 * np.cos(0.05 * s) + wobble, 2 * np.sin(0.05 * s), 0.02 * s], 1)
    yaw = 0.3 * s + wobble
    q = np.stack([np.zeros(n), np.zeros(n), np.sin(yaw / 2), np.cos(yaw / 2)], 1)
    with open(path, "w") as f:
        f.write("# t tx ty tz qx qy qz qw\n")
        np.savetxt(f, np.column_stack([t, xyz, q]), fmt=["%.6f"] + ["%.9f"] * 7)
t = np.arange(n) / rate
write(f"{d}/gt.txt", t, 0.0)
te = t + rng.uniform(-0.003, 0.003, n)
write(f"{d}/est.txt", te, 0.01 * np.sin(3.1 * te))
PY
time_evo() {
    local start end
    start=$(date +%s.%N)
    # evo writes ~/.evo on first use: give it a scratch home.
    HOME=$dir MPLBACKEND=Agg "$evo_bin/evo_ape" tum "$dir/gt.txt" "$dir/est.txt" -a > /dev/null
    HOME=$dir MPLBACKEND=Agg "$evo_bin/evo_rpe" tum "$dir/gt.txt" "$dir/est.txt" > /dev/null
    HOME=$dir MPLBACKEND=Agg "$evo_bin/evo_rpe" tum "$dir/gt.txt" "$dir/est.txt" -r angle_deg > /dev/null
    end=$(date +%s.%N)
    echo "evo_ape -a + evo_rpe (trans) + evo_rpe (angle_deg): $(echo "$end - $start" | bc) s"
}
time_evo
RSLAM_BENCH_FILES=$dir cargo bench -p rslam-eval --bench eval_throughput -- from_tum_files
