#!/usr/bin/env bash
# A one-node Slurm cluster on this machine, everything under STATE_DIR: install installs slurm
# and munge if missing (start does too; CI installs them ahead, while the tests run); start
# writes STATE_DIR/slurm.conf, starts munged, slurmctld and slurmd as root and waits for the
# node to be idle; stop cancels the cluster's jobs and ends exactly those daemons.
# Every slurm command must see SLURM_CONF=STATE_DIR/slurm.conf (nothing under /etc is written).
set -euo pipefail

usage() { echo "usage: $0 install | $0 start|stop STATE_DIR" >&2; exit 2; }
cmd=${1:-}
if [ "$cmd" = install ]; then
  [ $# -eq 1 ] || usage
else
  [ $# -eq 2 ] || usage
  mkdir -p "$2"
  state=$(cd "$2" && pwd)
  export SLURM_CONF=$state/slurm.conf
fi
daemons=(munged slurmctld slurmd)

# Whether a process runs: a zombie counts as ended (here pid 1 may take seconds to reap one).
alive() {
  local stat
  stat=$(cat "/proc/$1/stat" 2>/dev/null) || return 1
  [ "$(echo "$stat" | awk '{print $3}')" != Z ]
}

# Pid of a daemon this script started and that still runs (checked by name: pids get reused).
running() {
  local pid
  pid=$(cat "$state/run/$1.pid" 2>/dev/null) || return 1
  [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$1" ] && alive "$pid" && echo "$pid"
}

stop() {
  if running slurmctld >/dev/null; then
    local jobs
    jobs=$(squeue -h -o %A 2>/dev/null || true)
    if [ -n "$jobs" ]; then
      # shellcheck disable=SC2086
      scancel $jobs || true
      for _ in $(seq 30); do
        [ -z "$(squeue -h -o %A 2>/dev/null || true)" ] && break
        sleep 1
      done
    fi
  fi
  local name pid
  for name in slurmd slurmctld munged; do
    pid=$(running "$name") || { rm -f "$state/run/$name.pid"; continue; }
    kill "$pid"
    for _ in $(seq 100); do
      alive "$pid" || break
      sleep 0.2
    done
    if alive "$pid"; then
      echo "slurm-cluster: $name (pid $pid) ignored SIGTERM; killing it" >&2
      kill -9 "$pid" 2>/dev/null || true
    fi
    rm -f "$state/run/$name.pid"
  done
}

fail() {
  local name=$1
  shift
  echo "slurm-cluster: $name: $*; last lines of $state/log/$name.log:" >&2
  tail -n 30 "$state/log/$name.log" >&2 || true
  stop
  exit 1
}

install_packages() {
  local missing=() pkg
  for pkg in slurm-wlm munge; do
    dpkg -s "$pkg" >/dev/null 2>&1 || missing+=("$pkg")
  done
  [ ${#missing[@]} -eq 0 ] && return
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  echo "installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
}

# The first port from $1 on that nothing listens on: another cluster of this script may run here.
free_port() {
  local port=$1
  while (exec 3<>"/dev/tcp/127.0.0.1/$port") 2>/dev/null; do port=$((port + 1)); done
  echo "$port"
}

write_conf() {
  local node mem ctld_port slurmd_port
  node=$(hostname -s)
  ctld_port=$(free_port 6817)
  slurmd_port=$(free_port $((ctld_port + 1)))
  # 3/4 of the memory: slurmd marks the node invalid when RealMemory exceeds what it finds.
  mem=$(awk '/^MemTotal:/ {print int($2 / 1024 * 3 / 4)}' /proc/meminfo)
  cat >"$SLURM_CONF" <<EOF
ClusterName=rslam
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmUser=root
SlurmdUser=root
# The munge socket under STATE_DIR: neither /run/munge nor a system munged is needed or touched.
AuthType=auth/munge
AuthInfo=socket=$state/munge/munge.socket
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/slurmd
SlurmctldPidFile=$state/ctld/slurmctld.pid
SlurmdPidFile=$state/slurmd/slurmd.pid
# Plain /proc process tracking and no task binding: nothing here needs cgroups.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
# One job per CPU, whatever the core/thread layout; memory is not a scheduled resource.
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
# No slurmdbd: accounting storage is off, so plain sacct answers "accounting storage is
# disabled". The job completion file is a lasting record of every job (state, exit code, array
# task); \`sacct -c\` reads it, but this version cannot select an array's tasks by the array's id.
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/filetxt
JobCompLoc=$state/log/jobcomp.txt
# Finished jobs stay in the controller an hour, so that \`scontrol show job\` gives their exit codes.
MinJobAge=3600
# A node that was down when the cluster stopped comes back as soon as its slurmd registers.
ReturnToService=2
MpiDefault=none
MailProg=/bin/true
NodeName=$node NodeAddr=127.0.0.1 Port=$slurmd_port CPUs=$(nproc) RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
}

# Starts a daemon in the foreground of a background job so that its pid is known and a daemon
# that exits at once is noticed; its log is STATE_DIR/log/NAME.log.
launch() {
  local name=$1
  shift
  "$@" </dev/null >>"$state/log/$name.log" 2>&1 &
  local pid=$!
  echo "$pid" >"$state/run/$name.pid"
  # Until the background shell has exec'd the daemon, its name is not the daemon's yet.
  for _ in $(seq 50); do
    [ "$(cat "/proc/$pid/comm" 2>/dev/null)" = "$name" ] && return
    alive "$pid" || return 0
    sleep 0.1
  done
}

start() {
  local name
  for name in "${daemons[@]}"; do
    if running "$name" >/dev/null; then
      echo "slurm-cluster: $name already runs for $state; stop it first" >&2
      exit 1
    fi
  done
  install_packages
  mkdir -p "$state"/{run,log,ctld,slurmd,munge}
  chmod 700 "$state/munge"
  if [ ! -s "$state/munge/munge.key" ]; then
    mungekey --create --keyfile="$state/munge/munge.key"
  fi
  chmod 600 "$state/munge/munge.key"
  write_conf

  # --force: munged otherwise refuses a socket whose folders are not searchable by all (mktemp's
  # are 0700); only root uses this cluster.
  launch munged munged --foreground --force --socket="$state/munge/munge.socket" \
    --key-file="$state/munge/munge.key" --pid-file="$state/munge/munged.pid" \
    --seed-file="$state/munge/munged.seed" --log-file="$state/log/munged.log"
  for _ in $(seq 50); do
    [ -S "$state/munge/munge.socket" ] && break
    running munged >/dev/null || fail munged "exited at start"
    sleep 0.2
  done
  munge --socket="$state/munge/munge.socket" -n </dev/null |
    unmunge --socket="$state/munge/munge.socket" >/dev/null 2>&1 ||
    fail munged "does not answer on $state/munge/munge.socket"

  launch slurmctld slurmctld -D -f "$SLURM_CONF"
  launch slurmd slurmd -D -f "$SLURM_CONF"

  local deadline=$((SECONDS + ${SLURM_CLUSTER_TIMEOUT:-60})) node_state=""
  while [ $SECONDS -lt $deadline ]; do
    for name in "${daemons[@]}"; do
      running "$name" >/dev/null || fail "$name" "exited at start"
    done
    node_state=$(sinfo -h -n "$(hostname -s)" -o %T 2>/dev/null || true)
    if [ "$node_state" = idle ]; then
      echo "slurm cluster up: node $(hostname -s), SLURM_CONF=$SLURM_CONF"
      return
    fi
    sleep 0.5
  done
  echo "slurm-cluster: node $(hostname -s) not idle after ${SLURM_CLUSTER_TIMEOUT:-60}s (sinfo: '${node_state:-no answer}')" >&2
  for name in slurmctld slurmd; do
    echo "--- $state/log/$name.log" >&2
    tail -n 20 "$state/log/$name.log" >&2 || true
  done
  stop
  exit 1
}

case $cmd in
  install) install_packages ;;
  start) start ;;
  stop) stop ;;
  *) usage ;;
esac
