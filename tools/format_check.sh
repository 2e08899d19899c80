#!/usr/bin/env bash
# Checks that the C++ sources follow .clang-format: lists every file that
# clang-format would change and exits 1 if there is one (0 when all are clean,
# 2 when clang-format is missing). Arguments: files to check (default: every
# tracked *.cpp and *.h). Fix with: clang-format -i FILE...
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang-format >/dev/null; then
  echo "format_check: clang-format not found (Debian package clang-format)" >&2
  exit 2
fi
if [ $# -gt 0 ]; then files=("$@"); else mapfile -t files < <(git ls-files '*.cpp' '*.h'); fi
for f in "${files[@]}"; do
  [ -f "$f" ] || { echo "format_check: no such file '$f'" >&2; exit 2; }
done
# One clang-format process; each of its warnings starts with "FILE:LINE:COL: ".
mapfile -t unformatted < <(clang-format --dry-run "${files[@]}" 2>&1 | sed -n 's/^\(.*\):[0-9]*:[0-9]*: warning: .*/\1/p' | sort -u)
if [ ${#unformatted[@]} -gt 0 ]; then
  echo "format_check: ${#unformatted[@]} of ${#files[@]} files differ from .clang-format:" >&2
  printf '  %s\n' "${unformatted[@]}" >&2
  exit 1
fi
echo "format_check: ${#files[@]} files formatted"
