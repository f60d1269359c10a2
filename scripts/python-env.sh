#!/usr/bin/env bash
# The venv the Python package's tests run in (target/python-venv): pip, pytest, rosbags and mcap
# (the real readers of the ROS 2 bags rslam writes), and the reference
# library imagecorruptions with what it needs. Made once; a venv that holds them already is kept
# (CI makes it while the Rust tests run, then scripts/test-python.sh installs the wheel into it).
# PYTHON picks the interpreter.
set -euo pipefail
cd "$(dirname "$0")/.."
python=${PYTHON:-python3}
venv=target/python-venv
ready=$venv/.reference-libraries
# imagecorruptions' maintained fork (same module, same corruptions; 1.1.2 itself needs
# scikit-image < 0.19 and numpy < 2, which have no wheels for current Pythons). Its requirement
# opencv-python needs libGL; the headless build is the same library.
libraries="pytest opencv-python-headless scikit-image scipy numba Pillow rosbags mcap PyYAML"
fork=imagecorruptions-imaug==1.1.5
if [ "$(cat "$ready" 2>/dev/null)" = "$libraries $fork" ] && [ -x "$venv/bin/python" ]; then
  exit 0
fi
if ! "$python" -c 'import ensurepip, venv' 2>/dev/null; then
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq python3-venv
fi
"$python" -m venv --clear "$venv"
pip=("$venv/bin/python" -m pip --disable-pip-version-check)
"${pip[@]}" install -q --upgrade pip
# shellcheck disable=SC2086 # one word per library
"${pip[@]}" install -q $libraries
"${pip[@]}" install -q --no-deps "$fork"
echo "$libraries $fork" >"$ready"
