#!/bin/sh
# Compares two chaosweep builds' lane pipeline on a shared, noisy machine:
# alternates `OLD bench --pipeline TARGET` and `NEW bench --pipeline TARGET`
# PAIRS times and prints the median of the pair ratios NEW/OLD and the ratio
# of the best runs (load only ever adds time). An A/A run (one binary twice)
# reads 1.00-1.02 here: smaller differences are noise.
#   usage: tests/benchmarks/ab.sh OLD_BIN NEW_BIN [PAIRS=20] [SECONDS=0.4] [TARGET=avx512]
set -eu
old=$1 new=$2 pairs=${3:-20} seconds=${4:-0.4} target=${5:-avx512}
runs=$(mktemp)
trap 'rm -f "$runs"' EXIT
i=0
while [ "$i" -lt "$pairs" ]; do
  a=$("$old" bench --pipeline "$target" --seconds "$seconds")
  b=$("$new" bench --pipeline "$target" --seconds "$seconds")
  echo "$a $b" >>"$runs"
  i=$((i + 1))
done
best_old=$(cut -d' ' -f1 "$runs" | sort -g | head -1)
best_new=$(cut -d' ' -f2 "$runs" | sort -g | head -1)
awk '{ print $2 / $1 }' "$runs" | sort -g | awk -v bo="$best_old" -v bn="$best_new" '
  { r[NR] = $1 }
  END {
    med = NR % 2 ? r[(NR + 1) / 2] : (r[NR / 2] + r[NR / 2 + 1]) / 2
    printf "old best %.3f ns, new best %.3f ns per lane-step; new/old: median of %d pairs %.3f, best vs best %.3f\n",
           bo, bn, NR, med, bn / bo
  }'
