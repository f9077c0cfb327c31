#!/usr/bin/env bash
# CPU seconds of the Chebyshev, bouncing and contraction planners' sweeps with
# two binaries, interleaved (OLD, NEW, OLD, NEW, ...) on one thread, so that
# load on a shared machine hits both alike (issue 20). Prints per planner the
# best CPU time of each binary, old/new of the bests (the speed-up) and the
# median of the pairs' ratios.
#   usage: tests/benchmarks/planners_ab.sh OLD_BIN NEW_BIN [PAIRS=5]
set -euo pipefail
old=$1 new=$2 pairs=${3:-5}
[[ $pairs =~ ^[1-9][0-9]*$ ]] || { echo "PAIRS must be a positive whole number, not '$pairs'" >&2; exit 2; }
src=$(cd "$(dirname "$0")/../.." && pwd)
work=$(mktemp -d /tmp/chaosweep-planners-ab.XXXXXX)
trap 'rm -rf "$work"' EXIT
cpu() {  # user + system CPU seconds of one sweep
  /usr/bin/time -f "%U %S" -o "$work/t" "$1" sweep "$2" -o "$work/out.h5" --threads 1 --force -q --progress never \
    >/dev/null 2>"$work/err" || { cat "$work/err" >&2; exit 3; }
  awk '{ print $1 + $2 }' "$work/t"
}
for case in chebyshev:experiments/seed001.toml bouncing:tests/benchmarks/specs/bouncing.toml \
  contraction:experiments/seed003.toml; do
  name=${case%%:*} spec=$src/${case#*:}
  ratios=() best_old=1e9 best_new=1e9
  for ((i = 0; i < pairs; i++)); do
    o=$(cpu "$old" "$spec") n=$(cpu "$new" "$spec")
    ratios+=("$(awk -v o="$o" -v n="$n" 'BEGIN { print (n > 0 ? o / n : 0) }')")
    best_old=$(awk -v a="$best_old" -v b="$o" 'BEGIN { print (b < a ? b : a) }')
    best_new=$(awk -v a="$best_new" -v b="$n" 'BEGIN { print (b < a ? b : a) }')
  done
  median=$(printf '%s\n' "${ratios[@]}" | sort -g | awk '{ v[NR] = $1 } END { print (NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2) }')
  printf '%-12s old %.2f CPU-s  new %.2f CPU-s  old/new %.2fx  (median of %d pairs %.2fx)\n' \
    "$name" "$best_old" "$best_new" "$(awk -v o="$best_old" -v n="$best_new" 'BEGIN { print o / n }')" "$pairs" "$median"
done
