#!/usr/bin/env bash
# Installs the Debian packages fremond needs that are missing on this machine (idempotent).
set -euo pipefail
packages=(
  build-essential cmake pkg-config ccache
  libeigen3-dev libnlopt-dev libnlopt-cxx-dev libboost-dev
  nlohmann-json3-dev libcli11-dev libfmt-dev
  libgtest-dev libgmock-dev libbenchmark-dev libsiconos-numerics-dev libsiconos-kernel-dev
  pybind11-dev python3-dev python3-pybind11 python3-numpy python3-scipy python3-matplotlib python3-pil
  python3-nbclient python3-nbformat python3-ipykernel python3-pytest
  python3-mpmath         # tests/python/test_cli_against_mpmath.py: the 40-digit references
  clang libclang-rt-dev  # scripts/fuzz.sh: libFuzzer and clang's sanitizer runtimes
  clang-format           # scripts/check-format.sh (the ctest test "format")
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "installing: ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi
