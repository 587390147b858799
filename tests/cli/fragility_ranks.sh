#!/usr/bin/env bash
# A fragility study gives the same bits on 1, 2 and 3 MPI ranks and without mpirun (issue 14; "results stay
# bit-identical for any rank count"): the bisection IDA of yielding pairs (hunt + bisection per record, model and
# gap, each rank bisecting its own units) and the multiple-stripe analysis with scale_elastic, both through the
# fits, the bootstrap and the hazard integration on rank 0 -- every dataset and attribute of /ida, /intensity,
# /fragility, /hazard and the fields. A small version of studies/fragility-pair(-ida).toml: 6 synthetic records x
# 30 models. Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1; src=$(cd "$2" && pwd)
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
. "$src/tests/lib/needs_real_records.sh"
py=${POUNDING_PYTHON:-/usr/bin/python3}
"$py" -c 'import h5py, numpy' 2>/dev/null || skip_or_fail "needs $py with h5py and numpy (Debian: python3-h5py)"
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for method in ida msa; do
  sed -e "s|^output = .*|output = \"$tmp/$method.h5\"|" \
      -e 's|^curve = "example-hazard.csv"|curve = "'"$src"'/studies/example-hazard.csv"|' \
      -e 's|^synthetic_only = true|synthetic_only = true\nlimit = 6|' \
      -e 's|^samples_per_pair = 200 |samples_per_pair = 30 |' \
      -e 's|^bootstrap = 2000|bootstrap = 300|' \
      -e "s|^method = \"ida\" .*|method = \"$method\"|" \
      -e "$([ "$method" = msa ] && echo '/^tolerance = /d' || echo 's|^tolerance = .*|tolerance = 0.01|')" \
      "$src/studies/fragility-pair-ida.toml" > "$tmp/$method.toml"
  grep -q '^limit = 6' "$tmp/$method.toml" && grep -q "^method = \"$method\"" "$tmp/$method.toml"
  "$bin" run "$tmp/$method.toml" --out "$tmp/${method}0.h5" --quiet > /dev/null
  mpirun -np 1 "$bin" run "$tmp/$method.toml" --out "$tmp/${method}1.h5" --quiet > /dev/null
  timeout 300 mpirun -np 2 "$bin" run "$tmp/$method.toml" --out "$tmp/${method}2.h5" --quiet > /dev/null
  timeout 300 mpirun -np 3 --oversubscribe "$bin" run "$tmp/$method.toml" --out "$tmp/${method}3.h5" --quiet > /dev/null
  for n in 1 2 3; do "$py" "$src/tests/cli/compare_results.py" "$tmp/${method}0.h5" "$tmp/${method}$n.h5"; done
  "$py" - "$tmp/${method}0.h5" "$method" <<'PY'
import sys, h5py, numpy as np
f, method = h5py.File(sys.argv[1], "r"), sys.argv[2]
groups = {"ida": ["ida", "intensity", "fragility", "hazard"], "msa": ["intensity", "fragility", "hazard"]}[method]
for g in groups:
    assert g in f, (method, "missing group", g)
theta = f["fragility/theta"][()]
assert np.isfinite(theta).sum() >= 3, ("too few fitted gaps to make the comparison mean something", theta)
if method == "ida":
    assert f["ida/analyses"][()].sum() > 0, "no bisection analyses"
print(f"fragility_ranks {method}: 0, 1, 2, 3 ranks bit-identical; theta {np.round(theta, 4).tolist()}")
PY
done
