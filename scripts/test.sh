#!/usr/bin/env bash
# Installs dependencies, builds the program and its tests, and runs the whole test suite
# through CTest. Prints each stage's time.
set -euo pipefail
cd "$(dirname "$0")/.."
t0=$(date +%s)
took() { echo "test.sh: $1: $(($(date +%s) - t0)) s"; t0=$(date +%s); }
./scripts/install-deps.sh
took "dependencies"
./scripts/build.sh --tests
took "plain build"
# One test process at a time: each already uses every core through OpenMP, and two
# OpenMP processes sharing the cores busy-wait at each other's barriers (6 s -> 40-200 s).
ctest --preset release
took "plain tests"
