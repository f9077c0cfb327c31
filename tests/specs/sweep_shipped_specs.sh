#!/usr/bin/env bash
# Sweeps every shipped spec in experiments/ (one shard of it where it is long)
# with 2 threads and checks that each exits 0 with one row per run of the
# shard. Under ThreadSanitizer the same set runs as COPIES sweeps at once,
# ROUNDS times, so that the load of a busy machine shakes out races (the
# seed002.toml crash showed only under load).
#   usage: sweep_shipped_specs.sh CHAOSWEEP SOURCE_DIR [COPIES] [ROUNDS] [MAX_RUNS]
set -euo pipefail
bin=$1 src=$2 copies=${3:-1} rounds=${4:-1} max_runs=${5:-48}
work=$(mktemp -d /tmp/chaosweep-specs.XXXXXX)
trap 'rm -rf "$work"' EXIT
fail=0
specs=("$src"/experiments/*.toml)
((${#specs[@]} > 0)) || { echo "no specs in $src/experiments" >&2; exit 1; }

# Runs of a spec, from `plan` (its second line: "runs  N ...").
runs_of() { "$bin" plan "$1" | awk '$1 == "runs" && !n++ { print $2 }'; }

for ((round = 0; round < rounds; ++round)); do
  pids=() names=()
  for spec in "${specs[@]}"; do
    name=$(basename "$spec" .toml)
    # A spec with [tune] is raced, not swept: its smallest race (first_test
    # seeds of two configurations) per case, one validation seed, runs cut at
    # 100 s; its rows are whatever the races spent, so only the exit is checked.
    tune=0 index=0 count=1 expect=any
    if grep -q '^\[tune\]' "$spec"; then
      tune=1
    else
      total=$(runs_of "$spec")
      [[ $total =~ ^[0-9]+$ ]] || { echo "$name: plan printed no run count" >&2; fail=1; continue; }
      # Shard K/N where N keeps the shard at most max_runs runs; K moves with the round.
      count=$(( (total + max_runs - 1) / max_runs ))
      index=$(( round % count ))
      expect=$(( (total - index + count - 1) / count ))
    fi
    for ((c = 0; c < copies; ++c)); do
      out="$work/$name.$round.$c.h5"
      if ((tune)); then
        ( "$bin" tune "$spec" -o "$out" --threads 2 --budget 10 --validation-seeds 1 --set max_time=100 -q \
            --progress never >"$out.log" 2>&1; echo $? >"$out.rc" ) &
      else
        ( "$bin" sweep "$spec" -o "$out" --threads 2 --shard "$index/$count" -q --progress never \
            >"$out.log" 2>&1; echo $? >"$out.rc" ) &
      fi
      pids+=($!) names+=("$name shard $index/$count copy $c|$out|$expect")
    done
    # Keep at most copies x 2 sweeps in flight: enough load, bounded memory.
    while (( $(jobs -rp | wc -l) >= copies * 2 )); do wait -n || true; done
  done
  wait || true
  for entry in "${names[@]}"; do
    IFS='|' read -r what out expect <<<"$entry"
    rc=$(cat "$out.rc" 2>/dev/null || echo missing)
    if [[ $rc != 0 ]]; then
      echo "FAIL $what: exit $rc" >&2; sed 's/^/  /' "$out.log" >&2; fail=1; continue
    fi
    rows=$(/usr/bin/h5dump -H -d /runs "$out" 2>/dev/null | awk '/DATASPACE/ { gsub(/[(),]/, " "); print $(NF-3) }')
    if [[ $expect != any && $rows != "$expect" ]] || [[ $expect == any && ! $rows =~ ^[1-9][0-9]*$ ]]; then
      echo "FAIL $what: $rows rows, expected $expect" >&2; fail=1
    fi
  done
done
((fail == 0)) && echo "every shipped spec swept: ${#specs[@]} specs x $copies copies x $rounds rounds"
exit $fail
