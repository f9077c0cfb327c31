#!/usr/bin/env bash
# Crash safety, proven by fault injection (issue 18): SIGKILL a sweep at
# random moments (small and large --batch, while it starts, writes, resumes),
# and a merge while it writes; every later --resume (or merge) must go on,
# never refuse, and end equal to the uninterrupted file (chaosweep compare).
#   sigkill_at_random_moments.sh CHAOSWEEP [KILLS_PER_PHASE] [SEED]
# Exit 0 when all holds; 1 with the failing step's output otherwise.
set -uo pipefail
bin=$1
kills=${2:-45}
RANDOM=${3:-1}
work=$(mktemp -d /tmp/chaosweep-sigkill.XXXXXX)
trap 'rm -rf "$work"' EXIT
cd "$work"

cat >cheap.toml <<'SPEC'
[fixed]
size = 10
sr = 2
max_time = 5
[axes]
A = {start = 0.1, stop = 0.9, num = 100}
B = {start = 0.1, stop = 0.9, num = 40}
C = {start = 0.1, stop = 0.9, num = 6}
SPEC

fail() {
  echo "FAIL: $*" >&2
  [[ -s err ]] && cat err >&2
  exit 1
}

# A random pause of up to $1 ms.
pause() { sleep "$(awk -v ms=$((RANDOM % $1)) 'BEGIN { printf "%.3f", ms / 1000 }')"; }

total_kills=0 mid_write=0 during_resume=0 rounds=0
"$bin" sweep cheap.toml -o ref.h5 --threads 2 -q 2>err || fail "the uninterrupted sweep"

# Kills a sweep of r.h5 (flags "$@") $kills times at random moments; after
# each kill it resumes, and whenever one completes it must equal ref.h5.
kill_sweeps() {
  local n=0 rc
  rm -f r.h5 r.h5.*
  while ((n < kills)); do
    [[ -e r.h5.partial ]] && resuming=1 || resuming=0
    "$bin" sweep cheap.toml -o r.h5 --threads 2 -q --resume "$@" 2>err &
    local pid=$!
    pause 900
    kill -9 $pid 2>/dev/null
    wait $pid
    rc=$?
    if ((rc == 137)); then
      ((n += 1, total_kills += 1, during_resume += resuming))
      if [[ -e r.h5.partial.journal || -e r.h5.partial.new.journal ]]; then ((mid_write += 1)); fi
    elif ((rc != 0)); then
      fail "sweep --resume $* exited $rc after a kill -9"
    fi
    if [[ -e r.h5 && ! -e r.h5.partial ]]; then
      "$bin" sweep cheap.toml -o r.h5 --threads 2 -q --resume "$@" 2>err || fail "a resume of a complete file"
      "$bin" compare r.h5 ref.h5 >cmp 2>err || { cat cmp >&2; fail "the resumed file differs from the uninterrupted one"; }
      ((rounds += 1))
      rm -f r.h5 r.h5.*
    fi
  done
  "$bin" sweep cheap.toml -o r.h5 --threads 2 -q --resume "$@" 2>err || fail "the last resume ($*)"
  "$bin" compare r.h5 ref.h5 >cmp 2>err || { cat cmp >&2; fail "the resumed file differs from the uninterrupted one"; }
  ((rounds += 1))
}

kill_sweeps --batch 150 --flush-seconds 0.05
kill_sweeps --batch 6000 --flush-seconds 0.1

# Merges killed at random moments; merging again (without --force) gives
# the file of the sweep.
for k in 0 1; do "$bin" sweep cheap.toml -o "s$k.h5" --shard "$k/2" --threads 2 -q 2>err || fail "shard $k"; done
# A merge of these shards takes a fraction of a second: the kills fall
# uniformly within one measured uninterrupted merge, so that most land.
t0=$(date +%s%N)
"$bin" merge -o m.h5 s0.h5 s1.h5 >/dev/null 2>err || fail "an uninterrupted merge"
merge_ms=$(((($(date +%s%N) - t0) / 1000000) + 1))
merge_kills=0
for ((i = 0; i < 3 * kills && merge_kills < kills / 3; i++)); do
  rm -f m.h5 m.h5.*
  "$bin" merge -o m.h5 s0.h5 s1.h5 >/dev/null 2>err &
  pid=$!
  pause "$merge_ms"
  kill -9 $pid 2>/dev/null
  wait $pid
  rc=$?
  if ((rc == 137)); then
    ((merge_kills += 1, total_kills += 1))
    if [[ -e m.h5.merging.journal ]]; then ((mid_write += 1)); fi
  elif ((rc != 0)); then
    fail "merge exited $rc"
  fi
  if [[ ! -e m.h5 ]]; then "$bin" merge -o m.h5 s0.h5 s1.h5 >/dev/null 2>err || fail "merge after a kill -9"; fi
  "$bin" compare m.h5 ref.h5 >cmp 2>err || { cat cmp >&2; fail "the merged file differs from the uninterrupted one"; }
done

echo "kill -9: $total_kills kills ($during_resume during a resume, $merge_kills during a merge, $mid_write in the" \
  "middle of a write), $rounds sweeps resumed to the uninterrupted file, 0 refusals"
((total_kills >= 100)) || fail "only $total_kills kills"
((merge_kills >= kills / 3)) || fail "only $merge_kills kills hit a merge"
((mid_write >= 10)) || fail "only $mid_write kills hit a write: the test proves little"
