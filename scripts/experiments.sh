#!/usr/bin/env bash
# Regenerates docs/experiments/: every experiment of the thesis' chapter 5 (CSV files,
# figures, a summary.md each and the index README.md) and the snapshot montages of
# Figures 2 and 8. Needs a built sluice (scripts/build.sh) and an idle machine: the
# timing experiments measure wall time. About 30 minutes on 2 cores.
#   scripts/experiments.sh [OUTPUT_DIR]        (default docs/experiments)
#   scripts/experiments.sh --quick [OUTPUT_DIR] (small versions, about a minute)
set -euo pipefail
cd "$(dirname "$0")/.."
quick=()
if [[ "${1:-}" == "--quick" ]]; then quick=(--quick); shift; fi
out=${1:-docs/experiments}
mkdir -p "$out"
build/sluice experiment all "${quick[@]}" -o "$out"
echo "experiments: open $out/README.md"
