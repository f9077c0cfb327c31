#!/usr/bin/env bash
# CPU time of a cheap sweep (specs/cheap.toml: 1e5 short runs, so the
# engine's per-run costs weigh as much as the kernel) with two binaries,
# taking turns PAIRS times: spec_ab.sh on that spec. An A/A run (one binary
# twice) reads 0.99-1.02 here: smaller differences are noise.
#   usage: tests/benchmarks/cheap_ab.sh OLD_BIN NEW_BIN [PAIRS=15] [THREADS=1]
set -euo pipefail
(($# >= 2)) || { echo "usage: $0 OLD_BIN NEW_BIN [PAIRS=15] [THREADS=1]" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)
exec "$here/spec_ab.sh" "$here/specs/cheap.toml" "$1" "$2" "${3:-15}" "${4:-1}"
