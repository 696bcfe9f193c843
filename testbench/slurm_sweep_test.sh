#!/usr/bin/env bash
# A real Slurm cluster of one node for `tfu sweep --slurm` (docs/design-space.md, "On a Slurm
# cluster"). In a temporary directory it starts its own munged (own socket, Debian's key), slurmctld
# and slurmd on localhost with a generated slurm.conf (private ports), runs an 8-point sweep on the
# local runner, submits the same spec with --slurm as a 4-task job array (an sbatch option passed
# through), waits for the array, collects it, and requires results.csv to equal the local runner's
# byte for byte. Every daemon it started is stopped on exit (trap), by its pid file.
#
# The array's directory has a hostile name: the batch script must quote it (the task logs land in it
# and no injected command runs).
#
#   testbench/slurm_sweep_test.sh BUILD/bin/tfu [WORK]
#
# Needs root (munged runs as the munge user) and Debian's slurm-wlm and munge (scripts/bootstrap
# installs them); without them it exits 77, which ctest reports as skipped. Exit 1 on any failure.
set -euo pipefail
tfu=$(realpath "$1")
work=${2:-$(mktemp -d /tmp/tfu-slurm-test.XXXXXX)}

for b in munged slurmctld slurmd sbatch squeue sinfo; do
  if ! command -v "$b" >/dev/null 2>&1 && [[ ! -x /usr/sbin/$b ]]; then
    echo "slurm_sweep_test: SKIP: $b not installed (scripts/bootstrap installs slurm-wlm and munge)"
    exit 77
  fi
done
if [[ $(id -u) -ne 0 ]]; then
  echo "slurm_sweep_test: SKIP: needs root (munged runs as the munge user, slurmd as root)"
  exit 77
fi
export PATH=$PATH:/usr/sbin

rm -rf "$work" && mkdir -p "$work"
chmod 755 "$work"
work=$(realpath "$work")
mkdir -p "$work/munge" "$work/slurm/state" "$work/slurm/spool"
# The array's directory has a hostile name (spaces, quotes, $(...), backticks, ;, #, glob characters,
# and sbatch's own pattern characters %j and %%): the batch script quotes it and writes its '%' as %%,
# and sbatch reads the quoted #SBATCH --output line (the four task logs land in DIR/slurm below).
run="$work/slurm run 'q' \"d\" \$(touch MARK1) \`touch MARK2\`;touch MARK3 #*?[ab] %j %% 100%"
chown munge:munge "$work/munge" && chmod 755 "$work/munge"

cleanup() {
  local rc=$?
  for pidfile in "$work/slurm/slurmd.pid" "$work/slurm/slurmctld.pid" "$work/munge/munged.pid"; do
    if [[ -s $pidfile ]]; then
      pid=$(cat "$pidfile")
      kill "$pid" 2>/dev/null || true
      for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
      kill -9 "$pid" 2>/dev/null || true
    fi
  done
  if [[ $rc -ne 0 ]]; then
    echo "slurm_sweep_test: FAILED (exit $rc); logs:"
    tail -n 15 "$work"/slurm/*.log "$work"/munge/*.log "$run"/slurm/*.log 2>/dev/null || true
  fi
  exit $rc
}
trap cleanup EXIT

# munged on its own socket, as Debian's munge user with Debian's key.
su -s /bin/sh munge -c "munged --socket=$work/munge/munge.sock --pid-file=$work/munge/munged.pid \
  --log-file=$work/munge/munged.log --seed-file=$work/munge/munged.seed --key-file=/etc/munge/munge.key"

# Private ports from this process id, so that parallel runs do not collide.
port=$((20000 + ($$ % 4000) * 2))
export SLURM_CONF=$work/slurm/slurm.conf
cat >"$SLURM_CONF" <<EOF
ClusterName=tfutest
SlurmctldHost=localhost
SlurmUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$work/munge/munge.sock
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$work/slurm/state
SlurmdSpoolDir=$work/slurm/spool
SlurmctldPidFile=$work/slurm/slurmctld.pid
SlurmdPidFile=$work/slurm/slurmd.pid
SlurmctldLogFile=$work/slurm/slurmctld.log
SlurmdLogFile=$work/slurm/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
JobCompType=jobcomp/none
AccountingStorageType=accounting_storage/none
ReturnToService=2
NodeName=localhost CPUs=2 RealMemory=2000 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
EOF
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF" -N localhost
for i in $(seq 100); do
  sinfo -h -o %t 2>/dev/null | grep -Eq '^(idle|mix)' && break
  [[ $i == 100 ]] && { echo "slurm_sweep_test: the node did not become idle in 20 s"; exit 1; }
  sleep 0.2
done

# 8 points: 2 filters x 2 capacities x 2 ways, a small render.
cat >"$work/spec.json" <<'EOF'
{"scenes": ["ground_plane"], "filters": ["LINEAR", "trilinear"], "width": 64, "height": 48,
 "base": {"memory": {"latency": 60}},
 "grid": {"cache.capacity_bytes": [4096, 16384], "cache.ways": [1, 4]}}
EOF
"$tfu" sweep "$work/spec.json" --out "$work/local-run" --workers 2 --quiet >"$work/local.txt"
out=$(cd "$work" && "$tfu" sweep "$work/spec.json" --out "$run" --slurm --tasks 4 --sbatch-arg=--partition=debug \
      --sbatch-arg=--time=10)
echo "$out"
job=$(sed -n 's/.* submitted as Slurm job \([0-9][0-9]*\).*/\1/p' <<<"$out")
[[ -n $job ]] || { echo "slurm_sweep_test: no job id in the output"; exit 1; }
grep -q -- '--partition=debug' "$run/slurm/sweep.sbatch" &&
  { echo "sbatch options belong on the command line"; exit 1; }
for i in $(seq 600); do
  [[ -z $(squeue -h -j "$job" 2>/dev/null) ]] && break
  [[ $i == 600 ]] && { echo "slurm_sweep_test: job $job still queued after 120 s"; exit 1; }
  sleep 0.2
done
tasks=$(ls "$run/slurm"/task-*.log | wc -l)
[[ $tasks == 4 ]] || { echo "slurm_sweep_test: expected 4 array task logs, found $tasks"; exit 1; }
"$tfu" sweep --collect "$run"
cmp "$work/local-run/results.csv" "$run/results.csv"
marks=$(ls "$work" | grep '^MARK' || true)
[[ -z $marks ]] || { echo "slurm_sweep_test: an injected command ran: $marks"; exit 1; }
rows=$(($(wc -l <"$run/results.csv") - 1))
[[ $rows == 8 ]] || { echo "slurm_sweep_test: expected 8 rows, found $rows"; exit 1; }
echo "slurm_sweep_test: job $job, 4 array tasks, 8 points: results.csv equals the local runner's byte for byte"
