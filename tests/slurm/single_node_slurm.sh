#!/usr/bin/env bash
# Brings up a single-node Slurm on localhost (munged + slurmctld + slurmd from Debian's munge and
# slurm-wlm, a generated slurm.conf and munge key, all under a scratch folder; nothing in /etc is
# touched), runs a sweep through Snakemake's Slurm support with workflow/profiles/slurm, checks
# sweep.csv, and stops the daemons it started (by their PIDs).
# Usage: single_node_slurm.sh NMM_SWEEP SWEEP.json SCRATCH [extra nmm-sweep args]
# Exit 0 passed, 1 failed, 77 skipped (no Slurm/munge/snakemake, or the daemons cannot start
# here, e.g. not root; the reason is printed). Manual check: docs/fos-and-sweeps.md.
set -u
sweep_tool=$1; sweep_file=$2; scratch=$3; shift 3
here=$(cd "$(dirname "$0")/../.." && pwd)
skip() { echo "SKIP: $*"; exit 77; }
for tool in munged slurmctld slurmd sbatch sinfo snakemake; do
  command -v $tool >/dev/null 2>&1 || [ -x /usr/sbin/$tool ] || skip "$tool is not installed (apt-get install slurm-wlm munge snakemake)"
done
[ "$(id -u)" = 0 ] || skip "needs root to run slurmd (it starts jobs as their user)"
export PATH=$PATH:/usr/sbin
rm -rf "$scratch"; mkdir -p "$scratch"/{state,spool,log,munge}
scratch=$(cd "$scratch" && pwd)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null; done
  sleep 1
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null; done
}
trap cleanup EXIT

# munge: a fresh key and a private socket.
dd if=/dev/urandom of="$scratch/munge/munge.key" bs=1024 count=1 status=none
chmod 0400 "$scratch/munge/munge.key"
chmod 0700 "$scratch/munge"
sock="$scratch/munge/munge.socket"
munged --force --key-file="$scratch/munge/munge.key" --socket="$sock" \
       --pid-file="$scratch/munge/munged.pid" --log-file="$scratch/log/munged.log" \
       --seed-file="$scratch/munge/seed" || skip "munged does not start (see $scratch/log/munged.log)"
sleep 1
pids+=("$(cat "$scratch/munge/munged.pid")")

host=$(hostname -s)
cpus=$(nproc)
mem=$(awk '/MemTotal/ { printf "%d", $2 / 1024 * 0.8 }' /proc/meminfo)
export SLURM_CONF="$scratch/slurm.conf"
cat > "$SLURM_CONF" <<CONF
ClusterName=nmmtest
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$sock
SlurmctldPort=16817
SlurmdPort=16818
StateSaveLocation=$scratch/state
SlurmdSpoolDir=$scratch/spool
SlurmctldPidFile=$scratch/slurmctld.pid
SlurmdPidFile=$scratch/slurmd.pid
SlurmctldLogFile=$scratch/log/slurmctld.log
SlurmdLogFile=$scratch/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
MpiDefault=none
ReturnToService=2
MinJobAge=600
NodeName=$host CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -i -f "$SLURM_CONF" || skip "slurmctld does not start (see $scratch/log/slurmctld.log)"
sleep 1
[ -f "$scratch/slurmctld.pid" ] && pids+=("$(cat "$scratch/slurmctld.pid")")
slurmd -f "$SLURM_CONF" || skip "slurmd does not start (see $scratch/log/slurmd.log)"
sleep 1
[ -f "$scratch/slurmd.pid" ] && pids+=("$(cat "$scratch/slurmd.pid")")
for i in $(seq 1 30); do
  state=$(sinfo -h -N -o %t 2>/dev/null | head -n1)
  [ "$state" = idle ] && break
  sleep 1
done
[ "${state:-}" = idle ] || skip "the Slurm node did not become idle (state '${state:-none}'; logs in $scratch/log)"
echo "single-node Slurm up: $(sinfo -h -o '%P %D %t %C' | head -n1)"

export USER=${USER:-$(id -un)}  # Snakemake 7's Slurm executor reads $USER
"$sweep_tool" "$sweep_file" -o "$scratch/sweep" --engine snakemake \
    --profile "$here/workflow/profiles/slurm" "$@"
rc=$?
[ $rc = 0 ] || { echo "FAIL: nmm-sweep through Slurm exited $rc"; tail -n 30 "$scratch/sweep/snakemake.log"; exit 1; }
ls "$scratch/sweep/.snakemake/slurm_logs/rule_run/"*.log >/dev/null 2>&1 ||
  { echo "FAIL: no Slurm job logs: the jobs did not go through sbatch"; exit 1; }
rows=$(tail -n +2 "$scratch/sweep/sweep.csv" | wc -l)
ok=$(tail -n +2 "$scratch/sweep/sweep.csv" | awk -F, '$0 ~ /,0,ok,/' | wc -l)
echo "sweep through Slurm: $ok of $rows runs ok; $(ls "$scratch/sweep/.snakemake/slurm_logs/rule_run/" | wc -l) sbatch jobs"
[ "$rows" -gt 0 ] && [ "$ok" = "$rows" ] || { echo "FAIL: not every run is ok"; cat "$scratch/sweep/sweep.csv"; exit 1; }
echo PASS
