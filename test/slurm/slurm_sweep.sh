#!/usr/bin/env bash
# The Slurm backend on a real Slurm (issue 23): installs slurm-wlm and munge from Debian if
# missing, starts a single-node cluster on this machine (its own munge key, slurmctld and slurmd
# on the loopback address, configuration and state in a scratch folder), submits a sweep with
# `mpm_sdem_sweep --backend slurm`, waits for the dependent gather job, and checks that the
# gathered results.csv equals the local backend's (GNU parallel) but for the wall times; then the
# same for a validation sweep of one fast case (scripts/validate --backend slurm).
# usage: test/slurm/slurm_sweep.sh MPM_SDEM_SWEEP [SWEEP_FILE] [WORK_DIR]
# (default sweep: test/data/sweep_4runs.yaml, four runs). Needs root or sudo for the packages and
# the munge key. Exit 0 on equal results.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
sweep_bin="$(realpath "$1")"
sweep_file="$(realpath "${2:-$here/../data/sweep_4runs.yaml}")"
work="${3:-$(mktemp -d /tmp/mpm_sdem_slurm.XXXXXX)}"
sudo="" as_root=() as_munge=(runuser -u munge --)
if [ "$(id -u)" -ne 0 ]; then sudo="sudo" as_root=(sudo -E) as_munge=(sudo -u munge); fi
export PATH="/usr/bin:/usr/sbin:$PATH"

missing=()
for p in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq -o DPkg::Lock::Timeout=300 \
    "${missing[@]}" >/dev/null
fi

rm -rf "$work" && mkdir -p "$work"/{state,spool,munge}
host="$(hostname -s)"
# `scontrol shutdown` returns before the daemons have saved their state and exited; wait for their
# pids to go (up to 20 s) so that removing the scratch folder does not race their last writes.
wait_gone() {
  local pid
  pid="$($sudo cat "$1" 2>/dev/null)" || return 0
  for _ in $(seq 200); do $sudo kill -0 "$pid" 2>/dev/null || return 0; sleep 0.1; done
}
cleanup() {
  SLURM_CONF="$work/slurm.conf" scontrol shutdown >/dev/null 2>&1 || true
  wait_gone "$work/slurmctld.pid"
  wait_gone "$work/slurmd.pid"
  [ -f "$work/munge/munged.pid" ] && $sudo kill "$(cat "$work/munge/munged.pid")" 2>/dev/null || true
  wait_gone "$work/munge/munged.pid"
}
trap cleanup EXIT

# munge: a key made here, a daemon with its own socket (no system service touched).
$sudo chown munge:munge "$work/munge"
"${as_munge[@]}" dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
$sudo chmod 400 "$work/munge/munge.key"
socket="$work/munge/munge.socket"
"${as_munge[@]}" /usr/sbin/munged --key-file="$work/munge/munge.key" --socket="$socket" \
  --pid-file="$work/munge/munged.pid" --log-file="$work/munge/munged.log" \
  --seed-file="$work/munge/munged.seed" --force
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done

cat >"$work/slurm.conf" <<CONF
ClusterName=mpmsdemtest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
SlurmctldPort=16817
SlurmdPort=16818
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=ALL Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$work/slurm.conf"
"${as_root[@]}" slurmctld
"${as_root[@]}" slurmd
for _ in $(seq 100); do
  sinfo -h -o %t 2>/dev/null | grep -q idle && break
  sleep 0.2
done
sinfo -h -o "%P %D %t %C" || { cat "$work"/slurm*.log; exit 1; }

# Submits a sweep file to Slurm into $work/$2 and waits for its array and gather jobs.
submit_and_wait() {
  "$sweep_bin" "$1" --backend slurm --out "$work/$2"
  local ids
  ids="$(awk '{print $2}' "$work/$2/slurm/jobs.txt" | paste -sd,)"
  echo "waiting for jobs $ids"
  for _ in $(seq 600); do
    [ -z "$(squeue -h -j "$ids" 2>/dev/null)" ] && break
    sleep 1
  done
  if [ -n "$(squeue -h -j "$ids" 2>/dev/null)" ]; then
    echo "FAIL: jobs $ids still queued after 600 s"; squeue; exit 1
  fi
  cat "$work/$2/slurm/gather.out"
}
# Two CSV files equal but for their wall_s column (quoted fields may hold commas).
same_but_wall() {
  python3 - "$1" "$2" <<'PY'
import csv, sys
def rows(path):
    with open(path, newline="") as f:
        r = list(csv.reader(f))
    w = r[0].index("wall_s")
    return [row[:w] + row[w + 1:] for row in r]
sys.exit(0 if rows(sys.argv[1]) == rows(sys.argv[2]) else 1)
PY
}

submit_and_wait "$sweep_file" slurm_out
"$sweep_bin" "$sweep_file" --backend local --out "$work/local_out" 2>"$work/local.err" ||
  { cat "$work/local.err"; exit 1; }
if ! same_but_wall "$work/local_out/results.csv" "$work/slurm_out/results.csv"; then
  echo "FAIL: slurm and local results.csv differ"; exit 1
fi
echo "slurm and local results.csv agree ($(($(wc -l <"$work/slurm_out/results.csv") - 1)) runs)"

# The validation report's cases as scripts/validate --backend slurm submits them: one fast case.
printf 'name: v\nvalidation:\n  fast: true\n  cases: [bar]\n' >"$work/validation.yaml"
submit_and_wait "$work/validation.yaml" validation_slurm
"$sweep_bin" "$work/validation.yaml" --backend local --out "$work/validation_local" \
  2>"$work/local.err" || { cat "$work/local.err"; exit 1; }
if ! same_but_wall "$work/validation_local/data/results.csv" \
  "$work/validation_slurm/data/results.csv"; then
  echo "FAIL: slurm and local validation data differ"; exit 1
fi
echo "PASS: slurm and local agree (a sweep and a validation case)"
[ -n "${3:-}" ] || { cleanup; trap - EXIT; $sudo rm -rf "$work"; }  # a scratch folder of our own
