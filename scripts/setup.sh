#!/usr/bin/env bash
# Installs what esif needs from Debian 12 packages (only what is missing) and
# builds it in ./build. Safe to run again: it only does what is left to do.
#
#   bash scripts/setup.sh [TARGET...]   # default: everything (tests included)
#
# scripts/demo.sh builds only the host and the plugins (targets esif and
# esif_all_plugins); scripts/test.sh builds the rest. ccache is used when it
# is installed.
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config
  libmrpt-dev mrpt-apps mrpt-common   # MRPT 2.5: libraries, kf-slam app, demo datasets
  libeigen3-dev libsuitesparse-dev libceres-dev libgtest-dev libboost-dev zlib1g-dev libopencv-dev
  nlohmann-json3-dev                  # stats.json
  gnuplot-nox                         # draws every figure (PNG and SVG)
  parallel                            # GNU parallel, for the engine test of --emit-jobs lists (tests/engines)
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "esif setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "${launcher[@]}" >/dev/null
if [ $# -gt 0 ]; then
  cmake --build build --target "$@"
else
  cmake --build build
fi
