#!/usr/bin/env bash
# An `esif montecarlo --emit-jobs` list run as a Slurm job array with the
# line of docs/user-guide.md, collected, equals the same campaign run by esif
# itself. The cluster is this machine alone: munged, slurmctld and slurmd
# started here with their configuration, keys, state, spool and logs in a
# temporary folder, and stopped on exit (the daemons started here, by their
# process ids, and the job steps of their jobs).
#   bash tests/engines/slurm_array.sh ESIF_BINARY SOURCE_DIR
# Skips (exit 77), naming the reason, when not root (slurmd runs the jobs as
# root), without the Debian packages slurm-wlm and munge (.ci/run installs
# them), or when the daemons do not come up.
set -euo pipefail
ESIF=$1
SOURCE_DIR=$2
# shellcheck source-path=SCRIPTDIR
source "$(dirname "$0")/common.sh"

[ "$(id -u)" -eq 0 ] || skip "not root: the local slurmd of this test runs as root (SlurmdUser=root)"
missing=()
for b in munged munge unmunge slurmctld slurmd sbatch sinfo squeue scancel; do
  command -v "$b" > /dev/null || missing+=("$b")
done
[ ${#missing[@]} -eq 0 ] ||
  skip "${missing[*]} not found (Debian packages slurm-wlm and munge; .ci/run installs them)"

engine_tmpdir
daemons=()  # process ids of the daemons started here, in starting order
engine_pid=""  # the engine's command line, while it runs

alive() {  # a process that exists and is not a zombie
  [ -r "/proc/$1/stat" ] && [ "$(awk '{ sub(/^.*\) /, ""); print $1 }' "/proc/$1/stat" 2> /dev/null)" != Z ]
}

# The slurmstepd processes of this test's slurmd: the only processes whose
# environment holds ESIF_SLURM_TEST=$T (slurmd passes its environment on).
our_stepds() {
  local p
  for p in /proc/[0-9]*; do
    [ "$(cat "$p/comm" 2> /dev/null)" = slurmstepd ] || continue
    { tr '\0' '\n' < "$p/environ"; } 2> /dev/null | grep -qxF "ESIF_SLURM_TEST=$T" && echo "${p#/proc/}"
  done
  return 0
}

stop() {  # SIGTERM, then SIGKILL after 10 s
  local pid=$1 i
  kill -TERM "$pid" 2> /dev/null || return 0
  for i in $(seq 50); do alive "$pid" || break; sleep 0.2; done
  alive "$pid" && kill -KILL "$pid" 2> /dev/null
  wait "$pid" 2> /dev/null || true
}

show_logs() {
  local f
  for f in "$T"/log/*; do
    [ -s "$f" ] && { echo "--- ${f##*/} (last lines)"; tail -n 15 "$f"; }
  done >&2
}

cleanup() {
  local rc=$? i pid
  trap - EXIT INT TERM HUP
  [ -n "$engine_pid" ] && stop "$engine_pid"
  if [ ${#daemons[@]} -gt 1 ]; then
    # Cancel what is left of the jobs and let their steps end before slurmd goes.
    scancel --quiet --user=root 2> /dev/null || true
    for i in $(seq 50); do
      [ -z "$(squeue -h -o %i 2> /dev/null)" ] && [ -z "$(our_stepds)" ] && break
      sleep 0.2
    done
  fi
  for ((i = ${#daemons[@]} - 1; i >= 0; i--)); do stop "${daemons[i]}"; done
  for pid in $(our_stepds); do stop "$pid"; done
  [ "$rc" -ne 0 ] && [ "$rc" -ne 77 ] && show_logs
  engine_cleanup
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

line=$(doc_line "Slurm array")
host=$(hostname -s)
mkdir -p "$T/log" "$T/state" "$T/spool" "$T/munge" "$T/munge_socket"
# munged wants its key private and its socket's folder open to all (it
# checks the folders up to /).
chmod 755 "$T" "$T/munge_socket"
chmod 700 "$T/munge"
head -c 1024 /dev/urandom > "$T/munge/munge.key"
chmod 400 "$T/munge/munge.key"
socket="$T/munge_socket/socket"

# Two free TCP ports for slurmctld and slurmd (the defaults may be taken by a real cluster).
port_free() { ! (exec 3<> "/dev/tcp/127.0.0.1/$1") 2> /dev/null; }
ctld_port=""
for _ in $(seq 20); do
  p=$((20000 + RANDOM % 20000))
  if port_free "$p" && port_free $((p + 1)); then ctld_port=$p; break; fi
done
[ -n "$ctld_port" ] || skip "no two free consecutive TCP ports found for slurmctld and slurmd"

touch "$T/plugstack.conf"
cat > "$T/slurm.conf" << CONF
ClusterName=esiftest
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$((ctld_port + 1))
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/log/slurmctld.log
SlurmdLogFile=$T/log/slurmd.log
PlugStackConfig=$T/plugstack.conf
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
MpiDefault=none
ReturnToService=2
# sbatch --wait polls every 2 s while MinJobAge / 2 <= 2 (then 8 s and 32 s)
MinJobAge=4
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=esif Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$T/slurm.conf"

munged -F --key-file="$T/munge/munge.key" --socket="$socket" --pid-file="$T/munge/munged.pid" \
  --seed-file="$T/munge/munged.seed" --log-file="$T/log/munged.log" > "$T/log/munged.out" 2>&1 &
daemons+=($!)
for _ in $(seq 50); do
  munge -n -S "$socket" 2> /dev/null | unmunge -S "$socket" > /dev/null 2>&1 && break
  alive "${daemons[0]}" || break
  sleep 0.2
done
munge -n -S "$socket" 2> /dev/null | unmunge -S "$socket" > /dev/null 2>&1 ||
  { show_logs; skip "munged did not come up within 10 s (its log is above)"; }

ESIF_SLURM_TEST=$T slurmctld -D > "$T/log/slurmctld.out" 2>&1 &
daemons+=($!)
ESIF_SLURM_TEST=$T slurmd -D -N "$host" > "$T/log/slurmd.out" 2>&1 &
daemons+=($!)
state=""
for _ in $(seq 60); do
  state=$(sinfo -h -n "$host" -o %T 2> /dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.5
done
[ "$state" = idle ] ||
  { show_logs; skip "slurmctld and slurmd did not bring node $host up within 30 s (state '$state'; logs above)"; }
echo "local Slurm cluster up: node $host idle, slurmctld on port $ctld_port"

engine_prepare
echo "running in the job list's folder: $line"
# In the background so that a signal to this script stops it (through the
# EXIT trap) instead of waiting for it.
(cd "$T/engine" && exec timeout 120 bash -c "$line") &
engine_pid=$!
rc=0
wait "$engine_pid" || rc=$?
engine_pid=""
if [ "$rc" -ne 0 ]; then
  for f in "$T"/engine/slurm-*.out; do [ -s "$f" ] && { echo "--- ${f##*/}"; cat "$f"; }; done >&2
  [ "$rc" -eq 124 ] && fail "the job array did not finish within 120 s"
  fail "'$line' failed (exit $rc: the highest exit code of the array's tasks)"
fi
engine_collect_and_compare
