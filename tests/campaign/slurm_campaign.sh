#!/usr/bin/env bash
# ctest campaign_slurm (label slurm): a one-node Slurm cluster on loopback runs a campaign written by
# `michi campaign slurm` (a 4-task job array and a merge job depending on it); the merged database must hold as many
# runs per planner as an unsharded run's. Needs Debian's slurm-wlm (scripts/setup.sh installs it) and root (slurmd).
# Usage: slurm_campaign.sh MICHI SOURCE_DIR
set -euo pipefail
michi=$1
src=$2
for c in munged slurmctld slurmd sbatch scontrol sqlite3; do
    command -v "$c" >/dev/null || { echo "campaign_slurm: $c is missing (scripts/setup.sh installs slurm-wlm)"; exit 1; }
done
[[ $(id -u) -eq 0 ]] || { echo "campaign_slurm: needs root (slurmd starts the jobs)"; exit 1; }

work=$(mktemp -d /tmp/michi-slurm-XXXXXX)
pids=()
cleanup() {
    # only the daemons this script started, by their process ids
    for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
    for p in "${pids[@]}"; do wait "$p" 2>/dev/null || true; done
    rm -rf "$work"
}
trap cleanup EXIT
fail() {
    echo "campaign_slurm: $*"
    for f in slurmctld.log slurmd.log camp/slurm/shard-1.out camp/slurm/merge.out; do
        [[ -f $work/$f ]] && { echo "--- $f"; tail -n 20 "$work/$f"; }
    done
    exit 1
}

# munge, by hand: its key and socket in the temporary folder
mkdir -p "$work/munge" "$work/state" "$work/spool"
chmod 700 "$work/munge"
dd if=/dev/urandom of="$work/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$work/munge/munge.key"
munged -F -f --key-file="$work/munge/munge.key" --socket="$work/munge/socket" --pid-file="$work/munge/pid" \
    --log-file="$work/munge/log" --seed-file="$work/munge/seed" >"$work/munged.out" 2>&1 &
pids+=($!)

# one node on 127.0.0.1, ports other than Slurm's defaults (6817/6818), no systemd, cgroups or accounting
cat >"$work/slurm.conf" <<CONF
ClusterName=michitest
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort=16917
SlurmdPort=16918
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/socket
CredType=cred/munge
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/slurmctld.log
SlurmdLogFile=$work/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
NodeName=michinode NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=michi Nodes=michinode Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm.conf
for i in $(seq 1 100); do [[ -S $work/munge/socket ]] && break; sleep 0.1; done
slurmctld -D -c -f "$SLURM_CONF" >"$work/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -f "$SLURM_CONF" -N michinode >"$work/slurmd.out" 2>&1 &
pids+=($!)
for i in $(seq 1 300); do
    state=$(sinfo -h -n michinode -o %t 2>/dev/null || true)
    [[ $state == idle* ]] && break
    sleep 0.2
done
[[ ${state:-} == idle* ]] || fail "the node did not come up (state '${state:-}')"

# a campaign of 8 units: 2 problems x 2 planners x 2 runs
cat >"$work/camp.yaml" <<YAML
name: slurmtest
seed: 5
time_limit: 0.5
runs: 2
problems: [$src/problems/planar_2link.yaml, $src/problems/se2_corridor.yaml]
planners: [geometric::RRTConnect, geometric::PRM]
checkers: [fcl]
YAML
"$michi" campaign slurm "$work/camp.yaml" --shards 4 --out "$work/camp" >/dev/null || fail "campaign slurm failed"
read -r array merge < <(sh "$work/camp/submit.sh") || fail "sbatch failed"
[[ -n ${merge:-} ]] || fail "no job ids from submit.sh"
for i in $(seq 1 900); do
    jstate=$(scontrol show job "$merge" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n1)
    case $jstate in COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY) break ;; esac
    sleep 0.2
done
[[ $jstate == COMPLETED ]] || fail "merge job $merge ended as '$jstate'"
for k in 1 2 3 4; do
    s=$(scontrol show job "${array}_$k" 2>/dev/null | sed -n 's/.*JobState=\([A-Z_]*\).*/\1/p' | head -n1)
    [[ $s == COMPLETED ]] || fail "array task $k ended as '$s'"
done

# the same campaign unsharded, without Slurm
"$michi" campaign run "$work/camp.yaml" --out "$work/whole" >/dev/null 2>&1 || fail "unsharded run failed"
"$michi" campaign merge "$work/whole" --out "$work/whole-merged" >/dev/null 2>&1 || fail "unsharded merge failed"
q="select p.name, count(*) from runs r join plannerConfigs p on r.plannerid = p.id group by p.name order by p.name"
a=$(sqlite3 "$work/camp/merged/campaign.db" "$q")
b=$(sqlite3 "$work/whole-merged/campaign.db" "$q")
n=$(sqlite3 "$work/camp/merged/campaign.db" "select count(*) from runs")
[[ $n -eq 8 ]] || fail "merged database has $n runs, expected 8"
[[ $a == "$b" ]] || fail "sharded runs per planner ($a) differ from unsharded ($b)"
echo "campaign_slurm: 4 array tasks and the merge job completed; $n runs, per planner as unsharded: $a" | tr '\n' ' '
echo
