#!/usr/bin/env bash
# The unit tests under ThreadSanitizer: CMakePresets.json's tsan preset (build-tsan/).
#
#   scripts/tsan.sh [CTEST ARGS...]     e.g. scripts/tsan.sh -R GoldenState
#
# Builds with Debian's clang and LLVM's OpenMP runtime (libomp), installed with apt-get
# when missing and run as root: GCC's libgomp is not instrumented, so TSan cannot see its
# barriers and reports every parallel loop as a race. libomp loads its TSan tool (Archer,
# libarcher.so) by itself and tells TSan about its synchronisation. Runs the label unit
# without the minutes-long physics runs (the same set as CI's sanitizer run) and without
# the floating-point trap check, whose traps read back as off under TSan on every thread.
# Not part of CI: building and running it takes about 17 minutes on 2 cores
# (docs/testing.md). Exit status: 0 when every test passed and TSan reported nothing.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang++ >/dev/null 2>&1 || [ ! -e /usr/lib/llvm-14/lib/libarcher.so ]; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "tsan: clang++ or libomp-14-dev (Archer) is missing; as root: apt-get install clang libomp-14-dev" >&2
    exit 1
  fi
  apt-get update -q
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends clang libomp-14-dev
fi
cmake --preset tsan
cmake --build --preset tsan -j"$(nproc)" --target sluice_unit_tests
ctest --preset tsan -j"$(nproc)" \
  -E 'HardCase|^Validation\.DamBreak|^Validation\..*TankAt|^Validation\.ThinPlate|^Experiments\.|^Reliability\.MemoryEstimate|FloatingPointTraps' \
  "$@"
