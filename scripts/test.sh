#!/usr/bin/env bash
# Builds everything and runs every test (unit, property, stress smoke, command line, packaging,
# Python, notebooks), in the Release tree build/.
#
#   bash scripts/test.sh
#
# The longer checks (every test under the sanitizers, 100,000 stress problems per law, fuzzing
# for minutes) are scripts/check-long.sh's.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/lib/build-env.sh

stage install bash scripts/install-deps.sh
source scripts/lib/build-env.sh  # ccache may have just been installed
stage configure cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${FREMOND_CMAKE_LAUNCHER[@]}" \
  >/dev/null
stage build cmake --build build -j"$(nproc)"
stage ctest ctest --test-dir build --output-on-failure -j"$(nproc)"
