#!/usr/bin/env bash
# Integration test against a real SLURM on localhost: starts munged,
# slurmctld and slurmd with a minimal configuration in a temporary directory,
# runs a sweep as a 4-task array with `chaosweep slurm --submit` (partition,
# time, memory and job name given), checks the
# merged file equals a single-machine run, deletes one task's output, checks
# `chaosweep status` names it, resubmits just that task and checks the set is
# complete again. Then a slow 3-task array, 2 at a time: while two tasks run,
# status lists them as running and the third as pending and resubmits
# nothing; one task's process is killed (kill -9) and status names its shard
# with the state SLURM gives it (from scontrol: this SLURM has no accounting
# storage), the others still live; the array is cancelled and status names
# them all. Stops the daemons it started,
# by pid.
# Usage: slurm_integration.sh CHAOSWEEP_BIN.  Exit 77 (skip) only where this
# machine cannot run SLURM (not root, packages missing, daemons do not start).
set -u
BIN=$1
skip() { echo "SKIP: $*"; exit 77; }
fail() { echo "FAIL: $*"; exit 1; }
[[ $(id -u) -eq 0 ]] || skip "slurmctld/slurmd need root here"
for c in munged munge unmunge slurmctld slurmd sbatch squeue sinfo scontrol scancel; do
  command -v "$c" >/dev/null || skip "$c is not installed (Debian: slurm-wlm munge; ./quickstart test installs them)"
done

BASE=$(mktemp -d /tmp/chaosweep_slurm.XXXXXX)
chmod 755 "$BASE"
export SLURM_CONF=$BASE/slurm.conf
SOCK=$BASE/munge/munge.socket
PIDS=()
cleanup() {
  for p in "${PIDS[@]}"; do kill "$p" 2>/dev/null; done
  for p in "${PIDS[@]}"; do
    for _ in $(seq 60); do kill -0 "$p" 2>/dev/null || break; sleep 0.5; done
    kill -9 "$p" 2>/dev/null
  done
  [[ -f $BASE/munge/munged.pid ]] && kill "$(cat "$BASE/munge/munged.pid")" 2>/dev/null
  sleep 0.5
  rm -rf "$BASE"
}
trap cleanup EXIT
wait_for() {  # seconds, command...
  local end=$((SECONDS + $1)); shift
  until "$@"; do [[ $SECONDS -ge $end ]] && return 1; sleep 0.5; done
}
port_free() { ! (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null; }

# munge with its own key, socket and pid file.
mkdir -p "$BASE"/{munge,state,spool,log,run,work}
chmod 755 "$BASE/munge"
dd if=/dev/urandom bs=1 count=1024 of="$BASE/munge/munge.key" 2>/dev/null
chmod 400 "$BASE/munge/munge.key"
munged --socket="$SOCK" --pid-file="$BASE/munge/munged.pid" --key-file="$BASE/munge/munge.key" \
  --log-file="$BASE/munge/munged.log" --seed-file="$BASE/munge/munged.seed" || skip "munged does not start"
wait_for 10 sh -c "munge -n -S '$SOCK' | unmunge -S '$SOCK' >/dev/null 2>&1" || skip "munge does not work"

# Two free ports, away from a system SLURM's.
PORT=$((17000 + ($$ % 1000) * 2))
while ! port_free "$PORT" || ! port_free $((PORT + 1)); do PORT=$((PORT + 2)); done
cat > "$SLURM_CONF" <<CONF
ClusterName=chaosweeptest
SlurmctldHost=localhost(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$PORT
SlurmdPort=$((PORT + 1))
AuthType=auth/munge
AuthInfo=socket=$SOCK
CredType=cred/munge
MailProg=/bin/true
StateSaveLocation=$BASE/state
SlurmdSpoolDir=$BASE/spool
SlurmctldPidFile=$BASE/run/slurmctld.pid
SlurmdPidFile=$BASE/run/slurmd.pid
SlurmctldLogFile=$BASE/log/slurmctld.log
SlurmdLogFile=$BASE/log/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/backfill
SchedulerParameters=batch_sched_delay=0
DependencyParameters=kill_invalid_depend
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
NodeName=localhost NodeAddr=127.0.0.1 NodeHostname=localhost CPUs=$(nproc) RealMemory=1000 State=UNKNOWN
PartitionName=debug Nodes=localhost Default=YES MaxTime=INFINITE State=UP
CONF
slurmctld -D >"$BASE/log/slurmctld.stdout" 2>&1 & PIDS+=($!)
slurmd -D -N localhost >"$BASE/log/slurmd.stdout" 2>&1 & PIDS+=($!)
if ! wait_for 60 sh -c '[ "$(sinfo -h -N -o %T 2>/dev/null)" = idle ]'; then
  tail -n 20 "$BASE"/log/*
  skip "slurmctld/slurmd did not bring the node up (logs above)"
fi
echo "SLURM up on localhost:$PORT"

wait_jobs() {  # job ids...
  local ids; ids=$(IFS=,; echo "$*")
  wait_for 600 sh -c "[ -z \"\$(squeue -h -j $ids 2>/dev/null)\" ]" || { squeue; fail "jobs $ids did not finish"; }
}

cat > "$BASE/spec.toml" <<'SPEC'
[fixed]
size = 12
sr = 2
max_time = 2000
[axes]
A = [0.4, 0.5, 0.6]
B = [0.2, 0.3]
ds_index = [1, 2, 3]
SPEC
RUN=$BASE/work
# Values in the forms chaosweep slurm checks, to show SLURM takes them as written.
out=$("$BIN" slurm "$BASE/spec.toml" --tasks 4 -o "$RUN" --partition debug --time 0-0:10 --mem 100M \
  --job-name cw-integration --submit) || fail "chaosweep slurm --submit: $out"
echo "$out"
read -r array_job merge_job < <(echo "$out" | sed -n 's/^submitted array job \([0-9]*\) and merge job \([0-9]*\) .*/\1 \2/p')
[[ -n ${array_job:-} && -n ${merge_job:-} ]] || fail "no job ids in: $out"
wait_jobs "$array_job" "$merge_job"
[[ -f $RUN/results.h5 ]] || { cat "$RUN"/logs/*; fail "the merge job wrote no results.h5"; }

"$BIN" sweep "$BASE/spec.toml" -o "$BASE/single.h5" -q || fail "single-machine sweep"
"$BIN" compare "$RUN/results.h5" "$BASE/single.h5" || fail "merged cluster results differ from the single-machine run"

# Lose one task's output: status names it, a resubmission of it completes the set.
rm -f "$RUN/shard_2.h5"
status=$("$BIN" status "$RUN"); rc=$?
echo "$status"
[[ $rc -eq 1 ]] || fail "status should exit 1 with a shard missing"
grep -q "^missing  1: 2$" <<<"$status" || fail "status does not name shard 2 as missing"
grep -q -- "--array=2$" <<<"$status" || fail "status does not print --array=2"
job=$(sbatch --parsable --array=2 "$RUN/sweep.sbatch") || fail "resubmission"
wait_jobs "${job%%;*}"
"$BIN" status "$RUN" || fail "status after the resubmission"
"$BIN" merge --force -o "$RUN/results.h5" "$RUN"/shard_*.h5 >/dev/null || fail "merge after the resubmission"
"$BIN" compare "$RUN/results.h5" "$BASE/single.h5" >/dev/null || fail "results differ after the resubmission"
grep -q "^array $array_job$" "$RUN/jobs.txt" || fail "jobs.txt does not record array job $array_job"

# Live tasks, a pending one and a killed one. Runs to full coverage of a
# large map: each takes seconds, so the tasks run while status looks (they
# are cancelled). Two at once need two CPUs.
if [[ $(nproc) -lt 2 ]]; then
  echo "1 passed, 0 failed: SLURM array, merge, status and resubmission on localhost (one CPU: live tasks not tried)"
  exit 0
fi
A=$(LC_ALL=C seq -s ', ' 0.400 0.002 0.478)  # 40 values: 40 runs a task, more than the test waits for
cat > "$BASE/slow.toml" <<SPEC
[fixed]
size = 300
sr = 1
dc = 1.0
max_time = 1000000000
[axes]
A = [$A]
B = [0.2]
ds_index = [1, 2, 3]
SPEC
SLOW=$BASE/slow
out=$("$BIN" slurm "$BASE/slow.toml" --tasks 3 --concurrency 2 --cpus 1 -o "$SLOW" --submit) || fail "slurm --submit (slow): $out"
read -r slow_job _ < <(echo "$out" | sed -n 's/^submitted array job \([0-9]*\) and merge job \([0-9]*\) .*/\1 \2/p')
[[ -n ${slow_job:-} ]] || fail "no job id in: $out"
both_locked() { [[ -s $SLOW/shard_0.h5.lock && -s $SLOW/shard_1.h5.lock ]]; }
wait_for 120 both_locked || { squeue; cat "$SLOW"/logs/*; fail "the slow tasks did not start"; }
status=$("$BIN" status "$SLOW"); rc=$?
echo "$status"
[[ $rc -eq 1 ]] || fail "status should exit 1 while tasks run"
grep -q "^running  2: 0,1$" <<<"$status" || fail "status does not list both live tasks as running"
grep -q "^pending  1: 2$" <<<"$status" || fail "status does not list the throttled task as pending"
grep -q "^nothing to resubmit" <<<"$status" || fail "status would resubmit a live task"
grep -q "^note: sacct failed" <<<"$status" || fail "status does not say sacct has no accounting here"

pid=$(sed -n 's/^process \([0-9]*\) on .*/\1/p' "$SLOW/shard_1.h5.lock")
[[ -n $pid ]] || fail "no pid in $SLOW/shard_1.h5.lock"
kill -9 "$pid"
task1_ended() { ! squeue -h -r -j "$slow_job" -o %K 2>/dev/null | grep -qx 1; }
wait_for 60 task1_ended || fail "task 1 still in squeue after kill -9"
status=$("$BIN" status "$SLOW"); rc=$?
echo "$status"
[[ $rc -eq 1 ]] || fail "status should exit 1 with a task killed"
grep -Eq "^running  [12]: 0(,2)?$" <<<"$status" || fail "status does not keep task 0 as running"
grep -Eq "^(running  2: 0,2|pending  1: 2)$" <<<"$status" || fail "status does not keep task 2 live"
grep -Eq "^  shard 1: .*job ${slow_job}_1 [A-Z_]+ \(exit [0-9]+:[0-9]+\), no lock$" <<<"$status" ||
  fail "status does not name the killed task's state and exit code"
grep -q "^failed   1: 1$" <<<"$status" || fail "status does not list the killed task as failed"
grep -q -- "--array=1$" <<<"$status" || fail "status does not print --array=1 for the killed task"

scancel "$slow_job" || fail "scancel"
wait_jobs "$slow_job"
status=$("$BIN" status "$SLOW")
echo "$status"
grep -q "^  shard 0: .*job ${slow_job}_0 CANCELLED" <<<"$status" || fail "status does not name the cancelled task"
grep -q -- "--array=0,1,2$" <<<"$status" || fail "status does not print --array=0,1,2 after the cancel"
echo "1 passed, 0 failed: SLURM array, merge, status (live, killed, cancelled tasks) and resubmission on localhost"
