#!/usr/bin/env bash
# Measures the solver choices the simulator-core issue asks to compare, side by side in
# one run: the initial pressure guess (warm start against the thesis' p0) and the
# boundary-consistent diagonal against Eq. 26 as printed, for each boundary method.
# Usage: scripts/solver-options.sh [STEPS] [SCENE...]   (defaults: 2000 steps, the 20k
# dam break and the column). Writes renders/bench/solver-options-*.csv.
set -euo pipefail
cd "$(dirname "$0")/.."
steps=${1:-2000}
shift || true
scenes=("$@")
[ ${#scenes[@]} -gt 0 ] || scenes=(scenes/dam_break.json scenes/column.json)
mkdir -p renders/bench
for method in extrapolation mirroring zero; do
  for init in warm thesis; do
    for diag in true false; do
      tag="$method-$init-diag_$diag"
      echo "== boundary_pressure=$method pressure_init=$init boundary_diagonal=$diag"
      build/sluice bench "${scenes[@]}" --steps "$steps" --repeat 1 \
        --set "solver.boundary_pressure=$method" --set "solver.pressure_init=$init" \
        --set "solver.boundary_diagonal=$diag" --csv "renders/bench/solver-options-$tag.csv" | sed -n '2,$p' | grep -v '^wrote'
    done
  done
done
