#!/usr/bin/env bash
# Fuzzes the scene parser (fuzz/scene_fuzzer.cpp) with libFuzzer for a bounded time and
# prints the executions and the crashes found.
#
#   scripts/fuzz.sh [SECONDS]      (default 120)
#
# Builds with Debian's clang (installed with apt-get when missing and run as root) and
# -fsanitize=fuzzer,address,undefined into build-fuzz/, from the library sources the
# parser needs (no CMake: the fuzzer must not pick up the project's GCC build). The
# corpus (build-fuzz/corpus) is seeded from fuzz/corpus/ (kept in the repository),
# scenes/*.json and scenes/hard/*.json and kept between runs; the random seed is fixed
# (FUZZ_SEED, default 1) so that CI runs start alike. To refresh the kept corpus after a
# long run: build-fuzz/scene_fuzzer -merge=1 fuzz/corpus build-fuzz/corpus. A crashing, leaking, too slow or too hungry input is saved as
# build-fuzz/artifacts/{crash,leak,timeout,oom}-<hash>, and libFuzzer stops at the
# first one; an input over 10 s but inside -timeout, as slow-unit-<hash> (reported only).
# Exit status: 0 when nothing but slow units was found, 1 otherwise.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-120}
out=build-fuzz

have_libfuzzer() {
  command -v clang++ >/dev/null 2>&1 &&
    find "$(clang++ -print-resource-dir)" -name 'libclang_rt.fuzzer*.a' 2>/dev/null | grep -q .
}
if ! have_libfuzzer; then
  if [ "$(id -u)" -ne 0 ]; then
    echo "fuzz: clang++ with libFuzzer is missing; as root: apt-get install clang" >&2
    exit 1
  fi
  apt-get update
  DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends clang libclang-rt-dev
  have_libfuzzer || { echo "fuzz: clang is installed but libFuzzer (libclang_rt.fuzzer) is not found" >&2; exit 1; }
fi

sources=(fuzz/scene_fuzzer.cpp src/scene/build.cpp src/scene/json_reader.cpp src/scene/overrides.cpp
         src/scene/read_settings.cpp src/scene/read_shapes.cpp src/scene/read_motion.cpp src/scene/sample_file.cpp
         src/core/shapes.cpp src/solver/motion.cpp src/solver/settings.cpp src/solver/setup.cpp)
mkdir -p "$out/corpus" "$out/artifacts"
# Rebuild only when a source or header changed since the last build.
if [ ! -x "$out/scene_fuzzer" ] || [ -n "$(find src fuzz -newer "$out/scene_fuzzer" -type f | head -1)" ]; then
  echo "fuzz: building $out/scene_fuzzer with $(clang++ --version | head -1)"
  # -O1 -g: fast enough to fuzz, readable reports. UBSan findings abort like ASan ones.
  clang++ -std=c++20 -O1 -g -fno-omit-frame-pointer \
    -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
    -Isrc $(pkg-config --cflags eigen3) -DSLUICE_VERSION='"fuzz"' \
    "${sources[@]}" -o "$out/scene_fuzzer"
fi

# Seeds: the kept corpus and every shipped scene; build-fuzz/corpus keeps what earlier runs found.
cp fuzz/corpus/* scenes/*.json scenes/hard/*.json "$out/corpus/"

log="$out/fuzz.log"
echo "fuzz: running for $seconds s (log: $log)"
set +e
# -timeout: a unit over 30 s is a hang (the largest scenes the limits allow take seconds
# under ASan); -rss_limit_mb: more than 4 GiB for one scene is a finding.
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
  "$out/scene_fuzzer" "$out/corpus" -dict=fuzz/scene.dict -max_total_time="$seconds" -seed="${FUZZ_SEED:-1}" \
  -timeout=30 -rss_limit_mb=4096 -max_len=8192 -print_final_stats=1 \
  -artifact_prefix="$out/artifacts/" >"$log" 2>&1
status=$?
set -e

executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
[ -n "$executions" ] || executions=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#')
rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
# Crashes, leaks, timeouts (-timeout) and out-of-memory inputs fail; a slow unit (an input
# over libFuzzer's 10 s report threshold but inside -timeout) is reported, not failed: it is
# a scene with many particles, whose sampling costs about 7 us per particle under ASan and
# coverage (linear: docs/reliability.md), and the machine's load decides whether it crosses
# 10 s. A parse that is not linear still reaches the 30 s timeout and fails.
findings=$(grep '^artifact_prefix=.*Test unit written to' "$log" | grep -vc '/slow-unit-' || true)
slow=$(grep -o 'Test unit written to .*/slow-unit-[0-9a-f]*' "$log" | sed 's/^Test unit written to //' | sort -u | tr '\n' ' ' || true)
[ -z "$slow" ] || echo "fuzz: slow inputs (over 10 s, under the 30 s timeout), kept for a look: $slow"
corpus=$(find "$out/corpus" -type f | wc -l)
echo "fuzz: $executions executions in $seconds s (${rate:-?} per second), corpus $corpus inputs"
if [ "$status" -eq 0 ] && [ "$findings" -eq 0 ]; then
  echo "fuzz: crashes found: 0"
  exit 0
fi
echo "fuzz: crashes found: ${findings} (libFuzzer exit status $status); the report:"
grep -E '^(==[0-9]+==ERROR|SUMMARY|.*runtime error|artifact_prefix|.*Test unit written|==[0-9]+== ERROR)' "$log" | head -20
grep -m1 -A12 -E '^    #0 ' "$log" || true
exit 1
