#!/usr/bin/env bash
# The main job: the paper's comparison on the bar, reproduced from a fresh clone in one command.
#
#   bash scripts/paper.sh [OUT_DIR]        (default out/paper, or $FREMOND_OUT)
#
# Installs the Debian packages (scripts/install-deps.sh), builds the command and the Python module
# (Release, into build/), then runs the bar under each of the paper's five laws (the paper's Fig. 1)
# and Stronge's, prints the table (impacts, energy before and after the first impacts,
# admissibility, the inequality that failed) and writes every figure of the paper into OUT_DIR:
# the motions as GIFs and strips of poses (Figs. 2, 4, 6, 10, 12), the energies (Figs. 3, 5, 7,
# 11, 13), the normal restitution for several p (Fig. 8) and the viscous dead zone (Fig. 9), with
# the data of Figs. 8 and 9 as CSV; Stronge's runs as stronge_coulomb_*.
set -euo pipefail
cd "$(dirname "$0")/.."
OUT=${1:-${FREMOND_OUT:-out/paper}}

bash scripts/install-deps.sh
source scripts/lib/build-env.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release "${FREMOND_CMAKE_LAUNCHER[@]}" >/dev/null
cmake --build build -j"$(nproc)" --target fremond_cli fremond_python >/dev/null
mkdir -p "$OUT"

# The data of Figs. 8 and 9, on the grids the figures use (the library's scaling for Fig. 8, the paper's
# r = 0.4, k_T = 0.75 for Fig. 9; each row names its scaling).
build/fremond curve normal --p 1.5,2,2.5,3,4 --points 201 --max-speed 5 \
  --out "$OUT/fig08_normal_restitution.csv"
build/fremond curve tangential --scaling paper --points 301 --max-speed 1.5 \
  --out "$OUT/fig09_tangential_dead_zone.csv"

# The runs, the table and the figures (the Python module, with Debian's interpreter).
PYTHONPATH="$PWD/build/python" MPLBACKEND=Agg /usr/bin/python3 scripts/paper_figures.py --out "$OUT"
