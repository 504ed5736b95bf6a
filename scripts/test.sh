#!/usr/bin/env bash
# Installs dependencies, builds, and runs the whole test suite through CTest.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
./scripts/build.sh
# One test process at a time: each already uses every core through OpenMP, and two
# OpenMP processes sharing the cores busy-wait at each other's barriers (6 s -> 40-200 s).
ctest --preset release
