#!/usr/bin/env bash
# A pair whose answer is known independently (issue 13): two LINEAR SDOF buildings with fixed periods, heights,
# masses and (unequal) damping under six generated records. At gap g the probability of at least one impact is
# exactly the fraction of records whose peak of (u1 - u2) exceeds g; SciPy's lsim (first-order hold, exact
# for a piecewise-linear ground motion, as the Nigam-Jennings stepper) computes those peaks without any of our
# code. The study must give:
#   - every record's peak closing to 1e-9 relative,
#   - at gaps placed between the SciPy peaks, exactly the fraction of records above (Table 3's counts),
#   - at each target the separation = the (floor(t n) + 1)-th largest SciPy peak,
#   - an interval of zero width when all six records are copies of one, and a positive one when they differ;
#   - with [records] polarity = "both" (a pair study's default, issue 23): the reversed record's peak closing is
#     SciPy's peak of (u2 - u1) under the recorded one (linear: the response to -ag is exactly -u), every gap's
#     probability is the fraction over (record, sign) of those peaks above it, the separation the order
#     statistic of both, Table 2 lists each record ONCE with its two signs counted together, and the report and
#     /settings state the polarity.
# Args: <pounding binary> <source dir>
set -euo pipefail
bin=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cd "$tmp"
/usr/bin/python3 - "$bin" <<'PY'
import subprocess, sys, h5py, numpy as np
from scipy import signal

bin_ = sys.argv[1]
G = 9.80665
dt, n = 0.01, 2000
rng = np.random.default_rng(20261124)
t = np.arange(n) * dt
env = np.minimum(1, t / 2) * np.exp(-np.maximum(0, t - 8) / 4)
records = []
for k in range(6):  # band-limited noise with an envelope, PGA 0.15-0.40 g
    b, a = signal.butter(2, [0.3, 6.0], btype="band", fs=1 / dt)
    ag = signal.lfilter(b, a, rng.standard_normal(n)) * env
    ag *= (0.15 + 0.05 * k) / np.max(np.abs(ag))
    records.append(ag)

def write_at2(path, ag):
    with open(path, "w") as f:
        f.write("generated for pair_linear_exact.sh\nband-limited noise\nACCELERATION TIME SERIES IN UNITS OF G\n")
        f.write(f"NPTS= {len(ag)}, DT= {dt:.4f} SEC\n")
        for i in range(0, len(ag), 5):
            f.write("".join(f"{v:16.8e}" for v in ag[i:i + 5]) + "\n")

# the buildings: periods, damping, heights (code gap d = 0.005 (28 + 42) = 0.35 m)
T1, T2, z1, z2, h1, h2 = 0.9, 1.3, 0.05, 0.03, 28.0, 42.0
d = 0.005 * (h1 + h2)

def peak_closing(ag, sign=1):
    # read back as the engine does: the file's 8 significant digits; sign -1: the peak of u2 - u1
    u = []
    for T, z in ((T1, z1), (T2, z2)):
        w = 2 * np.pi / T
        sys_ = signal.StateSpace([[0, 1], [-w * w, -2 * z * w]], [[0], [-1]], [[1, 0]], [[0]])
        _, y, _ = signal.lsim(sys_, ag * G, t)
        u.append(y)
    return np.max(sign * (u[0] - u[1]))

def study(files, ratios, name, polarity="recorded"):  # polarity None: the key left out (a pair study: "both")
    text = f'''title = "linear pair with a known answer"
seed = 3
scene = "probability"
output = "{name}.h5"
[records]
files = {files!r}
{"" if polarity is None else f'polarity = "{polarity}"'}
[structures]
samples_per_pair = 2
hysteresis = "elastic"
[structures.building1]
period = {T1}
height = {h1}
mass = 2.0e6
zeta = {z1}
[structures.building2]
period = {T2}
height = {h2}
mass = 3.0e6
zeta = {z2}
[gaps]
ratios = {list(ratios)!r}
[analysis]
stepper = "nigam-jennings"
[report]
targets = [40, 20]
bootstrap = 400
'''.replace("'", '"')
    open(f"{name}.toml", "w").write(text)
    subprocess.run([bin_, "run", f"{name}.toml", "--quiet"], check=True, stdout=subprocess.DEVNULL)
    return subprocess.run([bin_, "report", f"{name}.h5", "--csv"], check=True, capture_output=True, text=True).stdout

def total_rows(csv):
    rows = {}
    for line in csv.splitlines()[1:]:
        c = line.split(",")
        if c[0] == "total":
            rows[float(c[2])] = (int(c[5]), int(c[6]))
    return rows

files = []
for k, ag in enumerate(records):
    write_at2(f"r{k}.AT2", ag)
    files.append(f"r{k}.AT2")
ag_read = [np.loadtxt(f, skiprows=4).ravel() for f in files]
ref = np.array([peak_closing(ag) for ag in ag_read])
s = np.sort(ref)
print("SciPy peak closings (m):", np.round(ref, 5))
assert s[0] > 0.02 and s[-1] < 0.5 * 6 * d, s
gaps = np.concatenate([[0.5 * s[0]], 0.5 * (s[1:] + s[:-1]), [1.5 * s[-1]]])  # between the peaks
ratios = np.round(gaps / d, 9)
csv = study(files, ratios, "pair")
f = h5py.File("pair.h5", "r")
pc = f["uncoupled/peak_closing"][()].reshape(len(files), -1)
assert np.all(f["uncoupled/status"][()] == 0)
err = np.max(np.abs(pc - ref[:, None]) / ref[:, None])
print(f"peak closing: largest relative difference to SciPy {err:.2e}")
assert err < 1e-9, err
rows = total_rows(csv)
for x, g in zip(ratios, gaps):
    want = int(np.sum(ref > x * d))
    hits, nn = rows[x]
    assert nn == 2 * len(files) and hits == 2 * want, (x, hits, nn, want)
print(f"{len(ratios)} gaps: the study's fraction equals the SciPy fraction of records exactly")
seps = [line.split(",") for line in csv.splitlines() if line.startswith("separation,")]
for c, t in zip(seps, (0.40, 0.20)):
    j = int(np.floor(t * 2 * len(files)))  # two identical models per record
    want = np.sort(np.repeat(ref, 2))[::-1][j]
    got, lo, hi = float(c[8]), float(c[9]), float(c[10])
    assert abs(got - want) < 1e-6, (t, got, want)
    assert hi - lo > 1e-3, ("records disagree: the interval must have width", lo, hi)
    print(f"target {t:.0%}: separation {got:.6f} m = SciPy {want:.6f} m, interval [{lo:.4f}, {hi:.4f}]")
# all records copies of one: the bootstrap interval collapses to the value
csv = study([files[2]] * 6, ratios, "copies")
for c in (line.split(",") for line in csv.splitlines() if line.startswith("separation,")):
    assert float(c[9]) == float(c[8]) == float(c[10]) and abs(float(c[8]) - ref[2]) < 1e-6, c
print("copies of one record: interval of zero width at the SciPy peak")

# polarity "both": each record also with its sign reversed, two analyses of the same record
t = np.arange(n) * dt  # (the loops above reused t)
neg = np.array([peak_closing(ag, -1) for ag in ag_read])
both = np.concatenate([ref, neg])
print("SciPy peaks of u2 - u1 (m):", np.round(neg, 5))
sb = np.sort(both)
gaps_b = np.concatenate([[0.5 * sb[0]], 0.5 * (sb[1:] + sb[:-1]), [1.5 * sb[-1]]])
ratios_b = np.round(gaps_b / d, 9)
csv = study(files, ratios_b, "both", None)  # a pair study's default
f = h5py.File("both.h5", "r")
assert f["settings/records"].attrs["polarity"] in (b"both", "both"), f["settings/records"].attrs["polarity"]
pol = f["records/polarity"][()]
assert list(pol) == [1, -1] * len(files), pol
ids = [v.decode() if isinstance(v, bytes) else v for v in f["records/id"][()]]
assert ids[0::2] == ids[1::2], ids
pc = f["uncoupled/peak_closing"][()].reshape(2 * len(files), -1)
err = max(np.max(np.abs(pc[0::2] - ref[:, None]) / ref[:, None]), np.max(np.abs(pc[1::2] - neg[:, None]) / neg[:, None]))
print(f"polarity both: recorded and reversed peak closing, largest relative difference to SciPy {err:.2e}")
assert err < 1e-9, err
rows = total_rows(csv)
for x in ratios_b:
    want = int(np.sum(both > x * d))
    hits, nn = rows[x]
    assert nn == 2 * 2 * len(files) and hits == 2 * want, (x, hits, nn, want)
per_record = [line.split(",") for line in csv.splitlines() if line.startswith("per_record,")]
assert len(per_record) == len(files) * len(ratios_b), len(per_record)  # one row per record, not per sign
for c in per_record:
    k = int(c[1][1:]); x = float(c[2])
    assert int(c[6]) == 4 and int(c[5]) == 2 * (int(ref[k] > x * d) + int(neg[k] > x * d)), c
seps = [line.split(",") for line in csv.splitlines() if line.startswith("separation,")]
for c, tt in zip(seps, (0.40, 0.20)):
    want = np.sort(np.repeat(both, 2))[::-1][int(np.floor(tt * 4 * len(files)))]
    assert abs(float(c[8]) - want) < 1e-6, (tt, c, want)
md = subprocess.run([bin_, "report", "both.h5"], check=True, capture_output=True, text=True).stdout
assert "record polarity: **both**" in md, md[:2000]
# the separation's bootstrap and its "records above" see 6 records of 2 signs x 2 models, not 12 rows
assert "with N = 6 independent records" in md, md[:4000]
sep_rows = [l for l in md.splitlines() if l.startswith("| 40% |") or l.startswith("| 20% |")]
assert len(sep_rows) == 2 and all(l.split("|")[4].strip().endswith("of 6") for l in sep_rows), sep_rows
print(f"polarity both: {len(ratios_b)} gaps and 2 targets equal the SciPy fractions over (record, sign); "
      "Table 2 one row per record")
PY
echo "1 passed, 0 failed"
