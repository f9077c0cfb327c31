#!/usr/bin/env bash
# The C++ sources follow .clang-format (Debian's clang-format-14): lists every
# file that differs and exits 1; format them with
#   git ls-files '*.cpp' '*.hpp' | xargs clang-format-14 -i
set -euo pipefail
cd "$(dirname "$0")/.."
fmt=$(command -v clang-format-14 || command -v clang-format || true)
[[ -n $fmt ]] || { echo "check_format: clang-format not found (apt-get install clang-format)" >&2; exit 1; }
bad=0
while IFS= read -r f; do
  if ! "$fmt" --dry-run -Werror "$f" >/dev/null 2>&1; then echo "not formatted: $f"; bad=1; fi
done < <(git ls-files '*.cpp' '*.hpp')
exit $bad
