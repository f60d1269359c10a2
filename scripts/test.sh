#!/usr/bin/env bash
# The whole test suite, on a fresh machine too: installs the Vulkan driver if missing, then
# builds and runs every test of the workspace (GPU tests run on lavapipe when there is no GPU),
# and ends with the total over all test binaries.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-system-deps.sh
log=$(mktemp)
trap 'rm -f "$log"' EXIT
set +e
cargo test --workspace --all-targets "$@" 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
set -e
passed=$(grep -aE '^test result:' "$log" | grep -aEo '[0-9]+ passed' | awk '{s += $1} END {print s + 0}')
failed=$(grep -aE '^test result:' "$log" | grep -aEo '[0-9]+ failed' | awk '{s += $1} END {print s + 0}')
echo "tests: $passed passed, $failed failed"
exit "$status"
