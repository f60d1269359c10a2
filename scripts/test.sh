#!/usr/bin/env bash
# The whole test suite, on a fresh machine too: installs the Vulkan driver if missing, then
# builds and runs every test of the workspace (GPU tests run on lavapipe when there is no GPU).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-system-deps.sh
cargo test --workspace --all-targets "$@"
