#!/usr/bin/env bash
# Formats the C++ sources with clang-format and the repository's .clang-format (Google's
# style at 120 columns), or with --check only reports the files that differ (exit 1).
# Uses Debian 12's clang-format 14 (installed with apt-get when missing and run as root):
# another version formats some constructs differently.
#
#   scripts/format.sh           rewrite the files in place
#   scripts/format.sh --check   list the files that would change; exit 1 if any
set -euo pipefail
cd "$(dirname "$0")/.."
tool=clang-format-14
if ! command -v "$tool" >/dev/null 2>&1; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "format: $tool is missing; as root: apt-get install clang-format-14" >&2
    exit 1
  fi
  apt-get update -q
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends clang-format-14
fi
mapfile -t files < <(git ls-files 'src/*.cpp' 'src/*.h' 'tests/*.cpp' 'tests/*.h' 'fuzz/*.cpp')
if [ "${1:-}" = "--check" ]; then
  bad=0
  for f in "${files[@]}"; do
    if ! "$tool" "$f" | cmp -s - "$f"; then
      echo "format: $f differs from clang-format (scripts/format.sh rewrites it)"
      bad=1
    fi
  done
  [ "$bad" -eq 0 ] && echo "format: ${#files[@]} files follow .clang-format"
  exit "$bad"
fi
"$tool" -i "${files[@]}"
