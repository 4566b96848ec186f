#!/usr/bin/env bash
# A real Slurm on this machine: munge, slurmctld and slurmd on localhost, configured in a temporary
# folder; the packaged batch script (packaging/slurm/airr-array.sbatch) submitted as an array of 3
# shards of a render and of a sweep, waited for, merged with `airr merge`, and compared with one
# process's files (byte for byte). Skipped (exit 77) with the reason only where the daemons cannot start.
set -euo pipefail
airr=$(realpath "$1")
source_dir=$(realpath "$2")
default_scene="$source_dir/assets/scenes/default.json"
skip() { echo "SKIPPED: $*"; exit 77; }
for tool in munged mungekey slurmctld slurmd sbatch squeue; do
  command -v "$tool" >/dev/null || skip "$tool is not installed (packaging/setup.sh installs slurm-wlm and munge)"
done
[ "$(id -u)" -eq 0 ] || skip "slurmd must run as root to start jobs"
tmp=$(mktemp -d)
cleanup() {
  for pid in "$tmp"/slurmd.pid "$tmp"/slurmctld.pid "$tmp"/munged.pid; do
    [ -f "$pid" ] && kill "$(cat "$pid")" 2>/dev/null || true
  done
  sleep 1
  rm -rf "$tmp"
}
trap cleanup EXIT
mkdir -p "$tmp/state" "$tmp/spool" "$tmp/log"
chmod 700 "$tmp"

mungekey -c -k "$tmp/munge.key" || skip "mungekey could not make a key"
munged -f --key-file="$tmp/munge.key" --socket="$tmp/munge.socket" --pid-file="$tmp/munged.pid" \
  --log-file="$tmp/log/munged.log" --seed-file="$tmp/munged.seed" || skip "munged did not start: $(tail -1 "$tmp/log/munged.log" 2>/dev/null)"

# Ports of this run's own (tests may run side by side).
port=$((20000 + ($$ % 10000) * 2))
host=$(hostname -s)
cat >"$tmp/slurm.conf" <<CONF
ClusterName=airrtest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
AuthType=auth/munge
AuthInfo=socket=$tmp/munge.socket
CredType=cred/munge
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/log/slurmctld.log
SlurmdLogFile=$tmp/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=airr Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$tmp/slurm.conf"
slurmctld -f "$SLURM_CONF" || skip "slurmctld did not start: $(tail -1 "$tmp/log/slurmctld.log" 2>/dev/null)"
slurmd -f "$SLURM_CONF" || skip "slurmd did not start: $(tail -1 "$tmp/log/slurmd.log" 2>/dev/null)"
for _ in $(seq 100); do
  sinfo -h -o %t 2>/dev/null | grep -q idle && break
  sleep 0.2
done
sinfo -h -o %t | grep -q idle || skip "the node did not come up: $(tail -1 "$tmp/log/slurmd.log")"

args=(--spp 8 --set observer.width=80 --set observer.height=61)
"$airr" render "$default_scene" -o "$tmp/one.png" "${args[@]}" 2>/dev/null
AIRR="$airr" sbatch --parsable --wait --array=0-2 --cpus-per-task=1 --chdir="$tmp" -o "$tmp/task-%a.log" \
  "$source_dir/packaging/slurm/airr-array.sbatch" "$tmp/parts" render "$default_scene" "${args[@]}" >"$tmp/sbatch.out" ||
  { cat "$tmp"/task-*.log; echo "the render's array job failed"; exit 1; }
"$airr" merge "$tmp"/parts/shard-*-of-3.exr -o "$tmp/merged.png"
cmp "$tmp/one.png" "$tmp/merged.png" || { echo "the merged render differs from one process's"; exit 1; }
echo "array job $(cat "$tmp/sbatch.out") (3 tasks), merged: the same PNG as one process"

sweep=("$default_scene" --psf --vary floating_distance=150:250:50 --vary tilt=0:20:10 -o "$tmp/sweep.csv")
"$airr" sweep "${sweep[@]}" >/dev/null 2>&1
mv "$tmp/sweep.csv" "$tmp/sweep_one.csv"
AIRR="$airr" sbatch --parsable --wait --array=0-2 --cpus-per-task=1 --chdir="$tmp" -o "$tmp/sweep-%a.log" \
  "$source_dir/packaging/slurm/airr-array.sbatch" "$tmp/sweep_parts" sweep "${sweep[@]}" >"$tmp/sbatch.out" ||
  { cat "$tmp"/sweep-*.log; echo "the sweep's array job failed"; exit 1; }
[ ! -e "$tmp/sweep.csv" ] || { echo "a shard wrote the sweep's CSV"; exit 1; }
"$airr" merge "$tmp"/sweep_parts/part-*-of-3.json >/dev/null
cmp "$tmp/sweep_one.csv" "$tmp/sweep.csv" || { echo "the merged sweep differs from one process's"; exit 1; }
echo "array job $(cat "$tmp/sbatch.out") (3 tasks of a sweep), merged: the same CSV as one process"
