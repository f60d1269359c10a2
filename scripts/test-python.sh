#!/usr/bin/env bash
# The Python package's tests on a fresh machine: system packages (Vulkan/lavapipe, python3-venv),
# the CLI the tests compare with (cargo build -p rslam-cli, or $RSLAM_BIN_DIR/rslam), the venv
# target/python-venv with pytest and the reference library imagecorruptions
# (scripts/python-env.sh), into which `pip install ./crates/python` builds and installs the wheel
# (maturin through pip's build isolation); then pytest.
# Run from anywhere: scripts/test-python.sh [pytest args]. PYTHON picks the interpreter.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-system-deps.sh
# The CLI the tests compare with: a dev build, or the binary in $RSLAM_BIN_DIR (CI: the one
# scripts/test.sh built).
rslam=$(scripts/built-binary.sh rslam rslam-cli)
scripts/python-env.sh
venv=target/python-venv
pip=("$venv/bin/python" -m pip --disable-pip-version-check)
# The wheel is built with cargo's dev profile here (dependencies at opt-level 3, as for cargo
# test) so that it reuses the build `cargo test --workspace` already made; a plain
# `pip install ./crates/python` builds the release profile.
MATURIN_PEP517_ARGS="${MATURIN_PEP517_ARGS:---profile dev}" "${pip[@]}" install ./crates/python
RSLAM_BIN="$rslam" "$venv/bin/python" -m pytest crates/python/tests -q "$@"
