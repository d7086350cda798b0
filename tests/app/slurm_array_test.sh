#!/usr/bin/env bash
# A real scheduler in the tests: a single-node Slurm from Debian's packages
# (slurmctld, slurmd, slurm-client, munge; `make setup` installs them) runs
# `dfrecon batch` as an array job of 3 tasks over a manifest of 10 entries
# (synthetic shapes, the examples, a broken file). Checks that the merged
# batch-report equals a single-machine run's and a --shard run's, and that a
# resubmission skips every finished entry. Needs root (munged runs as the
# munge user, the daemons as root); exits 77 (ctest: skipped) with the reason
# otherwise. Everything lives in a scratch folder: its own munge key and
# socket, slurm.conf, state, spool, logs and pid files; the daemons are
# stopped by their pid files on every way out.
#
# Usage: slurm_array_test.sh DFRECON EXAMPLES_DIR
set -euo pipefail
dfrecon=$(realpath "$1")
examples=$(realpath "$2")

skip() {
  echo "SKIPPED: $*"
  exit 77
}
[ "$(id -u)" -eq 0 ] || skip "needs root to start munged and the Slurm daemons"
for tool in munged slurmctld slurmd sbatch sinfo runuser; do
  command -v "$tool" >/dev/null ||
    skip "$tool is not installed (make setup installs slurmctld slurmd slurm-client munge)"
done
id munge >/dev/null 2>&1 || skip "no munge user (the munge package makes it)"

scratch=$(mktemp -d /tmp/dfrecon-slurm-XXXXXX)
chmod 755 "$scratch"

stop_by_pidfile() {  # NAME PIDFILE: SIGTERM, then SIGKILL after 10 s
  local pid
  [ -s "$2" ] || return 0
  pid=$(cat "$2")
  kill "$pid" 2>/dev/null || return 0
  for _ in $(seq 100); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
  echo "$1 ($pid) did not stop on SIGTERM; killing it"
  kill -9 "$pid" 2>/dev/null || true
}
cleanup() {
  local rc=$?
  stop_by_pidfile slurmd "$scratch/slurmd.pid"
  stop_by_pidfile slurmctld "$scratch/slurmctld.pid"
  stop_by_pidfile munged "$scratch/munge/munged.pid"
  if [ "$rc" -ne 0 ] && [ "$rc" -ne 77 ]; then
    for log in "$scratch"/slurmctld.log "$scratch"/slurmd.log "$scratch"/munge/munged.log \
      "$scratch"/task-*.out "$scratch"/runs.err; do
      [ -f "$log" ] && { echo "---- $log"; tail -n 20 "$log"; }
    done
  fi
  [ -n "${KEEP_SLURM_SCRATCH:-}" ] || rm -rf "$scratch"
  exit "$rc"
}
trap cleanup EXIT

fail() {
  echo "FAILED: $*"
  exit 1
}

# ---- the archive: 10 entries, one of them broken ------------------------
archive=$scratch/archive
mkdir -p "$archive"
# SYNTH_OPTIONS (e.g. "--points 512 --spacing 0.25") makes the shapes
# heavier, for timings; the test itself runs them as synth makes them.
for shape in sphere torus two-blobs y capsule ellipsoid; do
  # shellcheck disable=SC2086
  "$dfrecon" synth "$shape" ${SYNTH_OPTIONS:-} -o "$archive/$shape.slices" >/dev/null
done
cp "$examples/torus.slices" "$examples/two-rois.slices" "$examples/y.slices" "$archive/"
printf 'dfrecon-slices 1\nroi A\nslice 0\ncontour 2\n0 0\n' >"$archive/broken.slices"
cat >"$archive/manifest.csv" <<'CSV'
input,id,roi,cap
sphere.slices,sphere,,
torus.slices,torus-synth,,dome
two-blobs.slices,,,
y.slices,y-synth,,
capsule.slices,capsule,,none
ellipsoid.slices,ellipsoid,,
torus.slices,torus-example,,
two-rois.slices,two-rois,,
y.slices,y-example,,
broken.slices,broken,,
CSV
manifest=$archive/manifest.csv
entries=10

seconds_since() { echo "$(($(date +%s%N) - $1))" | awk '{printf "%.1f", $1 / 1e9}'; }

# ---- one machine (one entry at a time, and two), and --shard by hand ------
for jobs in 1 2; do
  start=$(date +%s%N)
  rc=0
  "$dfrecon" -q batch "$manifest" -o "$scratch/single-j$jobs" -j "$jobs" >/dev/null \
    2>>"$scratch/runs.err" || rc=$?
  echo "one machine, -j $jobs: $(seconds_since "$start") s"
  [ "$rc" -eq 2 ] || fail "one machine, -j $jobs: exit $rc, expected 2 (the broken file)"
done
for i in 0 1 2; do
  rc=0
  "$dfrecon" -q batch "$manifest" -o "$scratch/sharded" --shard "$i/3" >/dev/null \
    2>>"$scratch/runs.err" || rc=$?
  [ "$rc" -eq 0 ] || [ "$rc" -eq 2 ] || fail "--shard $i/3: exit $rc"
done

# ---- a single-node Slurm ---------------------------------------------------
mkdir -p "$scratch/munge" "$scratch/state" "$scratch/spool"
chown munge:munge "$scratch/munge"
chmod 711 "$scratch/munge"  # munged wants its socket's folder searchable by all
dd if=/dev/urandom of="$scratch/munge/munge.key" bs=1024 count=1 status=none
chown munge:munge "$scratch/munge/munge.key"
chmod 400 "$scratch/munge/munge.key"
socket=$scratch/munge/munge.socket
runuser -u munge -- munged --key-file="$scratch/munge/munge.key" --socket="$socket" \
  --pid-file="$scratch/munge/munged.pid" --log-file="$scratch/munge/munged.log" \
  --seed-file="$scratch/munge/munged.seed"

host=$(hostname -s)
port=$((20000 + $$ % 20000))
cat >"$scratch/slurm.conf" <<CONF
ClusterName=dfrecon-test
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
MpiDefault=none
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SchedulerType=sched/backfill
ReturnToService=2
SlurmctldPort=$port
SlurmdPort=$((port + 1))
StateSaveLocation=$scratch/state
SlurmdSpoolDir=$scratch/spool
SlurmctldPidFile=$scratch/slurmctld.pid
SlurmdPidFile=$scratch/slurmd.pid
SlurmctldLogFile=$scratch/slurmctld.log
SlurmdLogFile=$scratch/slurmd.log
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) RealMemory=100 State=UNKNOWN
PartitionName=dfrecon Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$scratch/slurm.conf
slurmctld -f "$SLURM_CONF"
slurmd -f "$SLURM_CONF"
for _ in $(seq 300); do
  state=$(sinfo -h -N -o %t 2>/dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.1
done
[ "$state" = idle ] || fail "the node did not come up idle within 30 s (sinfo: '$state')"

# The body of the array job is the same command line for every task: the
# shard comes from SLURM_ARRAY_TASK_ID and SLURM_ARRAY_TASK_COUNT.
cat >"$scratch/batch.sbatch" <<JOB
#!/bin/bash
echo "started \$(date +%s%N)"
"$dfrecon" batch "$manifest" -o "$scratch/array" -j 1
rc=\$?
echo "ended \$(date +%s%N)"
exit \$rc
JOB
submit() {  # the highest task exit code is sbatch --wait's
  local rc=0
  sbatch --array=0-2 --wait --quiet -o "$scratch/task-%a.out" "$scratch/batch.sbatch" || rc=$?
  [ "$rc" -eq 2 ] || fail "sbatch --wait: exit $rc, expected 2 (the broken file's task)"
}
start=$(date +%s%N)
submit
first=$(cat "$scratch"/task-*.out | awk '/^started/ {print $2}' | sort -n | head -1)
last=$(cat "$scratch"/task-*.out | awk '/^ended/ {print $2}' | sort -n | tail -1)
echo "Slurm array of 3 tasks: $(((last - first) / 1000000)) ms from the first task's start to" \
  "the last one's end; sbatch --wait returned after $(seconds_since "$start") s (it polls)"
for i in 0 1 2; do
  grep -q "SLURM_ARRAY_TASK_ID $i of SLURM_ARRAY_TASK_COUNT 3" "$scratch/task-$i.out" ||
    fail "task $i did not take its shard from Slurm: $(cat "$scratch/task-$i.out")"
done

# ---- one report, whichever way it ran -------------------------------------
for run in single-j1 single-j2 sharded array; do
  "$dfrecon" batch-report "$scratch/$run" --no-seconds >/dev/null
done
for ext in csv json; do
  for run in single-j2 sharded array; do
    cmp "$scratch/single-j1/batch-report.$ext" "$scratch/$run/batch-report.$ext" ||
      fail "$run's batch-report.$ext differs from one machine's (-j 1)"
  done
done
rows=$(($(wc -l <"$scratch/array/batch-report.csv") - 1))
[ "$rows" -ge "$entries" ] || fail "the report has $rows rows for $entries entries"

# ---- resubmitted, every finished entry is skipped ---------------------------
records_before=$(cat "$scratch"/array/*/record.json | sha256sum)
submit
skipped=0
for i in 0 1 2; do
  line=$(grep '^batch: ' "$scratch/task-$i.out") || fail "task $i printed no summary"
  [[ $line =~ \ 0\ done,\ ([0-9]+)\ skipped ]] || fail "task $i ran entries again: $line"
  skipped=$((skipped + BASH_REMATCH[1]))
done
[ "$skipped" -eq "$entries" ] || fail "$skipped of $entries entries skipped"
[ "$(cat "$scratch"/array/*/record.json | sha256sum)" = "$records_before" ] ||
  fail "a resubmission changed a record"
echo "PASSED: the array's report equals one machine's (-j 1, -j 2) and --shard's;" \
  "the resubmission skipped all $entries entries"
