#!/usr/bin/env bash
# Results before and after a change that must not change them (issue 19):
# sweeps every shipped spec in experiments/ with both binaries (the whole spec
# when it has at most MAX_RUNS runs, else shard 0 of the fewest shards that
# keep a shard within MAX_RUNS; a tune spec: its race at a budget of 100
# runs per case) and runs NEW's `compare` on the two files.
# Prints one line per spec; exit 0 when every pair is identical.
#   usage: tests/benchmarks/same_results.sh OLD_BIN NEW_BIN [MAX_RUNS=2000] [THREADS=2]
set -uo pipefail
old=$1 new=$2 max_runs=${3:-2000} threads=${4:-2}
src=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d /tmp/chaosweep-same.XXXXXX)
trap 'rm -rf "$work"' EXIT
fail=0
# both NAME WHAT COMMAND...: runs COMMAND -o FILE with each binary, then compares the files.
both() {
  local name=$1 what=$2 b line
  shift 2
  for b in old new; do
    "${!b}" "$@" -o "$work/$name.$b.h5" --threads "$threads" -q --progress never >"$work/$name.$b.log" 2>&1 ||
      { echo "$name: the $b binary failed"; cat "$work/$name.$b.log"; fail=1; }
  done
  if line=$("$new" compare "$work/$name.old.h5" "$work/$name.new.h5" 2>&1); then
    echo "$name ($what): $(grep -o '[0-9]* identical' <<<"$line" | head -1)"
  else
    echo "$name ($what): DIFFERENT"; echo "$line" | head -20; fail=1
  fi
}
for spec in "$src"/experiments/*.toml; do
  name=$(basename "$spec" .toml)
  plan=$("$new" plan "$spec")
  if [[ $plan == "tune "* ]]; then
    # A tune spec: the race of every case at a budget of 100 runs, 4 validation seeds.
    both "$name" "tune, budget 100 per case" tune "$spec" --budget 100 --validation-seeds 4
    continue
  fi
  total=$(awk '$1 == "runs" && !n++ { print $2 }' <<<"$plan")
  [[ $total =~ ^[0-9]+$ ]] || { echo "$name: plan printed no run count"; fail=1; continue; }
  count=$(( (total + max_runs - 1) / max_runs ))
  both "$name" "shard 0/$count of $total runs" sweep "$spec" --shard "0/$count"
done
exit $fail
