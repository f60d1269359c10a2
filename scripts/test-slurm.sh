#!/usr/bin/env bash
# CI: a small suite rendered as a real Slurm array job (2 tasks) on a one-node cluster on this
# machine (scripts/slurm-cluster.sh). Every array task must exit 0 and `rslam suite status` must
# then find every sequence complete.
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
script=$("$rslam" suite slurm "$tmp/suite" --tasks "$tasks" | tail -n 1)
[ -f "$script" ] || fail "rslam suite slurm printed '$script', which is no file"
job=$(sbatch --parsable "$script") || fail "sbatch refused $script"
job=${job%%;*}
echo "submitted $script as array job $job"

# One line per array task: task id, state, exit code, log file. Read from the controller, which
# keeps finished jobs (MinJobAge); sacct has no accounting storage here (see slurm-cluster.sh).
tasks_of() {
  scontrol show job -o "$job" | awk '{
    delete f
    for (i = 1; i <= NF; i++) { k = $i; sub(/=.*/, "", k); v = $i; sub(/^[^=]*=/, "", v); f[k] = v }
    print f["ArrayTaskId"], f["JobState"], f["ExitCode"], f["StdOut"]
  }'
}

print_logs() {
  local log
  for log in $(tasks_of | awk '{print $4}'); do
    echo "--- $log" >&2
    cat "$log" >&2 || true
  done
}

deadline=$((SECONDS + timeout))
last=""
while :; do
  records=$(tasks_of) || fail "scontrol has no record of job $job"
  summary=$(awk '{print $2}' <<<"$records" | sort | uniq -c | xargs)
  [ "$summary" = "$last" ] || echo "job $job: $summary"
  last=$summary
  if ! awk '$2 !~ /^(COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|BOOT_FAIL|DEADLINE|PREEMPTED)$/ {busy = 1} END {exit !busy}' <<<"$records"; then
    break
  fi
  if [ $SECONDS -ge "$deadline" ]; then
    print_logs
    fail "array job $job not finished after ${timeout}s ($summary)"
  fi
  sleep 2
done

expected=$(seq 0 $((tasks - 1)) | awk '{print $1, "COMPLETED", "0:0"}')
got=$(awk '{print $1, $2, $3}' <<<"$records" | sort -n)
if [ "$got" != "$expected" ]; then
  echo "array tasks (id state exit code):" >&2
  echo "$got" >&2
  print_logs
  fail "array job $job: not every one of its $tasks tasks completed with exit code 0"
fi

"$rslam" suite status "$tmp/suite" || fail "rslam suite status: the suite is not complete after job $job"
echo "slurm array job $job: $tasks tasks completed, suite complete"
