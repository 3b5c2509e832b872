#!/bin/bash
# A one-node Slurm on localhost runs the quickstart's simulate stage (workflows/quickstart.yaml, its
# scene and 3 x 3 design, figures off, train and map left out) as job arrays, then the stages job, to
# completion; metrics.csv must equal a serial run's byte for byte.
#
#   bash tests/cluster/slurm_localhost.sh BUILD/bin/spreadmap
#
# Needs Debian's slurm-wlm and munge (apt-get install slurm-wlm munge) and root: slurmd starts jobs
# as their owner. Everything lives in a temporary folder: its own munge key and socket, a
# slurm.conf for this host alone on two free loopback ports, slurmctld and slurmd started here and
# stopped (by their pid files) on exit. Nothing of the machine's own Slurm or munge is used.
set -euo pipefail
spreadmap=$(readlink -f "${1:?usage: slurm_localhost.sh PATH/TO/spreadmap}")
here=$(cd "$(dirname "$0")" && pwd)

fail() { echo "slurm_localhost: $*" >&2; exit 1; }
for p in munged mungekey slurmctld slurmd sbatch squeue sinfo; do
  command -v "$p" >/dev/null || [ -x "/usr/sbin/$p" ] ||
    fail "$p not found: install Debian's slurm-wlm and munge (apt-get install slurm-wlm munge)"
done
[ "$(id -u)" -eq 0 ] || fail "must run as root (slurmd starts each job as its owner)"
export PATH="$PATH:/usr/sbin"

top=$(mktemp -d /tmp/spreadmap_slurm.XXXXXX)
cleanup() {
  for pid_file in "$top/slurmd.pid" "$top/slurmctld.pid" "$top/munge/munged.pid"; do
    [ -s "$pid_file" ] && kill "$(cat "$pid_file")" 2>/dev/null || true
  done
  sleep 1
  rm -rf "$top"
}
trap cleanup EXIT

# two free TCP ports on the loopback
read -r ctld_port slurmd_port < <(python3 -c '
import socket
s = [socket.socket() for _ in range(2)]
for x in s: x.bind(("127.0.0.1", 0))
print(*[x.getsockname()[1] for x in s])')

workflow="$top/quickstart.yaml"
sed -e '/^  - train:/,$d' -e 's/^  - simulate:$/  - simulate:\n      render: false/' \
    -e 's/^  - characterise:$/  - characterise:\n      render: false/' "$here/../../workflows/quickstart.yaml" > "$workflow"
grep -q 'render: false' "$workflow" || fail "could not derive the test's workflow from workflows/quickstart.yaml"

mkdir -p "$top/munge" "$top/state" "$top/spool"
chmod 700 "$top/munge"
mungekey --create --keyfile="$top/munge/munge.key" --force
munged --force --socket="$top/munge/munge.socket" --key-file="$top/munge/munge.key" \
  --pid-file="$top/munge/munged.pid" --log-file="$top/munge/munged.log" --seed-file="$top/munge/seed"

node=$(hostname -s)
cpus=$(nproc)
cat > "$top/slurm.conf" <<CONF
ClusterName=spreadmaptest
SlurmctldHost=$node(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$top/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$top/state
SlurmdSpoolDir=$top/spool
SlurmctldPidFile=$top/slurmctld.pid
SlurmdPidFile=$top/slurmd.pid
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmctldLogFile=$top/slurmctld.log
SlurmdLogFile=$top/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
ReturnToService=2
NodeName=$node NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=1000 State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF="$top/slurm.conf"
slurmctld -c
slurmd -N "$node"
for _ in $(seq 60); do
  [ "$(sinfo -h -o %T 2>/dev/null)" = idle ] && break
  sleep 0.5
done
[ "$(sinfo -h -o %T)" = idle ] || { tail -20 "$top/slurmctld.log" "$top/slurmd.log" >&2; fail "the node did not come up"; }

# the reference, then the same workflow through Slurm
"$spreadmap" run "$workflow" --out "$top/serial" --jobs 2 -q
run="$top/run"
"$spreadmap" run "$workflow" --out "$run" --executor slurm | tee "$top/submitted"
[ "$(grep -c '^submitted job [0-9]*:' "$top/submitted")" -eq 3 ] || fail "expected three jobs (heap array, cases array, stages)"
for _ in $(seq 600); do
  [ -z "$(squeue -h)" ] && break
  sleep 0.5
done
[ -z "$(squeue -h)" ] || { squeue; fail "jobs still queued or running after 5 minutes"; }

for log in "$run"/slurm/logs/*.log; do echo "== $log"; cat "$log"; done
for k in 0 1 2 3 4 5 6 7 8; do
  grep -q '"status": "done"' "$run/cases/c00$k/case.json" || fail "case c00$k did not finish"
done
[ -f "$run/metrics.csv" ] || fail "the stages job wrote no metrics.csv"
cmp "$top/serial/metrics.csv" "$run/metrics.csv" || fail "metrics.csv differs from the serial run's"
grep -q 'characterise: 9 cases in metrics.csv' "$run/slurm/logs/stages.log" || fail "the stages job did not characterise"
echo "slurm_localhost: the quickstart's 9 cases as array tasks and the stages job: metrics.csv equals the serial run's"
