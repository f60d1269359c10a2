#!/usr/bin/env bash
# Prints the path of a binary the test scripts run. With RSLAM_BIN_DIR set (.ci/run sets it to
# target/debug, which `cargo test --workspace --all-targets` in scripts/test.sh has just built, the
# binaries of crates with integration tests included), that folder's NAME, without building
# anything; else it builds PACKAGE with `cargo build CARGO_ARGS` (output on stderr) and prints
# target/debug/NAME, or target/release/NAME with --release. Fails if the binary is not there.
#   rslam=$(scripts/built-binary.sh rslam rslam-cli --release)
set -euo pipefail
[ $# -ge 2 ] || { echo "usage: $0 NAME PACKAGE [CARGO_ARGS...]" >&2; exit 2; }
name=$1
package=$2
shift 2
cd "$(dirname "$0")/.."
if [ -n "${RSLAM_BIN_DIR:-}" ]; then
  bin=$(cd "$RSLAM_BIN_DIR" && pwd)/$name
else
  cargo build "$@" -p "$package" >&2
  profile=debug
  for arg in "$@"; do [ "$arg" = --release ] && profile=release; done
  bin=$PWD/target/$profile/$name
fi
[ -x "$bin" ] || { echo "built-binary: no executable $bin" >&2; exit 1; }
echo "$bin"
