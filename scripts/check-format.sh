#!/usr/bin/env bash
# Every C++ source and header of the project is as the checked-in .clang-format makes it. Fix with
#   bash scripts/check-format.sh --fix
set -euo pipefail
cd "$(dirname "$0")/.."
mapfile -t files < <(find include src potentials tests bench fuzz -name '*.cpp' -o -name '*.hpp' |
  sort)
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  exit 0
fi
if ! clang-format --dry-run -Werror "${files[@]}"; then
  echo "not formatted (bash scripts/check-format.sh --fix formats them)" >&2
  exit 1
fi
echo "${#files[@]} files formatted as .clang-format says"
