#!/usr/bin/env bash
# Do people (`actors`, or `objects`) cost a real SLAM more as their severity grows, over several
# draws? Each seed draws other walkers, and one draw's walkers can cost more at a low severity
# than another's at a high one, so one draw says little. Per scene: ../shared/validity/validity.sh
# (ORB-SLAM3 RGB-D) on the clean sequence once and on ITEM:1..5 for every seed, rendered through
# TUM's camera (TUM's walking sequences are filmed through it); then per severity each draw's
# median ATE, the median of the draws, that over the clean ATE, the runs that lost tracking, and
# the mean share of a frame people cover (the manifests' dynamic fractions); and whether the ATE
# grows with the severity beyond what the draws' spread explains (Spearman's rho over every draw,
# and the mean of each seed's own rho, each with a shuffle test; SciPy from validity.sh's venv).
# By hand only: it needs ../shared/validity and about 5 minutes a scene and seed on 2 cores.
#
#   scripts/validity-actors.sh WORK_DIR SCENE...      # e.g. scripts/validity-actors.sh /tmp/a office2
#
# env: SEEDS="0 1 2", CAMERA=tum, RUNS=3, FRAMES=400, ITEM=actors, RSLAM=target/release/rslam
# (built if missing), TRAJ=a camera path for every render (`rslam render --traj`; a held camera
# as in TUM's walking_xyz: scripts/held-camera-path.py). Writes validity.sh's folders as
# WORK_DIR/SCENE/seed0, seed1, ... and the table as WORK_DIR/SCENE/table.md, and prints it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
validity=$root/../shared/validity
[ $# -ge 2 ] || { echo "usage: $0 WORK_DIR SCENE..." >&2; exit 2; }
[ -x "$validity/validity.sh" ] || { echo "$validity/validity.sh: not found (the validity kit lives beside the repository)" >&2; exit 1; }
work=$(mkdir -p "$1" && cd "$1" && pwd); shift
rslam=${RSLAM:-$root/target/release/rslam}
[ -x "$rslam" ] || cargo build --release -q --bin rslam --manifest-path "$root/Cargo.toml"
item=${ITEM:-actors}
seeds=${SEEDS:-0 1 2}
severities="$item:1 $item:2 $item:3 $item:4 $item:5"
# validity.sh's Python (its venv holds evo, and so scipy), as validity.sh finds it.
py=${PY:-${XDG_CACHE_HOME:-$HOME/.cache}/rslam-validity/venv/bin/python}

# validity.sh renders with --seed 0, a scene's own camera and its default path: this rslam swaps
# in the draw's seed, the camera and TRAJ.
traj=${TRAJ:+$(realpath "$TRAJ")}
wrapper=$work/rslam
cat > "$wrapper" <<EOF
#!/usr/bin/env bash
if [ "\$1" = render ]; then
  args=(); previous=
  for a in "\$@"; do [ "\$previous" = --seed ] && a=\$SEED; args+=("\$a"); previous=\$a; done
  exec "$rslam" "\${args[@]}" --camera "${CAMERA:-tum}" ${traj:+--traj \"$traj\"}
fi
exec "$rslam" "\$@"
EOF
chmod +x "$wrapper"

for scene in "$@"; do
    w=$work/$scene
    settings="clean $severities"
    for seed in $seeds; do
        mkdir -p "$w/seed$seed"
        : > "$w/seed$seed/log"
        # One setting at a time: validity.sh stops at a render that fails, and a plan that
        # refuses (too many walkers for the floor) must not cost the severities after it.
        for setting in $settings; do
            env RSLAM="$wrapper" SEED="$seed" FRAMES="${FRAMES:-400}" RUNS="${RUNS:-3}" SCENE="$scene" \
                SETTINGS="$setting" "$validity/validity.sh" "$w/seed$seed" >> "$w/seed$seed/log" 2>&1 ||
                echo "$scene, seed $seed, $setting: validity.sh failed; see $w/seed$seed/log" >&2
        done
        settings=$severities # the clean sequence has nothing to draw
    done
    "$py" - "$w" "$item" $seeds <<'EOF' | tee "$w/table.md"
import json, os, statistics, sys

from scipy.stats import permutation_test, spearmanr

w, item, seeds = sys.argv[1], sys.argv[2], sys.argv[3:]


def folder(seed, kind, setting):
    """Where validity.sh keeps a setting's runs or data (it names them as `tr ':/' '-_'` does)."""
    return os.path.join(w, f"seed{seed}", kind, setting.replace(":", "-").replace("/", "_"))


def runs(seed, setting):
    """(ATE in cm or None, whether tracking was lost) of each run; a run that died counts lost."""
    d = folder(seed, "runs", setting)
    found, r = [], 1
    while os.path.exists(os.path.join(d, f"run{r}.log")):
        o = os.path.join(d, f"run{r}")
        try:
            lost = json.load(open(o + ".json"))["lost"]
        except (OSError, ValueError, KeyError):
            lost = True
        try:
            ate = 100 * json.load(open(o + ".eval.json"))["ate"]["rmse"]
        except (OSError, ValueError, KeyError):
            ate = None
        found.append((ate, lost))
        r += 1
    return found


def cover(seed, setting):
    """The mean dynamic fraction of the draw's dataset, if it is kept."""
    manifest = os.path.join(folder(seed, "data", setting), "rslam.json")
    try:
        fractions = json.load(open(manifest))["extra"]["masks"]["dynamic_fraction"]
    except (OSError, ValueError, KeyError):
        return None
    return sum(fractions) / len(fractions)


def refusal(seed, setting):
    """The error rslam gave for the setting's render in the draw's log, if it gave one."""
    try:
        lines = open(os.path.join(w, f"seed{seed}", "log")).read().splitlines()
    except OSError:
        return None
    starts = [i for i, line in enumerate(lines) if line.startswith(f"== render {setting}:")]
    for line in lines[starts[-1] + 1 :] if starts else []:
        if line.startswith("error:"):
            return line
        if line.startswith("=="):
            break
    return None


def median(values):
    return statistics.median(values) if values else float("nan")


clean = median([a for a, _ in runs(seeds[0], "clean") if a is not None])
print(f"{os.path.basename(w)}: clean {clean:.2f} cm; seeds {', '.join(seeds)}\n")
print("| setting | median ATE per draw (cm) | median of the draws (cm) | × clean | runs that lost tracking | cover, mean per draw |")
print("|---|---|---|---|---|---|")
medians, severity_draws = [], []
for s in range(1, 6):
    setting = f"{item}:{s}"
    per_draw = [runs(seed, setting) for seed in seeds]
    if not any(per_draw):
        why = next(filter(None, (refusal(seed, setting) for seed in seeds)), "no runs (see the seeds' logs)")
        print(f"| {setting} | not run: {why} | | | | |")
        continue
    draws = [median([a for a, _ in d if a is not None]) for d in per_draw]
    medians.append(median([x for x in draws if x == x]))
    severity_draws.append((s, draws))
    lost = sum(l for d in per_draw for _, l in d)
    total = sum(len(d) for d in per_draw)
    covers = [cover(seed, setting) for seed in seeds]
    print(f"| {setting} | {' / '.join('%.2f' % x for x in draws)} | {medians[-1]:.2f} | "
          f"{medians[-1] / clean:.1f} | {lost} of {total} | "
          f"{' / '.join('-' if c is None else '%.1f %%' % (100 * c) for c in covers)} |")
pairs = [(s, x) for s, d in severity_draws for x in d if x == x]
if len({s for s, _ in pairs}) < 2:
    sys.exit("Too few severities with an ATE for a trend.")
grows = all(a < b for a, b in zip(medians, medians[1:]))
print(f"\nThe median of the draws grows with every severity: {'yes' if grows else 'no'}.")
severity, ates = zip(*pairs)
# How often the ATEs shuffled over the severities correlate with them as strongly: whether the
# growth could be chance, with draws this spread.
trend = permutation_test(
    (severity, ates), lambda x, y: spearmanr(x, y).statistic, permutation_type="pairings",
    alternative="greater", n_resamples=10000, rng=0)
print(f"Severity against each draw's median ATE: Spearman's rho {trend.statistic:.2f} over {len(pairs)} draws, "
      f"one-sided p {'< 0.001' if trend.pvalue < 0.001 else '%.3f' % trend.pvalue} (the ATEs shuffled over the severities 10000 times).")
# Up the ladder a seed keeps its walkers and adds one (severities 1-3, and 4-5), so one seed's
# draws are paired: does the cost grow within each seed, whatever that seed's own level? Each
# seed's ATEs are a sample of their own, shuffled among its own severities.
seed_rows = [[d[i] for _, d in severity_draws] for i in range(len(seeds))]
seed_rows = [r for r in seed_rows if all(x == x for x in r)]
if seed_rows:
    within = permutation_test(
        seed_rows, lambda *rows: sum(spearmanr(range(len(r)), r).statistic for r in rows) / len(rows),
        permutation_type="pairings", alternative="greater", n_resamples=10000, rng=0, vectorized=False)
    print(f"Within each seed: mean Spearman's rho {within.statistic:.2f} over {len(seed_rows)} seeds with an ATE at every severity, "
          f"one-sided p {'< 0.001' if within.pvalue < 0.001 else '%.3f' % within.pvalue} (each seed's ATEs shuffled over its severities 10000 times).")
EOF
done
