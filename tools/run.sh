#!/usr/bin/env bash
# The main job: set up (missing Debian packages, build the `pounding` program only), run the quick study on
# 2 MPI ranks (synthetic stand-ins of the paper's 25 records), print its report and write the HTML report
# beside the results. Extra arguments go to `pounding run` (e.g. --out other.h5, --force).
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/tools/setup.sh" pounding
cd "$here"
if [ "$(id -u)" -eq 0 ]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
out=""
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  case ${args[i]} in
    --out) out=${args[i + 1]:-} ;;
    --out=*) out=${args[i]#--out=} ;;
  esac
done
[ -n "$out" ] || { out=quick.h5; args=(--out "$out" "${args[@]}"); }
mpirun -np 2 ./build/pounding run studies/quick.toml "${args[@]}"
html=${out%.h5}.html
./build/pounding report "$out" --html "$html"
echo "Open $html in a browser (results: $out; every command: build/pounding --help)"
