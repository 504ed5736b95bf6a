#!/usr/bin/env bash
# Configures and builds sluice (Release) into build/: the program only, or with --tests
# the program and the three test binaries too (scripts/test.sh). Other arguments go to
# cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
targets=(--target sluice)
configure=()
for a in "$@"; do
  if [ "$a" = --tests ]; then targets=(); else configure+=("$a"); fi
done
cmake --preset release "${configure[@]}"
cmake --build --preset release -j"$(nproc)" "${targets[@]}"
