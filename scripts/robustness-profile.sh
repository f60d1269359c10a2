#!/usr/bin/env bash
# The robustness profile in the book (docs/src/search.md): `rslam suite search` of ORB-SLAM3
# RGB-D and OpenCV's RGB-D odometry on two built-in scenes under six families, then the profile
# printed as a table. Run by hand, not in CI: hours on a CPU.
#   PY=python-with-pyorbslam3-and-cv2 ORBSLAM3_VOCABULARY=ORBvoc.txt scripts/robustness-profile.sh DIR
# Environment (defaults in brackets): SCENES [room0,office1], FAMILIES [gaussian_noise,motion_blur,
# fog,contrast,depth_noise,depth_missing], FRAMES [150], CAMERA [tum], RESOLUTION [0.25],
# CRITERION [ate>3xclean], JOBS [1]. ORB-SLAM3 is multi-threaded and differs run to run: 3 runs
# at each severity, their median judged; OpenCV's odometry is deterministic: 1.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
dir=${1:?usage: scripts/robustness-profile.sh DIR}
: "${PY:?PY: a python with pyorbslam3 and OpenCV 5 (e.g. the venv ../shared/validity/validity.sh makes)}"
: "${ORBSLAM3_VOCABULARY:?ORBSLAM3_VOCABULARY: an ORB vocabulary (ORBvoc.txt)}"
export ORBSLAM3_VOCABULARY
rslam=$(scripts/built-binary.sh rslam rslam-cli --release)

mkdir -p "$dir/methods"
printf 'seed = 0\n[defaults]\nframes = %s\ncamera = "%s"\n' "${FRAMES:-150}" "${CAMERA:-tum}" >"$dir/suite.toml"
cat >"$dir/methods/orbslam3.toml" <<EOF
name = "orbslam3"
reads = "tum"
command = ["$PY", "$repo/examples/methods/orbslam3_rgbd.py", "--dataset", "{dataset}", "--settings", "{camera}", "--out", "{estimate}"]
timeout_s = 900
repeats = 3
EOF
cat >"$dir/methods/opencv_rgbd.toml" <<EOF
name = "opencv_rgbd"
reads = "tum"
command = ["$PY", "$repo/examples/methods/opencv_rgbd_odometry.py", "--dataset", "{dataset}", "--out", "{estimate}"]
timeout_s = 900
EOF

start=$SECONDS
"$rslam" suite search "$dir" --methods "$dir/methods/orbslam3.toml" --methods "$dir/methods/opencv_rgbd.toml" \
  --families "${FAMILIES:-gaussian_noise,motion_blur,fog,contrast,depth_noise,depth_missing}" \
  --scenes "${SCENES:-room0,office1}" --criterion "${CRITERION:-ate>3xclean}" \
  --resolution "${RESOLUTION:-0.25}" --jobs "${JOBS:-1}"
echo "search: $((SECONDS - start)) s"

python3 - "$dir/search/profile.json" <<'PY'
import json, sys
profile = json.load(open(sys.argv[1]))
methods = sorted(profile)
rows = sorted({(f, s) for m in methods for f in profile[m] for s in profile[m][f]})
def cell(p):
    if p is None:
        return "—"
    if p["breaking_severity"] is None:
        return "> 5"
    return f"{p['breaking_severity']:g} ({p['low']:g}–{p['high']:g}]"
print("| family | scene | " + " | ".join(methods) + " |")
print("|---|---|" + "---|" * len(methods))
for family, scene in rows:
    cells = [cell(profile[m].get(family, {}).get(scene)) for m in methods]
    print(f"| {family} | {scene} | " + " | ".join(cells) + " |")
PY
