#!/usr/bin/env bash
# Checks every C++ file of squeal (include/, source/, tribology/, tests/)
# against .clang-format (deal.II's style); exits non-zero and lists the files
# that differ. With --fix, formats them in place. Needs clang-format 14
# (Debian 12's clang-format package; scripts/setup.sh installs it).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
format=$(command -v clang-format-14 || command -v clang-format || true)
if [ -z "$format" ]; then
  echo "check_format: clang-format not found (Debian: apt-get install clang-format)" >&2
  exit 1
fi
# tracked files and new ones git does not ignore
mapfile -t files < <(git ls-files --cached --others --exclude-standard 'include/*.h' 'source/*.cc' 'source/*.h' \
                                  'tribology/*.cc' 'tribology/*.h' \
                                  'tests/*.cc' 'tests/*.h' 'benchmarks/*.cc')
if [ "${1:-}" = "--fix" ]; then
  "$format" -i "${files[@]}"
  exit 0
fi
bad=()
for f in "${files[@]}"; do
  if ! "$format" "$f" | cmp -s - "$f"; then
    bad+=("$f")
  fi
done
if [ ${#bad[@]} -gt 0 ]; then
  echo "check_format: ${#bad[@]} file(s) differ from .clang-format; run scripts/check_format.sh --fix:"
  printf '  %s\n' "${bad[@]}"
  exit 1
fi
echo "check_format: ${#files[@]} C++ files follow .clang-format"
