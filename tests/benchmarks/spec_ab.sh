#!/usr/bin/env bash
# CPU time (user + system) of one sweep spec with two binaries, taking turns
# PAIRS times (OLD, NEW, OLD, NEW, ...), so that load on a shared machine hits
# both alike. Prints the median CPU seconds of each, the best of each and the
# median of the pairs' NEW/OLD ratios (CPU and wall); checks that the last
# pair's files are identical (`compare`). Run it a second time with the
# binaries swapped: on a shared host the later run of a pair can read slower.
#   usage: tests/benchmarks/spec_ab.sh SPEC OLD_BIN NEW_BIN [PAIRS=12] [THREADS=1]
set -euo pipefail
(($# >= 3)) || { echo "usage: $0 SPEC OLD_BIN NEW_BIN [PAIRS=12] [THREADS=1]" >&2; exit 2; }
spec=$1 old=$2 new=$3 pairs=${4:-12} threads=${5:-1}
[[ $pairs =~ ^[1-9][0-9]*$ ]] || { echo "PAIRS must be a positive whole number, not '$pairs'" >&2; exit 2; }
[[ $threads =~ ^[1-9][0-9]*$ ]] || { echo "THREADS must be a positive whole number, not '$threads'" >&2; exit 2; }
[[ -f $spec ]] || { echo "no spec file '$spec'" >&2; exit 2; }
work=$(mktemp -d /tmp/chaosweep-spec-ab.XXXXXX)
trap 'rm -rf "$work"' EXIT
one() {  # wall and CPU seconds of one sweep, its file left in $work/$2.h5
  /usr/bin/time -f "%e %U %S" -o "$work/t" "$1" sweep "$spec" -o "$work/$2.h5" --threads "$threads" --force -q \
    --progress never >/dev/null 2>"$work/err" || { cat "$work/err" >&2; exit 3; }
  awk '{ print $1, $2 + $3 }' "$work/t"
}
for ((i = 0; i < pairs; i++)); do
  echo "$(one "$old" old) $(one "$new" new)"
done >"$work/pairs"
"$new" compare "$work/old.h5" "$work/new.h5" | head -1
/usr/bin/python3 - "$work/pairs" <<'PY'
import statistics, sys
rows = [tuple(map(float, line.split())) for line in open(sys.argv[1])]  # old wall, old CPU, new wall, new CPU
o, n = [r[1] for r in rows], [r[3] for r in rows]
print(f"old: median {statistics.median(o):.3f} CPU-s, best {min(o):.3f}; "
      f"new: median {statistics.median(n):.3f}, best {min(n):.3f}")
print(f"new/old: median of {len(rows)} pairs {statistics.median(b / a for a, b in zip(o, n)):.3f} CPU, "
      f"{statistics.median(r[2] / r[0] for r in rows):.3f} wall; best vs best {min(n) / min(o):.3f} CPU")
PY
