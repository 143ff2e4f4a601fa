#!/usr/bin/env bash
# A one-node Slurm cluster on the loopback for tests (docs/cluster.md "Testing"): munged,
# slurmctld and slurmd, each started by this shell with its own pid, config and state under
# one temporary folder. Source it, then `slurm_start DIR` and `slurm_stop` (also on EXIT).
# Needs root (slurmd runs jobs as their user) and Debian's slurm-wlm and munge.

slurm_free_port() {
  python3 - <<'PY' 2>/dev/null || echo $((20000 + RANDOM % 20000))
import socket
s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()
PY
}

slurm_start() {
  SLURM_TEST_DIR=$1
  local d=$SLURM_TEST_DIR
  mkdir -p "$d/munge" "$d/state" "$d/spool" "$d/log"
  chmod 700 "$d/munge"
  dd if=/dev/urandom of="$d/munge/munge.key" bs=1024 count=1 status=none
  chmod 400 "$d/munge/munge.key"
  SLURM_MUNGE_SOCKET="$d/munge/munge.socket"
  munged --force --key-file="$d/munge/munge.key" --socket="$SLURM_MUNGE_SOCKET" \
    --pid-file="$d/munge/munged.pid" --log-file="$d/log/munged.log" \
    --seed-file="$d/munge/munge.seed" || return 1
  local ctld_port slurmd_port
  ctld_port=$(slurm_free_port)
  slurmd_port=$(slurm_free_port)
  cat > "$d/slurm.conf" <<CONF
ClusterName=foveatest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$SLURM_MUNGE_SOCKET
StateSaveLocation=$d/state
SlurmdSpoolDir=$d/spool
SlurmctldPidFile=$d/slurmctld.pid
SlurmdPidFile=$d/slurmd.pid
SlurmctldLogFile=$d/log/slurmctld.log
SlurmdLogFile=$d/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
InactiveLimit=0
MinJobAge=300
KillWait=5
Waittime=0
NodeName=localhost NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
  export SLURM_CONF="$d/slurm.conf"
  slurmctld -f "$SLURM_CONF" -i || return 1
  slurmd -f "$SLURM_CONF" -N localhost || return 1
  # Ready when the node accepts jobs (idle).
  for _ in $(seq 1 60); do
    if sinfo -h -N -o '%T' 2>/dev/null | grep -q idle; then return 0; fi
    sleep 0.5
  done
  echo "slurm_cluster: the node did not come up (logs in $d/log)" >&2
  return 1
}

slurm_stop() {
  local d=${SLURM_TEST_DIR:-}
  [[ -n $d ]] || return 0
  local pidfile pid
  for pidfile in "$d/slurmd.pid" "$d/slurmctld.pid" "$d/munge/munged.pid"; do
    [[ -f $pidfile ]] || continue
    pid=$(cat "$pidfile")
    kill "$pid" 2>/dev/null || true
    for _ in $(seq 1 40); do kill -0 "$pid" 2>/dev/null || break; sleep 0.25; done
    kill -9 "$pid" 2>/dev/null || true
  done
  # Job steps slurmd started (slurmstepd) end with their daemon; any left over are ours.
  pkill -9 -f "slurmstepd.*$d" 2>/dev/null || true
  SLURM_TEST_DIR=""
}
