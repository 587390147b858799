#!/usr/bin/env bash
# Set up (missing Debian packages, build) and run the main job on its embedded default.
set -euo pipefail
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$here/tools/setup.sh"
cd "$here"
exec ./build/pounding simulate "$@"
