#!/usr/bin/env bash
# CPU time of a cheap sweep (specs/cheap.toml: 1e5 short runs, so the
# engine's per-run costs weigh as much as the kernel) with two binaries,
# taking turns PAIRS times. Prints the median user + system CPU seconds of
# each and the median of the pairs' NEW/OLD ratios (CPU and wall). An A/A
# run (one binary twice) reads 0.99-1.02 here: smaller differences are noise.
#   usage: tests/benchmarks/cheap_ab.sh OLD_BIN NEW_BIN [PAIRS=15] [THREADS=1]
set -euo pipefail
old=$1 new=$2 pairs=${3:-15} threads=${4:-1}
[[ $pairs =~ ^[1-9][0-9]*$ ]] || { echo "PAIRS must be a positive whole number, not '$pairs'" >&2; exit 2; }
[[ $threads =~ ^[1-9][0-9]*$ ]] || { echo "THREADS must be a positive whole number, not '$threads'" >&2; exit 2; }
spec=$(cd "$(dirname "$0")" && pwd)/specs/cheap.toml
work=$(mktemp -d /tmp/chaosweep-cheap-ab.XXXXXX)
trap 'rm -rf "$work"' EXIT
one() {  # wall, user and system seconds of one sweep
  /usr/bin/time -f "%e %U %S" -o "$work/t" "$1" sweep "$spec" -o "$work/out.h5" --threads "$threads" --force -q \
    --progress never >/dev/null 2>"$work/err" || { cat "$work/err" >&2; exit 3; }
  cat "$work/t"
}
for ((i = 0; i < pairs; i++)); do
  echo "$(one "$old") $(one "$new")"
done >"$work/pairs"
/usr/bin/python3 - "$work/pairs" <<'PY'
import statistics, sys
rows = [list(map(float, line.split())) for line in open(sys.argv[1])]
old = [r[1] + r[2] for r in rows]
new = [r[4] + r[5] for r in rows]
print(f"old {statistics.median(old):.3f} CPU-s, new {statistics.median(new):.3f} CPU-s (medians)")
print(f"new/old: CPU {statistics.median(n / o for n, o in zip(new, old)):.3f}, "
      f"wall {statistics.median(r[3] / r[0] for r in rows):.3f} (median of {len(rows)} pairs)")
PY
