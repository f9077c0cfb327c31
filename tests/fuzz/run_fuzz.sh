#!/usr/bin/env bash
# Builds a libFuzzer target with clang (Debian clang-14, libclang-rt-14-dev)
# under ASan+UBSan and runs it for a bounded time on a temporary corpus (new
# inputs stay there): the hand-written seeds of tests/fuzz/corpus_<dir> and,
# for the parsers, the shipped inputs (experiments/*.toml, experiments/envs/
# *.toml), read at run time so that no copy of them goes stale.
#   run_fuzz.sh NAME SECONDS SOURCE|FLAG...  exit 0 clean, 1 a finding, 77 no clang
# (a SOURCE is relative to the source tree, or an absolute path ending in .cpp,
# e.g. a generated file; other arguments starting with - or / are compiler
# flags and libraries, passed as they are)
# FUZZ_SEED (default 1) and FUZZ_RUNS (default 200000) set the search; give
# FUZZ_RUNS=-1 to run until SECONDS.
set -euo pipefail
name=$1 seconds=$2
shift 2
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
cxx=$(command -v clang++-14 || command -v clang++ || true)
if [[ -z "$cxx" ]]; then
  echo "run_fuzz: clang++ not found (apt-get install clang libclang-rt-14-dev)" >&2
  exit 77
fi
work=$(mktemp -d /tmp/chaosweep-fuzz.XXXXXX)
trap 'rm -rf "$work"' EXIT
srcs=() flags=()
for s in "$@"; do
  if [[ $s == /*.cpp ]]; then srcs+=("$s")
  elif [[ $s == -* || $s == /* ]]; then flags+=("$s")
  else srcs+=("$root/$s"); fi
done
"$cxx" -std=c++20 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
  -I"$root" \
  "$here/fuzz_$name.cpp" "${srcs[@]}" ${flags[@]+"${flags[@]}"} -o "$work/fuzz_$name"
mkdir -p "$work/corpus"
shopt -s nullglob
case $name in
  sweep_spec) seeds=("$here"/corpus_spec/* "$root"/experiments/*.toml) ;;
  environment) seeds=("$here"/corpus_env/* "$root"/experiments/envs/*.toml) ;;
  *) seeds=("$here/corpus_$name"/*) ;;
esac
if ((${#seeds[@]} == 0)); then
  echo "run_fuzz: no seed inputs for $name" >&2
  exit 1
fi
cp "${seeds[@]}" "$work/corpus/"
cd "$work"
# -seed and -runs make a run reproducible (CI); -max_total_time bounds it;
# -timeout: one input may not take more than 10 s; -rss_limit_mb bounds memory.
"$work/fuzz_$name" -seed="${FUZZ_SEED:-1}" -runs="${FUZZ_RUNS:-200000}" -max_total_time="$seconds" \
  -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 "$work/corpus"
