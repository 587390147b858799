#!/usr/bin/env bash
# Installs the Debian packages pounding needs (only the missing ones) and builds it in build/.
# Idempotent: with everything present it only runs an incremental build.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$here"

packages=(g++ make cmake pkg-config git
          libeigen3-dev libopenmpi-dev openmpi-bin libhdf5-dev zlib1g-dev libboost-random-dev libgtest-dev
          libcli11-dev libtomlplusplus-dev libfmt-dev libbenchmark-dev
          python3 python3-numpy python3-scipy python3-matplotlib python3-h5py python3-pandas python3-pytest
          python3-dev pybind11-dev
          chromium)  # chromium: the HTML report's browser test (cli.report_html_browser)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "pounding setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Build options for a fresh build/ (README, "Build options"): POUNDING_KERNEL_ARCH=native|x86-64-v3|x86-64-v4|OFF,
# POUNDING_WITH_MPI=ON|OFF; POUNDING_NATIVE=OFF is the older spelling of POUNDING_KERNEL_ARCH=OFF.
arch=${POUNDING_KERNEL_ARCH:-native}
[ "${POUNDING_NATIVE:-ON}" = OFF ] && arch=OFF
mpi=${POUNDING_WITH_MPI:-ON}
if [ ! -f build/CMakeCache.txt ]; then
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DPOUNDING_KERNEL_ARCH="$arch" -DPOUNDING_WITH_MPI="$mpi" >/dev/null
fi
if ! cmake --build build -j "$(nproc)" > build/build.log 2>&1; then
  grep -E -v '^\[ *[0-9]+%\]' build/build.log >&2
  echo "pounding setup: build failed (full log: build/build.log)" >&2
  exit 1
fi
