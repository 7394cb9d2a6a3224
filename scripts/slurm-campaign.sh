#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# A sharded campaign on a real Slurm (issue 33, docs/campaign.md "Sharding"): starts a single-node
# Slurm on 127.0.0.1 (Debian's slurm-wlm and munge, installed with apt when missing: needs root),
# submits the AIS campaign as an array job of SHARDS shards and a merge that depends on it
# (afterok), waits for both, and checks that the merged summary.json and runs.jsonl equal an
# unsharded run's, but for the measured fields (plan times, wall clock). Everything it starts (its
# own munged on its own socket and key, slurmctld, slurmd) runs from a temporary directory and is
# stopped again; nothing of the machine's Slurm or munge configuration is touched. Takes about
# 20 s: not in ctest's default run.
#
# Usage: scripts/slurm-campaign.sh PATH_TO_SEWERPLAN [RUNS=40] [SHARDS=4]
# Exit 0: equal; 1: they differ or a job failed; 2: Slurm could not be started.
set -uo pipefail
sp=$(realpath "${1:?usage: $0 PATH_TO_SEWERPLAN [RUNS] [SHARDS]}")
runs=${2:-40}
shards=${3:-4}
src=$(cd "$(dirname "$0")/.." && pwd)
map="$src/datasets/ais-testbed/map.json"
mission="$src/datasets/ais-testbed/missions/paper.json"
seed=7

if ! command -v slurmctld > /dev/null || ! command -v munged > /dev/null; then
  echo "installing slurm-wlm and munge (apt)"
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends slurm-wlm munge \
    > /dev/null || exit 2
fi

tmp=$(mktemp -d)
chmod 755 "$tmp"
cleanup() {
  for pid_file in "$tmp/slurmd.pid" "$tmp/slurmctld.pid" "$tmp/munged.pid"; do
    [ -s "$pid_file" ] && kill "$(cat "$pid_file")" 2> /dev/null
  done
  sleep 1
  rm -rf "$tmp"
}
trap cleanup EXIT

# munge: its own key and socket.
dd if=/dev/urandom of="$tmp/munge.key" bs=128 count=1 2> /dev/null
chmod 400 "$tmp/munge.key"
munged --force --socket="$tmp/munge.sock" --key-file="$tmp/munge.key" \
  --log-file="$tmp/munged.log" --pid-file="$tmp/munged.pid" --seed-file="$tmp/munged.seed" ||
  { cat "$tmp/munged.log"; exit 2; }

# Slurm: one node, this host, on 127.0.0.1, as many CPUs as it has.
host=$(hostname -s)
cpus=$(nproc)
mkdir -p "$tmp/spool" "$tmp/state" "$tmp/work"
cat > "$tmp/slurm.conf" << CONF
ClusterName=sewerplan-test
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$tmp/munge.sock
CredType=cred/munge
SlurmctldPort=${SLURMCTLD_PORT:-6817}
SlurmdPort=${SLURMD_PORT:-6818}
StateSaveLocation=$tmp/state
SlurmdSpoolDir=$tmp/spool
SlurmctldPidFile=$tmp/slurmctld.pid
SlurmdPidFile=$tmp/slurmd.pid
SlurmctldLogFile=$tmp/slurmctld.log
SlurmdLogFile=$tmp/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus State=UNKNOWN
PartitionName=test Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$tmp/slurm.conf"
slurmctld -f "$SLURM_CONF" || { cat "$tmp/slurmctld.log"; exit 2; }
slurmd -f "$SLURM_CONF" || { cat "$tmp/slurmd.log"; exit 2; }
for _ in $(seq 60); do
  sinfo -h -N -o '%T' 2> /dev/null | grep -qE '^(idle|mixed|allocated)' && break
  sleep 1
done
if ! sinfo -h -N -o '%T' | grep -qE '^(idle|mixed|allocated)'; then
  echo "the Slurm node did not come up:"
  sinfo -N
  tail -20 "$tmp/slurmctld.log" "$tmp/slurmd.log"
  exit 2
fi
echo "Slurm up: $(sinfo -h -N -o '%N %C %T')"

# The campaign as an array job of shards, and the merge after all of them.
cd "$tmp/work" || exit 2
cat > shards.sbatch << JOB
#!/bin/bash
#SBATCH --array=0-$((shards - 1))
#SBATCH --cpus-per-task=1
#SBATCH --output=shard-%a.out
"$sp" campaign --map "$map" --mission "$mission" --runs $runs --seed $seed --jobs 1 \\
  --shard "\$SLURM_ARRAY_TASK_ID/$shards" -q -o "shards/\$SLURM_ARRAY_TASK_ID"
JOB
array=$(sbatch --parsable shards.sbatch) || exit 1
# afterany, not afterok: a shard that found a problem (a missed exit) exits 3 with its runs written,
# and the merge is what checks that every shard and run is there (it names the missing ones).
merge=$(sbatch --parsable --dependency="afterany:$array" --output=merge.out --wrap \
  "\"$sp\" campaign merge shards/* -o merged -q") || exit 1
echo "submitted: array job $array ($shards shards of $runs runs), merge job $merge after it"
for _ in $(seq "${SLURM_WAIT_S:-600}"); do
  [ -z "$(squeue -h -j "$array,$merge" 2> /dev/null)" ] && break
  sleep 1
done
if [ -n "$(squeue -h -j "$array,$merge" 2> /dev/null)" ]; then
  echo "FAIL: the jobs did not finish:"
  squeue -j "$array,$merge"
  exit 1
fi
if [ ! -f merged/summary.json ]; then
  echo "FAIL: the merge wrote no summary:"
  tail -n 5 ./*.out
  exit 1
fi
differ=0
if [ -s merge.out ]; then
  echo "FAIL: campaign merge -q printed something:"
  head -5 merge.out
  differ=1
fi

# The same campaign unsharded, here.
"$sp" campaign --map "$map" --mission "$mission" --runs "$runs" --seed $seed --jobs 1 -q -o whole
status=$?
[ "$status" -le 3 ] || { echo "FAIL: the unsharded campaign exited $status"; exit 1; }

# Equal but for what is measured (times): summary.json and runs.jsonl.
strip() {
  python3 - "$1" << 'PY'
import json, sys
# What a run measures on its machine, not what it computes (docs/campaign.md).
MEASURED = {"measured", "planning_ms_p50", "planning_ms_p99"}
def clean(v):
    if isinstance(v, dict):
        return {k: clean(x) for k, x in v.items() if k not in MEASURED}
    if isinstance(v, list):
        return [clean(x) for x in v]
    return v
path = sys.argv[1]
if path.endswith(".jsonl"):
    for line in open(path):
        print(json.dumps(clean(json.loads(line)), sort_keys=True))
else:
    print(json.dumps(clean(json.load(open(path))), sort_keys=True, indent=1))
PY
}
for f in summary.json runs.jsonl; do
  if ! diff <(strip "whole/$f") <(strip "merged/$f") > "$f.diff"; then
    echo "FAIL: merged/$f differs from the unsharded run's:"
    head -20 "$f.diff"
    differ=1
  fi
done
[ "$differ" -eq 0 ] && echo "OK: the merged summary.json and runs.jsonl of $shards Slurm shards equal the unsharded run's ($runs runs, seed $seed)"
exit "$differ"
