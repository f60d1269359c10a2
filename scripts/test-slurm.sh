#!/usr/bin/env bash
# CI: two small suites and a search as real Slurm array jobs (2 tasks each, submitted together)
# on a one-node cluster on this machine (scripts/slurm-cluster.sh): one made with its datasets
# kept (`suite run`), one benched ephemerally (`suite bench --ephemeral` with a method that
# returns the ground truth, its frames made in scratch), and a `suite search` of that method
# under two families, each task taking its shard of the searches. Every array task must exit 0;
# then `rslam suite status` must find the first suite complete and every sequence of the second
# used with its frames deleted, every run recorded, and no frame left anywhere; and the search
# without --shard must find every run done and write the profile.
set -euo pipefail
cd "$(dirname "$0")/.."
tasks=2
timeout=${SLURM_TEST_TIMEOUT:-900}

fail() { echo "test-slurm: $*" >&2; exit 1; }

scripts/install-system-deps.sh
# A release build, or the binary in $RSLAM_BIN_DIR (CI: the one scripts/test.sh built).
rslam=$(scripts/built-binary.sh rslam rslam-cli --release)

tmp=$(mktemp -d)
cluster=$tmp/cluster
# Every slurm command, and the jobs (sbatch exports this environment), use the cluster's own conf.
export SLURM_CONF=$cluster/slurm.conf
trap 'scripts/slurm-cluster.sh stop "$cluster" || true; rm -rf "$tmp"' EXIT
scripts/slurm-cluster.sh start "$cluster"

"$rslam" suite init --preset mini --scenes room0 --frames 10 --out "$tmp/suite"
"$rslam" suite init --preset mini --scenes room0 --frames 10 --format tum --out "$tmp/ephemeral"
printf '%s\n' 'name = "oracle"' 'reads = "tum"' \
  'command = ["cp", "{dataset}/groundtruth.txt", "{estimate}"]' 'timeout_s = 60' >"$tmp/oracle.toml"
kept_script=$("$rslam" suite slurm "$tmp/suite" --tasks "$tasks" | tail -n 1)
ephemeral_script=$("$rslam" suite slurm "$tmp/ephemeral" --tasks "$tasks" --ephemeral \
  --methods "$tmp/oracle.toml" --scratch "$tmp/scratch" | tail -n 1)
mkdir -p "$tmp/search"
search_args=(--methods "$tmp/oracle.toml" --families fog,depth_noise --scenes room0 --frames 10
  --criterion failed --resolution 1)
search_script=$("$rslam" suite slurm "$tmp/search" --tasks "$tasks" --search "${search_args[@]}" \
  --scratch "$tmp/scratch" | tail -n 1)
for script in "$kept_script" "$ephemeral_script" "$search_script"; do
  [ -f "$script" ] || fail "rslam suite slurm printed '$script', which is no file"
done
grep -q ' suite search .* --families fog,depth_noise ' "$search_script" \
  || fail "$search_script runs no search"
grep -q ' suite bench .* --ephemeral ' "$ephemeral_script" \
  || fail "$ephemeral_script runs no ephemeral bench"
jobs=()
for script in "$kept_script" "$ephemeral_script" "$search_script"; do
  job=$(sbatch --parsable "$script") || fail "sbatch refused $script"
  job=${job%%;*}
  echo "submitted $script as array job $job"
  jobs+=("$job")
done

# One line per array task of job $1: task id, state, exit code, log file. Read from the
# controller, which keeps finished jobs (MinJobAge); sacct has no accounting storage here (see
# slurm-cluster.sh).
tasks_of() {
  scontrol show job -o "$1" | awk '{
    delete f
    for (i = 1; i <= NF; i++) { k = $i; sub(/=.*/, "", k); v = $i; sub(/^[^=]*=/, "", v); f[k] = v }
    print f["ArrayTaskId"], f["JobState"], f["ExitCode"], f["StdOut"]
  }'
}

print_logs() {
  local log
  for log in $(tasks_of "$1" | awk '{print $4}'); do
    echo "--- $log" >&2
    cat "$log" >&2 || true
  done
}

# Waits for array job $1 to end; every one of its tasks must complete with exit code 0.
wait_for() {
  local job=$1 records summary last="" deadline=$((SECONDS + timeout))
  while :; do
    records=$(tasks_of "$job") || fail "scontrol has no record of job $job"
    summary=$(awk '{print $2}' <<<"$records" | sort | uniq -c | xargs)
    [ "$summary" = "$last" ] || echo "job $job: $summary"
    last=$summary
    if ! awk '$2 !~ /^(COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|BOOT_FAIL|DEADLINE|PREEMPTED)$/ {busy = 1} END {exit !busy}' <<<"$records"; then
      break
    fi
    if [ $SECONDS -ge "$deadline" ]; then
      print_logs "$job"
      fail "array job $job not finished after ${timeout}s ($summary)"
    fi
    sleep 2
  done
  local expected got
  expected=$(seq 0 $((tasks - 1)) | awk '{print $1, "COMPLETED", "0:0"}')
  got=$(awk '{print $1, $2, $3}' <<<"$records" | sort -n)
  if [ "$got" != "$expected" ]; then
    echo "array tasks of job $job (id state exit code):" >&2
    echo "$got" >&2
    print_logs "$job"
    fail "array job $job: not every one of its $tasks tasks completed with exit code 0"
  fi
}

for job in "${jobs[@]}"; do
  wait_for "$job"
done

"$rslam" suite status "$tmp/suite" >/dev/null \
  || fail "rslam suite status: the suite is not complete after job ${jobs[0]}"
status=$("$rslam" suite status "$tmp/ephemeral") \
  || fail "rslam suite status: the ephemeral suite is not finished after job ${jobs[1]}"
echo "$status"
sequences=$(grep -c '^\[\[sequence\]\]' "$tmp/ephemeral/suite.toml")
grep -q "0 complete, $sequences frames-deleted" <<<"$status" \
  || fail "not every one of the ephemeral suite's $sequences sequences is used with its frames deleted"
runs=$(find "$tmp/ephemeral/runs/oracle" -name '0.txt' | wc -l)
[ "$runs" -eq "$sequences" ] || fail "$runs of $sequences ephemeral runs left an estimate"
left=$(find "$tmp/ephemeral" "$tmp/scratch" \( -name '*.png' -o -name '*.jpg' \) | wc -l)
[ "$left" -eq 0 ] || fail "$left frames left behind by the ephemeral job"
"$rslam" suite report "$tmp/ephemeral" >/dev/null || fail "rslam suite report of the ephemeral suite"
records=$(find "$tmp/search/search/runs" -name '*.json' | sort)
[ -n "$records" ] || fail "the search tasks recorded no run"
"$rslam" suite search "$tmp/search" "${search_args[@]}" >/dev/null 2>&1 \
  || fail "rslam suite search without --shard after job ${jobs[2]}"
[ "$(find "$tmp/search/search/runs" -name '*.json' | sort)" = "$records" ] \
  || fail "the search without --shard ran what the tasks should have"
grep -q '"breaking_severity": null' "$tmp/search/search/profile.json" \
  || fail "the oracle, which never fails, is not reported unbroken in the profile"
echo "slurm array jobs ${jobs[*]}: $tasks tasks each completed; a suite made, a suite benched ephemerally, a search"
