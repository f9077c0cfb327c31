#!/usr/bin/env bash
# The per-ISA kernel objects (lane_kernel_avx2/avx512, and the contraction
# planner's trig3_avx2) are compiled for newer
# CPUs than the rest. If one of them emitted an inline function that baseline
# code also uses (a weak symbol of, say, std::vector<double> or sincos<double>),
# the linker could keep that copy for the whole program and an older CPU would
# crash with SIGILL. Pass: every global code symbol they define (nm's T, W
# and i) is vector-typed or their own entry point. Data they define (weak
# objects V, D, B; read-only R) holds no instructions, whichever copy the
# linker keeps: GCC emits DW.ref.__gxx_personality_v0 where an object has
# unwind tables (e.g. at -O1 under ASan); clang under UBSan emits the
# typeinfo of the function types its -fsanitize=function checks, and the
# inline constexpr members its code refers to (e.g. Chirikov::heading_scale).
set -euo pipefail
status=0
checked=0
for obj in "$@"; do
  case "$obj" in *lane_kernel_avx* | *trig3_avx2*) ;; *) continue ;; esac
  checked=$((checked + 1))
  while read -r kind name; do
    case "$name" in
      *"__vector("*|"chaosweep::integrate_lanes_avx"*|"chaosweep::sincos4_avx2("*|"chaosweep::wrap_sincos4_avx2("*) ;;
      *) echo "FAIL: $obj defines $kind $name"; status=1 ;;
    esac
  done < <(nm -C --defined-only "$obj" | awk '$2 ~ /^[TWi]$/ { $1 = ""; sub(/^ /, ""); k = $1; $1 = ""; sub(/^ /, ""); print k, $0 }')
done
if [[ $checked -ne 3 ]]; then
  echo "FAIL: expected 3 per-ISA objects, found $checked"
  exit 1
fi
[[ $status -eq 0 ]] && echo "ok: per-ISA kernel objects define only vector-typed code symbols"
exit $status
