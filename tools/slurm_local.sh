#!/usr/bin/env bash
# A real single-node Slurm cluster on this machine, from Debian's packages, without systemd:
# for trying `criticality-campaign slurm --submit` and for the tests.
#
#   tools/slurm_local.sh start    install what is missing (apt-get), write the configuration,
#                                 start munged, slurmctld and slurmd; wait until the node is idle
#   tools/slurm_local.sh status   the daemons this script started, and sinfo
#   tools/slurm_local.sh stop     stop every daemon this script started (and nothing else)
#
# Needs root (daemons run as root: SlurmUser=root). Configuration: proctrack/linuxproc,
# task/none, select/cons_tres (cores and memory), no accounting, one node named localhost
# (`slurmd -N localhost`), partition `local`, batch_sched_delay=0. State, logs and pid files live
# in SLURM_LOCAL_DIR (default /var/tmp/slurm-local). /etc/slurm/slurm.conf is written only when
# absent or written by this script earlier: a real cluster's configuration is never touched.
# Wait for jobs by polling squeue (sbatch --wait needs job accounting, which is off).
set -euo pipefail

DIR=${SLURM_LOCAL_DIR:-/var/tmp/slurm-local}
CONF=/etc/slurm/slurm.conf
MARK="# written by sumo-criticality tools/slurm_local.sh"
packages=(slurmctld slurmd munge slurm-client)

die() {
  echo "slurm_local: $*" >&2
  exit 1
}

# The pid a daemon wrote, if that process is still alive.
alive_pid() {
  local f=$1
  [ -s "$f" ] || return 1
  local pid
  pid=$(cat "$f")
  kill -0 "$pid" 2>/dev/null && echo "$pid"
}

install_missing() {
  local missing=() p
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "slurm_local: installing ${missing[*]}" >&2
  # Debian's postinst scripts would start the daemons through systemd/init: forbid that.
  local policy=/usr/sbin/policy-rc.d restore=0
  if [ ! -e "$policy" ]; then
    printf '#!/bin/sh\nexit 101\n' >"$policy"
    chmod +x "$policy"
    restore=1
  fi
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" \
    >/dev/null || { [ $restore = 1 ] && rm -f "$policy"; die "apt-get install failed"; }
  [ $restore = 1 ] && rm -f "$policy"
  return 0
}

write_config() {
  if [ -e "$CONF" ] && ! head -n 1 "$CONF" | grep -qF "$MARK"; then
    die "$CONF exists and was not written by this script; this script only sets up a" \
        "throwaway local cluster (move that file away, or use your real cluster)"
  fi
  local cpus mem
  cpus=$(nproc)
  # Leave 1 GiB of the machine's memory to the system; at least 1 GiB for jobs.
  mem=$(awk '/MemTotal/ {m = int($2 / 1024) - 1024; if (m < 1024) m = 1024; print m}' /proc/meminfo)
  mkdir -p /etc/slurm "$DIR/state" "$DIR/spool" "$DIR/log"
  cat >"$CONF" <<EOF
$MARK
ClusterName=local
SlurmctldHost=localhost
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/slurmctld.pid
SlurmdPidFile=$DIR/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
SlurmctldPort=6817
SlurmdPort=6818
NodeName=localhost CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=local Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
}

start_munge() {
  if alive_pid "$DIR/munged.pid" >/dev/null; then return 0; fi
  mkdir -p /run/munge /var/lib/munge /var/log/munge
  chown munge:munge /run/munge /var/lib/munge /var/log/munge
  chmod 0755 /run/munge
  [ -s /etc/munge/munge.key ] || die "/etc/munge/munge.key is missing (reinstall munge)"
  # munged refuses to run as root; it forks into the background and writes its pid file.
  rm -f /run/munge/munged.pid
  runuser -u munge -- /usr/sbin/munged --pid-file=/run/munge/munged.pid \
    || die "munged did not start (see /var/log/munge/munged.log)"
  cp /run/munge/munged.pid "$DIR/munged.pid"
}

wait_for() {  # seconds, description, command...
  local secs=$1 what=$2
  shift 2
  local end=$((SECONDS + secs))
  until "$@" >/dev/null 2>&1; do
    [ $SECONDS -lt $end ] || return 1
    sleep 0.2
  done
  echo "slurm_local: $what" >&2
}

node_idle() { sinfo -h -N -n localhost -o %T | grep -qE '^(idle|mixed|allocated)'; }

cmd_start() {
  [ "$(id -u)" -eq 0 ] || die "start needs root (the daemons run as root)"
  install_missing
  mkdir -p "$DIR"
  write_config
  start_munge
  if ! alive_pid "$DIR/slurmctld.pid" >/dev/null; then
    rm -f "$DIR/slurmctld.pid"
    # -c: a clean start (no jobs from an earlier session); -i: ignore stale state files.
    /usr/sbin/slurmctld -c -i || die "slurmctld did not start (see $DIR/log/slurmctld.log)"
  fi
  wait_for 30 "slurmctld is up" scontrol ping \
    || die "slurmctld does not answer (see $DIR/log/slurmctld.log)"
  if ! alive_pid "$DIR/slurmd.pid" >/dev/null; then
    rm -f "$DIR/slurmd.pid"
    /usr/sbin/slurmd -N localhost || die "slurmd did not start (see $DIR/log/slurmd.log)"
  fi
  wait_for 60 "node localhost is ready (partition local)" node_idle \
    || die "node localhost did not become idle (see $DIR/log/slurmd.log; sinfo -R)"
}

cmd_stop() {
  local name pid stopped=0
  for name in slurmd slurmctld munged; do
    if pid=$(alive_pid "$DIR/$name.pid"); then
      kill -TERM "$pid" 2>/dev/null || true
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -0 "$pid" 2>/dev/null && kill -KILL "$pid" 2>/dev/null
      echo "slurm_local: stopped $name (pid $pid)" >&2
      stopped=1
    fi
    rm -f "$DIR/$name.pid"
  done
  [ $stopped = 1 ] || echo "slurm_local: nothing to stop" >&2
}

cmd_status() {
  local name pid up=0
  for name in munged slurmctld slurmd; do
    if pid=$(alive_pid "$DIR/$name.pid"); then
      echo "$name running (pid $pid)"
      up=1
    else
      echo "$name not running"
    fi
  done
  [ $up = 1 ] && sinfo 2>/dev/null || true
}

case "${1:-}" in
  start) cmd_start ;;
  stop) cmd_stop ;;
  status) cmd_status ;;
  *) die "usage: tools/slurm_local.sh start|stop|status" ;;
esac
