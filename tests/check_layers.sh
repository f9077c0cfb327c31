#!/usr/bin/env bash
# The layers' one-way dependencies (docs/architecture.md): every
# #include "..." in kernels/, engine/, analysis/ and apps/ must name a folder
# below the including file's own (or the file's own folder), and no kernel
# file may include TBB, HDF5, CLI11 or toml++. Prints each violation as
# "file:line: includes X (layer) above or beside its own (layer)"; exit 1 if any.
# Usage: check_layers.sh [SOURCE_DIR]
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"

# Sets rank and unit for a repository path: a folder may include its own
# unit and any unit of lower rank. Equal ranks are siblings that may not
# include each other (the planners).
layer_of() {
  case $1 in
    kernels/math/*) rank=0 unit=kernels/math ;;
    kernels/systems/*) rank=1 unit=kernels/systems ;;
    kernels/core/*) rank=2 unit=kernels/core ;;
    kernels/planners/*/*) rank=3 unit=${1#kernels/planners/} unit=kernels/planners/${unit%%/*} ;;
    kernels/planners/*) rank=4 unit=kernels/planners ;;
    kernels/lanes/*) rank=5 unit=kernels/lanes ;;
    engine/rows/*) rank=6 unit=engine/rows ;;
    engine/spec/*) rank=7 unit=engine/spec ;;
    engine/run/*) rank=8 unit=engine/run ;;
    engine/tune/*) rank=9 unit=engine/tune ;;
    engine/store/*) rank=10 unit=engine/store ;;
    engine/bench/*) rank=11 unit=engine/bench ;;
    analysis/*) rank=12 unit=analysis ;;  # analysis/papers and analysis, both ways for now
    apps/*) rank=13 unit=apps ;;
    *) rank=-1 unit=none ;;
  esac
}

bad=0
while IFS= read -r hit; do
  file=${hit%%:*}
  rest=${hit#*:}
  line=${rest%%:*}
  text=${rest#*:}
  layer_of "$file"
  from_rank=$rank from_unit=$unit
  if [[ $text =~ \<([^\>]+)\> ]]; then
    inc=${BASH_REMATCH[1]}
    if [[ $from_unit == kernels/* && $inc =~ ^(tbb/|oneapi/|hdf5|H5|CLI/|toml\+\+/) ]]; then
      echo "$file:$line: includes <$inc>: kernels know no TBB, HDF5, CLI11 or toml++"
      bad=1
    fi
    continue
  fi
  [[ $text =~ \"([^\"]+)\" ]] || continue
  inc=${BASH_REMATCH[1]}
  layer_of "$inc"
  if ((rank < 0)); then
    echo "$file:$line: includes \"$inc\", which is in no layer (write includes from the repository root)"
    bad=1
  elif [[ $unit != "$from_unit" ]] && ((rank >= from_rank)); then
    echo "$file:$line: includes \"$inc\" ($unit) from $from_unit, which is not below it"
    bad=1
  fi
done < <(grep -rnE '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]' kernels engine analysis apps \
           --include='*.hpp' --include='*.cpp' --include='*.h' --include='*.cc' | sort)

if ((bad)); then
  echo "check_layers: the includes above point up or sideways (order: kernels/math < systems < core" \
       "< planners/<each> < planners < lanes < engine/rows < engine/spec < engine/run < engine/tune < engine/store" \
       "< engine/bench < analysis < apps)"
  exit 1
fi
echo "check_layers: every include points down"
