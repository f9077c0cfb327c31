#!/usr/bin/env bash
# Runs a libFuzzer target (built by CMake with the debug preset, see
# tests/fuzz/CMakeLists.txt) for a bounded time on a temporary corpus (new
# inputs stay there): the hand-written seeds of tests/fuzz/corpus_<dir> and,
# for the parsers, the shipped inputs (experiments/*.toml, experiments/envs/
# *.toml), read at run time so that no copy of them goes stale.
#   run_fuzz.sh FUZZER NAME SECONDS   exit 0 clean, 1 a finding
# NAME (sweep_spec, environment, result_files) picks the seed inputs.
# FUZZ_SEED (default 1) and FUZZ_RUNS (default 200000) set the search; give
# FUZZ_RUNS=-1 to run until SECONDS.
set -euo pipefail
fuzzer=$1 name=$2 seconds=$3
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
if [[ ! -x $fuzzer ]]; then
  echo "run_fuzz: no fuzzer at '$fuzzer' (build it: cmake --preset debug && cmake --build --preset debug)" >&2
  exit 1
fi
fuzzer=$(cd "$(dirname "$fuzzer")" && pwd)/$(basename "$fuzzer")
work=$(mktemp -d /tmp/chaosweep-fuzz.XXXXXX)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/corpus"
shopt -s nullglob
case $name in
  sweep_spec) seeds=("$here"/corpus_spec/* "$root"/experiments/*.toml) ;;
  environment) seeds=("$here"/corpus_env/* "$root"/experiments/envs/*.toml) ;;
  result_files) seeds=("$here"/corpus_result_files/*) ;;
  *)
    echo "run_fuzz: unknown fuzzer name '$name' (sweep_spec, environment, result_files)" >&2
    exit 1
    ;;
esac
if ((${#seeds[@]} == 0)); then
  echo "run_fuzz: no seed inputs for $name" >&2
  exit 1
fi
cp "${seeds[@]}" "$work/corpus/"
cd "$work"
# -seed and -runs make a run reproducible (CI); -max_total_time bounds it;
# -timeout: one input may not take more than 10 s; -rss_limit_mb bounds memory.
"$fuzzer" -seed="${FUZZ_SEED:-1}" -runs="${FUZZ_RUNS:-200000}" -max_total_time="$seconds" \
  -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 "$work/corpus"
