#!/usr/bin/env bash
# Fuzzes every input parser for SECONDS each (default 10; as many targets at once as there are
# cores) with mutations of the seed files in crates/fuzz/corpus, and prints per target the
# executions, the distinct errors and the crashes (panics, aborts, allocations over the 1 GiB
# cap, inputs over 5 s); crash inputs are saved in target/fuzz/crashes/. Exits 1 if anything
# crashed.
#   scripts/fuzz.sh 60           # a minute per target
#   scripts/fuzz.sh 5 ply obj    # only these targets (scripts/fuzz.sh 0 lists them)
# A saved crash runs again with: target/debug/rslam-fuzz replay TARGET target/fuzz/crashes/FILE.bin
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-10}
shift || true
# A dev build, or the binary in $RSLAM_BIN_DIR (CI: the one scripts/test.sh built).
fuzz=$(scripts/built-binary.sh rslam-fuzz rslam-fuzz --quiet)
if [ "$seconds" = 0 ]; then
    exec "$fuzz" list
fi
exec "$fuzz" run --seconds "$seconds" --out target/fuzz "$@"
