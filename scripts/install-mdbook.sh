#!/usr/bin/env bash
# Installs mdBook (the user guide's builder) with cargo into ~/.cargo/bin when it is missing.
set -euo pipefail
export PATH=$HOME/.cargo/bin:$PATH
command -v mdbook >/dev/null && exit 0
echo "installing mdBook"
cargo install mdbook --locked --no-default-features --features search ||
  cargo install mdbook --locked
