#!/usr/bin/env bash
# 2-thread scaling of a cheap sweep (issue 20: ">= 1.7x for a 1e5-run cheap
# sweep") with two binaries: each round runs OLD and NEW at --threads 1 and 2,
# interleaved, so that load on a shared machine hits both alike. Prints per
# binary the median wall seconds at one and two threads and their ratio (the
# scaling), and the median of the rounds' NEW/OLD wall at two threads.
#   usage: tests/benchmarks/scaling_ab.sh OLD_BIN NEW_BIN [ROUNDS=7]
set -euo pipefail
old=$1 new=$2 rounds=${3:-7}
[[ $rounds =~ ^[1-9][0-9]*$ ]] || { echo "ROUNDS must be a positive whole number, not '$rounds'" >&2; exit 2; }
spec=$(cd "$(dirname "$0")" && pwd)/specs/cheap.toml
work=$(mktemp -d /tmp/chaosweep-scaling-ab.XXXXXX)
trap 'rm -rf "$work"' EXIT
wall() {  # wall seconds of one sweep
  /usr/bin/time -f "%e" -o "$work/t" "$1" sweep "$spec" -o "$work/out.h5" --threads "$2" --force -q \
    --progress never >/dev/null 2>"$work/err" || { cat "$work/err" >&2; exit 3; }
  cat "$work/t"
}
for ((i = 0; i < rounds; i++)); do
  o1=$(wall "$old" 1) n1=$(wall "$new" 1) o2=$(wall "$old" 2) n2=$(wall "$new" 2)
  echo "$o1 $o2 $n1 $n2"
done >"$work/rounds"
/usr/bin/python3 - "$work/rounds" <<'EOF'
import statistics, sys
rows = [list(map(float, line.split())) for line in open(sys.argv[1])]
o1, o2, n1, n2 = (statistics.median(r[k] for r in rows) for k in range(4))
print(f"old: --threads 1 {o1:.2f} s, --threads 2 {o2:.2f} s, scaling {o1 / o2:.2f}x")
print(f"new: --threads 1 {n1:.2f} s, --threads 2 {n2:.2f} s, scaling {n1 / n2:.2f}x")
print(f"new/old at --threads 2: {statistics.median(r[3] / r[1] for r in rows):.3f} (median of {len(rows)} rounds)")
EOF
