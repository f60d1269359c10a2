#!/usr/bin/env bash
# The Python package's tests on a fresh machine: system packages (Vulkan/lavapipe, python3-venv),
# the CLI the tests compare with (cargo build -p rslam-cli, or $RSLAM_BIN_DIR/rslam), then a venv
# under target/python-venv in which `pip install ./crates/python` builds and installs the wheel
# (maturin through pip's build isolation), plus pytest and the reference library
# imagecorruptions; then pytest.
# Run from anywhere: scripts/test-python.sh [pytest args]. PYTHON picks the interpreter.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-system-deps.sh
python=${PYTHON:-python3}
if ! "$python" -c 'import ensurepip, venv' 2>/dev/null; then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq python3-venv
fi
# The CLI the tests compare with: a dev build, or the binary in $RSLAM_BIN_DIR (CI: the one
# scripts/test.sh built).
rslam=$(scripts/built-binary.sh rslam rslam-cli)
venv=target/python-venv
"$python" -m venv --clear "$venv"
pip=("$venv/bin/python" -m pip --disable-pip-version-check)
"${pip[@]}" install -q --upgrade pip
# The wheel is built with cargo's dev profile here (dependencies at opt-level 3, as for cargo
# test) so that it reuses the build `cargo test --workspace` already made; a plain
# `pip install ./crates/python` builds the release profile.
MATURIN_PEP517_ARGS="${MATURIN_PEP517_ARGS:---profile dev}" "${pip[@]}" install ./crates/python
# The reference: imagecorruptions' maintained fork (same module, same corruptions; 1.1.2 itself
# needs scikit-image < 0.19 and numpy < 2, which have no wheels for current Pythons). Its
# requirement opencv-python needs libGL; the headless build is the same library.
"${pip[@]}" install -q pytest opencv-python-headless scikit-image scipy numba Pillow
"${pip[@]}" install -q --no-deps imagecorruptions-imaug==1.1.5
RSLAM_BIN="$rslam" "$venv/bin/python" -m pytest crates/python/tests -q "$@"
