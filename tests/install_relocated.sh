#!/usr/bin/env bash
# The binary needs no source tree: `cmake --install` into a temporary prefix,
# copy the installed binary into an empty directory and, with the source and
# build trees hidden (a tmpfs mounted over them in a private mount namespace),
# no CHAOSWEEP_* variable set and the working directory elsewhere, run the
# demo, a spec naming every built-in environment, a trajectory replay, a
# `chaosweep slurm` job script (and one task of it), and an environment from
# $CHAOSWEEP_ENV_PATH (which still wins over a built-in of the same name).
#   usage: install_relocated.sh BUILD_DIR SOURCE_DIR
# Exit 77 (skip) after the checks only where the trees cannot be hidden
# (no mount namespace), since the checks then prove less.
set -euo pipefail
build=$(cd "$1" && pwd) src=$(cd "$2" && pwd)
work=$(mktemp -d /tmp/chaosweep-install.XXXXXX)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$work/prefix" >"$work/install.log" || { cat "$work/install.log"; fail "cmake --install"; }
for f in bin/chaosweep share/chaosweep/experiments/demo.toml share/chaosweep/experiments/envs/five_squares.toml \
         share/chaosweep/cluster/sweep.sbatch.in share/doc/chaosweep/README.md share/doc/chaosweep/docs/spec.md; do
  [[ -e $work/prefix/$f ]] || fail "cmake --install did not install $f"
done

# The run directory: the binary, the demo spec, a spec of every built-in
# environment, and an environment directory for $CHAOSWEEP_ENV_PATH.
run=$work/run
mkdir -p "$run/myenvs"
cp "$work/prefix/bin/chaosweep" "$run/"
cp "$work/prefix/share/chaosweep/experiments/demo.toml" "$run/"
envs=()
for f in "$src"/experiments/envs/*.toml; do envs+=("\"$(basename "$f" .toml)\""); done
cat >"$run/envs.toml" <<EOF
[fixed]
size = 20
sr = 2
max_time = 300
[axes]
env = [$(IFS=,; echo "${envs[*]}")]
EOF
printf 'obstacles = [{ x = 0.4, y = 0.4, w = 0.2, h = 0.2 }]\n' >"$run/myenvs/box.toml"
# Shadows the built-in one_square (a 0.4 L square) with a smaller one.
printf 'obstacles = [{ x = 0.45, y = 0.45, w = 0.1, h = 0.1 }]\n' >"$run/myenvs/one_square.toml"

cat >"$run/checks.sh" <<'EOF'
set -euo pipefail
cd "$1"
[[ -z $(ls "$2" 2>/dev/null) ]] || { echo "the source tree is still visible" >&2; exit 1; }
./chaosweep sweep demo.toml -o demo.h5 -q
./chaosweep table best demo.h5 --top 3 >best.md
./chaosweep figure fig6a demo.h5 -o fig6a.png >/dev/null
./chaosweep sweep envs.toml -o envs.h5 -q
./chaosweep table summary envs.h5 --by env >envs.md
./chaosweep figure trajectory envs.h5 --run 3 -o trajectory.png >/dev/null
./chaosweep slurm demo.toml --tasks 4 -o slurm >/dev/null
grep -q "^exec '$1/chaosweep' sweep '$1/demo.toml'" slurm/sweep.sbatch
SLURM_ARRAY_TASK_ID=0 SLURM_CPUS_PER_TASK=1 bash slurm/sweep.sbatch >/dev/null 2>&1
./chaosweep status slurm >status.txt || true
grep -q "^finished 1: 0$" status.txt
CHAOSWEEP_ENV_PATH=$1/myenvs ./chaosweep run --size 20 --sr 2 --max-time 10 --env box --json >box.json
./chaosweep run --size 20 --sr 2 --max-time 10 --env one_square --json >builtin.json
CHAOSWEEP_ENV_PATH=$1/myenvs ./chaosweep run --size 20 --sr 2 --max-time 10 --env one_square --json >shadowed.json
EOF

# env -i: no CHAOSWEEP_SOURCE_DIR, CHAOSWEEP_ENV_PATH or anything else from here.
clean_env=(env -i PATH=/usr/bin:/bin HOME="$work" LC_ALL=C)
hidden=1
hide="mount -t tmpfs none '$src'"
case $build in "$src"/*) ;; *) hide+=" && mount -t tmpfs none '$build'" ;; esac
if ! unshare -rm sh -c "$hide" 2>/dev/null && ! unshare -m sh -c "$hide" 2>/dev/null; then
  hidden=0
fi
cd "$work"
if ((hidden)); then
  ns=(unshare -m); unshare -rm true 2>/dev/null && ns=(unshare -rm)
  "${clean_env[@]}" "${ns[@]}" sh -c "$hide && exec bash '$run/checks.sh' '$run' '$src'" || fail "the relocated binary (output above)"
else
  "${clean_env[@]}" bash "$run/checks.sh" "$run" /nonexistent || fail "the relocated binary (output above)"
fi

# What the runs printed, checked out here.
grep -q '^| 1 |' "$run/best.md" || fail "table best of the demo printed no rank 1"
[[ -s $run/fig6a.png && -s $run/trajectory.png ]] || fail "no figure"
for e in "${envs[@]}"; do
  grep -q "^| ${e//\"/} |" "$run/envs.md" || fail "environment ${e//\"/} is not in the summary of envs.toml"
done
free() { sed -n 's/.*"free_cells": *\([0-9]*\).*/\1/p' "$1"; }
[[ -n $(free "$run/box.json") ]] || fail "no free_cells for the \$CHAOSWEEP_ENV_PATH environment"
[[ $(free "$run/builtin.json") != "$(free "$run/shadowed.json")" ]] ||
  fail "\$CHAOSWEEP_ENV_PATH's one_square does not win over the built-in one"
if ((!hidden)); then
  echo "SKIP: the checks passed, but no mount namespace here to hide $src"
  exit 77
fi
echo "the installed binary, copied alone, ran the demo, ${#envs[@]} built-in environments, a trajectory, slurm and \$CHAOSWEEP_ENV_PATH without the source tree"
