#!/usr/bin/env bash
# Installs the Debian packages pounding needs (only the missing ones), configures build/ once and builds the
# targets given as arguments (none: every target, the tests' included).
#   tools/setup.sh pounding     the program only (what ./tools/run.sh needs)
#   tools/setup.sh              everything (./tools/test.sh)
# Idempotent: with everything present it only runs an incremental build of those targets. Ninja is used when it
# is installed (it is in the package list) and ccache when it is present. Build options for a fresh build/
# (docs/developing.md): POUNDING_KERNEL_ARCH=native|x86-64-v3|x86-64-v4|OFF, POUNDING_WITH_MPI=ON|OFF;
# POUNDING_NATIVE=OFF is the older spelling of POUNDING_KERNEL_ARCH=OFF.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$here"

packages=(g++ make cmake ninja-build pkg-config git
          libeigen3-dev libopenmpi-dev openmpi-bin libhdf5-dev zlib1g-dev libboost-random-dev libgtest-dev
          libcli11-dev libtomlplusplus-dev libfmt-dev libbenchmark-dev nlohmann-json3-dev
          python3 python3-numpy python3-scipy python3-matplotlib python3-h5py python3-pandas python3-pytest
          python3-dev pybind11-dev
          chromium)  # chromium: the HTML report's browser test (cli.report_html_browser)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "pounding setup: installing ${missing[*]}" >&2
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

arch=${POUNDING_KERNEL_ARCH:-native}
[ "${POUNDING_NATIVE:-ON}" = OFF ] && arch=OFF
mpi=${POUNDING_WITH_MPI:-ON}
if [ ! -f build/CMakeCache.txt ]; then
  generator=()
  command -v ninja >/dev/null && generator=(-G Ninja)
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
  log=$(mktemp)
  if ! cmake -S . -B build "${generator[@]}" "${launcher[@]}" -DCMAKE_BUILD_TYPE=Release \
         -DPOUNDING_KERNEL_ARCH="$arch" -DPOUNDING_WITH_MPI="$mpi" > "$log" 2>&1; then
    cat "$log" >&2
    rm -f "$log" build/CMakeCache.txt
    echo "pounding setup: configure failed (log above)" >&2
    exit 1
  fi
  mv "$log" build/configure.log
fi

targets=("$@")
what=${targets[*]:-everything}
start=$SECONDS
echo "pounding setup: building ${what} in build/ (log: build/build.log)" >&2
target_args=()
for t in "${targets[@]}"; do target_args+=(--target "$t"); done
if ! cmake --build build -j "$(nproc)" "${target_args[@]}" > build/build.log 2>&1; then
  grep -E -v '^\[ *[0-9]+(%|/[0-9]+)\]' build/build.log >&2
  echo "pounding setup: build failed (full log: build/build.log)" >&2
  exit 1
fi
echo "pounding setup: ${what} built in $((SECONDS - start)) s" >&2
