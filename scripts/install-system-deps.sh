#!/usr/bin/env bash
# Installs what a fresh Debian/Ubuntu machine lacks to build and run rslam: cmake and nasm, which
# build the libjpeg-turbo it links statically (its JPEG encoder); the Vulkan loader and Mesa's
# Vulkan drivers (lavapipe renders on the CPU when there is no GPU); for the Python package
# libpython (cargo test links crates/python against it) and venv (scripts/test-python.sh); for
# `rslam view`, the X11 libraries its window loads, and Xvfb (a virtual X server) for the window
# test and screenshot.
set -euo pipefail
missing=()
for pkg in cmake nasm libvulkan1 mesa-vulkan-drivers python3-dev python3-venv libx11-6 libx11-xcb1 libxcursor1 \
  libxi6 libxrandr2 libxkbcommon-x11-0 xvfb xauth; do
  dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
sudo=""
if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
echo "installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}"
