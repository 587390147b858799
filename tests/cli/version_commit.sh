#!/bin/bash
# The commit a binary names (`pounding --version`, the results' git_commit, the checkpoint's build) is the one it was
# built from: read at build time (cmake/git_commit.cmake), not at configure time, so an incremental build after new
# commits names the new HEAD. Compares `pounding --version` with `git rev-parse --short=12 HEAD` of the source tree.
# Skipped (with the reason) outside a git tree of its own (a tarball) or without git; there the binary says "unknown".
# A failure here after a commit without a rebuild is right: the binary then really is from an older commit.
# usage: version_commit.sh <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd -P)
got=$("$bin" --version)
if ! command -v git > /dev/null; then
  echo "SKIP: git is not installed, the source tree's commit cannot be read (the binary says: $got)"; exit 77
fi
top=$(git -C "$src" rev-parse --show-toplevel 2> /dev/null || true)
if [ -z "$top" ] || [ "$(cd "$top" && pwd -P)" != "$src" ]; then
  echo "SKIP: $src is not a git tree of its own (a tarball?): nothing to compare (the binary says: $got)"; exit 77
fi
want=$(git -C "$src" rev-parse --short=12 HEAD)
if [[ "$got" =~ \(([0-9a-f]{12})\)$ ]] && [ "${BASH_REMATCH[1]}" = "$want" ]; then
  echo "ok: pounding --version names HEAD: $got"
else
  echo "FAIL: pounding --version says '$got', the source tree's HEAD is $want (a build after the last commit names it)"
  exit 1
fi
