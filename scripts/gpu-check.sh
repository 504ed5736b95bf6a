#!/usr/bin/env bash
# The NVIDIA EGL check (docs/rendering.md): renders the first frames of the default scene on
# the EGL device platform, checks that a hardware device drew them (an NVIDIA one unless
# --any-vendor), and compares them with Mesa llvmpipe's frames by `sluice compare --preset
# tests`. Exit 0 when every frame matches, 1 when a check fails, 2 on a usage error.
#
#   scripts/gpu-check.sh                       build, render both ways, compare
#   scripts/gpu-check.sh --sluice BIN --reference DIR
#                                              a machine without the build's packages or
#                                              Mesa: a prebuilt program and llvmpipe's frames
#                                              rendered elsewhere by `--make-reference DIR`
#   scripts/gpu-check.sh --make-reference DIR  llvmpipe's frames only, into DIR
#
# Options: -o DIR (work directory, default out/gpu-check), --frames N (default 4), --any-vendor
# (any hardware device), --allow-software (a dry run of the whole check where there is no GPU).
# Bounded: each render runs under `timeout` (5 min); the whole check takes seconds.
set -euo pipefail
cd "$(dirname "$0")/.."

sluice="" reference="" make_reference="" work="out/gpu-check" frames=4 vendor="NVIDIA" software=0
usage() { sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
while [ $# -gt 0 ]; do
  case "$1" in
    --sluice) sluice="${2:?--sluice needs a path}"; shift 2 ;;
    --reference) reference="${2:?--reference needs a directory}"; shift 2 ;;
    --make-reference) make_reference="${2:?--make-reference needs a directory}"; shift 2 ;;
    -o) work="${2:?-o needs a directory}"; shift 2 ;;
    --frames) frames="${2:?--frames needs a number}"; shift 2 ;;
    --any-vendor) vendor=""; shift ;;
    --allow-software) vendor="" software=1; shift ;;
    -h|--help) usage ;;
    *) echo "gpu-check: unknown argument '$1'" >&2; usage ;;
  esac
done
case "$frames" in ''|*[!0-9]*|0) echo "gpu-check: --frames '$frames' must be a whole number >= 1" >&2; exit 2 ;; esac

if [ -z "$sluice" ]; then
  cmake --preset release >/dev/null
  cmake --build --preset release -j"$(nproc)" --target sluice
  sluice=build/sluice
fi
[ -x "$sluice" ] || { echo "gpu-check: --sluice '$sluice' is not an executable" >&2; exit 2; }

scene=scenes/dam_break.json
last=$((frames - 1))
# render PLATFORM DIR: the first frames as PNGs; prints the renderer line sluice reports.
render() {
  timeout 300 "$sluice" render "$scene" --frames "0:$last" --no-video --egl "$1" -o "$2" --overwrite \
    2>"$2.log" >/dev/null || { cat "$2.log" >&2; echo "gpu-check: render on '$1' failed" >&2; exit 1; }
  sed -n 's/^sluice: rendering [0-9]*x[0-9]* with //p' "$2.log"
}

mkdir -p "$work"
if [ -n "$make_reference" ]; then
  mkdir -p "$(dirname "$make_reference")"
  echo "gpu-check: reference (llvmpipe): $(render surfaceless "$make_reference")"
  exit 0
fi
if [ -z "$reference" ]; then
  reference="$work/llvmpipe"
  echo "gpu-check: reference: $(render surfaceless "$reference")"
fi
[ -d "$reference/frames" ] || { echo "gpu-check: --reference '$reference' has no frames/ folder" >&2; exit 2; }

device_line=$(render device "$work/device")
echo "gpu-check: device:    $device_line"
case "$software:$device_line" in
  0:*llvmpipe*|0:*"(software)"*) echo "gpu-check: FAILED: the device platform fell back to Mesa's software renderer" >&2; exit 1 ;;
esac
if [ -n "$vendor" ] && ! grep -qi "$vendor" <<<"$device_line"; then
  echo "gpu-check: FAILED: the device platform did not choose an $vendor device" >&2
  exit 1
fi

# What `--egl auto` (surfaceless, then device) picks on this machine: reported, not checked.
echo "gpu-check: auto:      $(render auto "$work/auto")"

failed=0
for ref in "$reference"/frames/*.png; do
  name=$(basename "$ref")
  got="$work/device/frames/$name"
  [ -f "$got" ] || { echo "gpu-check: $name: missing from the device's frames"; failed=1; continue; }
  if out=$("$sluice" compare --preset tests --diff "$work/diff_$name" "$ref" "$got" 2>&1); then
    echo "gpu-check: $name: $(tr "\n" " " <<<"$out")"
  else
    echo "gpu-check: $name: DIFFERS: $(tr "\n" " " <<<"$out")"
    failed=1
  fi
done
[ "$failed" -eq 0 ] && echo "gpu-check: passed" || echo "gpu-check: FAILED" >&2
exit "$failed"
