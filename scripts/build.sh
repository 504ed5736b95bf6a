#!/usr/bin/env bash
# Configures and builds sluice (Release) into build/. Extra arguments go to cmake.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --preset release "$@"
cmake --build --preset release -j"$(nproc)"
