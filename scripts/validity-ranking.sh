#!/usr/bin/env bash
# The validity protocol of docs/src/validity.md, per scene: the paper's 16 corruptions at severity
# 3 beside a clean row, ORB-SLAM3 RGB-D twice on each (../shared/validity/validity.sh), the clean
# sequence up to CLEAN_RUNS times, then Spearman's rho against the paper (rank.py) and how many runs
# ORB-SLAM3 aborted ("SO3::exp failed"). By hand only: it needs ../shared/validity and about 35
# minutes a scene on 2 cores.
#
#   scripts/validity-ranking.sh WORK_DIR SCENE...     # e.g. scripts/validity-ranking.sh /tmp/v room0 office1
#
# env: CLEAN_RUNS=20, FRAMES=400, FULL=1 (the whole default path instead of FRAMES; about five times
# as long), RUN_LIMIT=600 (seconds an ORB-SLAM3 run may take; a longer one is killed and counts as
# failed, as an abort does), RSLAM=target/release/rslam (built if missing). Writes
# WORK_DIR/SCENE/{table.md,rank.txt} and prints one line per scene.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
validity=$root/../shared/validity
[ $# -ge 2 ] || { echo "usage: $0 WORK_DIR SCENE..." >&2; exit 2; }
[ -x "$validity/validity.sh" ] || { echo "$validity/validity.sh: not found (the validity kit lives beside the repository)" >&2; exit 1; }
work=$(mkdir -p "$1" && cd "$1" && pwd); shift
rslam=${RSLAM:-$root/target/release/rslam}
[ -x "$rslam" ] || cargo build --release -q --bin rslam --manifest-path "$root/Cargo.toml"
corruptions="motion_blur defocus_blur gaussian_blur glass_blur gaussian_noise shot_noise impulse_noise
  speckle_noise fog frost snow spatter brightness contrast jpeg_compression pixelate"
# validity.sh renders the whole default path for a setting named with a /full suffix.
whole=
if [ "${FULL:-0}" = 1 ]; then whole=/full; fi
settings=clean$whole
for c in $corruptions; do settings="$settings $c:3$whole"; done

# ORB-SLAM3 can hang after a loop closure (20 minutes at no CPU on office2's whole path) and
# validity.sh sets no time limit, so a watchdog kills every run of this job older than RUN_LIMIT and
# says so in the run's log. The limit counts wall time: a job paused with SIGSTOP loses its run.
limit=${RUN_LIMIT:-600}
killed_note="killed by validity-ranking.sh"
kill_overdue_runs() {
    while sleep 15; do
        ps -eo pid=,etimes=,args= | awk -v lim="$limit" -v work="$work" '
            $2 > lim && index($0, work) { for (i = 3; i < NF; i++) if ($i ~ /run_orbslam3\.py$/) print $1, $(i + 2) }' |
            while read -r pid out; do
                kill -KILL "$pid" 2>/dev/null && echo "$killed_note after ${limit} s (RUN_LIMIT)" >> "$out.log"
            done
    done
}
kill_overdue_runs &
watchdog=$!
trap 'kill $watchdog 2>/dev/null' EXIT

cd "$root"
for scene in "$@"; do
    w=$work/$scene
    mkdir -p "$w"
    common=(env RSLAM="$rslam" FRAMES="${FRAMES:-400}" SCENE="$scene" KEEP=0)
    "${common[@]}" RUNS=2 SETTINGS="$settings" "$validity/validity.sh" "$w" > "$w/log" 2>&1
    "${common[@]}" RUNS="${CLEAN_RUNS:-20}" SETTINGS="clean$whole" "$validity/validity.sh" "$w" > "$w/clean.log" 2>&1
    "${PY:-${XDG_CACHE_HOME:-$HOME/.cache}/rslam-validity/venv/bin/python}" "$validity/summarize.py" "$w" $settings |
        sed "s#^| \([a-z_:0-9]*\)$whole |#| \1 |#" > "$w/table.md"
    python3 "$validity/rank.py" "$w/table.md" 3 > "$w/rank.txt"
    aborts=$({ grep -l "SO3::exp failed" "$w"/runs/*/*.log || true; } | wc -l)
    killed=$({ grep -lF "$killed_note" "$w"/runs/*/*.log || true; } | wc -l)
    runs=$(ls "$w"/runs/*/*.log | wc -l)
    echo "$scene: $(head -1 "$w/rank.txt"); ORB-SLAM3 aborted in $aborts and was killed in $killed of $runs runs ($w/table.md)"
done
