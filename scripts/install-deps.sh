#!/usr/bin/env bash
# Installs the Debian 12 packages sluice builds and runs with. Run as root.
# Does nothing (no apt-get at all) when every package is already installed.
set -euo pipefail
packages=(
  build-essential cmake pkg-config
  libeigen3-dev nlohmann-json3-dev libcli11-dev libgtest-dev
  # the export tests' XML parser
  libexpat1-dev
  # renderer: glad loader generator, stb image I/O and TrueType, fast deflate, headless EGL (Mesa), video
  python3-glad libstb-dev libdeflate-dev libegl-dev libegl-mesa0 libgl1-mesa-dri ffmpeg
  # the labels' font, embedded at build time (pinned: another version changes the goldens)
  fonts-dejavu-core
  # figures (validation, benchmarks)
  gnuplot-nox
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages: ${missing[*]}; run this script as root (sudo $0)" >&2
  exit 1
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
apt-get update -q
apt-get install -y -q --no-install-recommends "${missing[@]}"
