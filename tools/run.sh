#!/usr/bin/env bash
# Set up (missing Debian packages, build) and run the main job: the quick study on 2 MPI ranks
# (synthetic stand-ins of the paper's 25 records), then print its report.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/tools/setup.sh"
cd "$here"
if [ "$(id -u)" -eq 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
mpirun -np 2 ./build/pounding run studies/quick.toml --out quick.h5 "$@"
