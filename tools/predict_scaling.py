#!/usr/bin/python3
"""Predict the speed-up of `pounding run` at many ranks from measured quantities (issue 27 item 4).

Inputs, all measured (README "Speed" says where each comes from):
  - the master's service time per unit, s: `POUNDING_MASTER_SERVICE=1 mpirun -np 2 pounding run STUDY` prints
    "the master's time per worker unit X us" (since issue 27.4 a worker stores and checkpoints its own units in its
    slice and sends the master the unit's id: the master receives 8 bytes and hands out the next unit). Before
    slices it printed "... = X us per unit": receiving, storing, checkpointing and handing out one unit's bytes;
  - the assembly after the units, a per unit: rank 0 reading the workers' slices into the result arrays (the same
    line's "assembly from the slices ... us per unit"); serial, after the units phase, for the units the workers
    computed ((p - 1) / p of them);
  - the compute time of one unit, t, the serial part (every rank's start: MPI start + inputs + structures, which
    do not shrink with more ranks) and the part after the units (analysis + report + results write, rank 0 only):
    from the /timing group of a one-rank results file (--results R1.h5), or given; the results write and mpirun's
    MPI start are not in such a file (--write-s, --mpi-start-s from the printed timing lines).

Model (units phase): U units of compute time t each; rank 0 also spends s per unit serving them, and computes
units itself when it is not serving. With p ranks the phase takes
    T_units(p) = max( (U t + U s) / p,          the work and the service spread over every rank,
                      U s,                      the master alone serving every unit (saturation),
                      ceil(U / p) t )           the last wave: no rank can finish fewer whole units;
end to end T(p) = serial + T_units(p) + U a (p - 1) / p + post. The master saturates at p* = (t + s) / s ranks. Efficiencies are
T(1) / (p T(p)) (end to end) and U t / (p T_units(p)) (units phase only).
Not modelled: MPI start-up growth with p, network latency beyond what s holds (measured on one node), stragglers.
"""
import argparse
import math
import sys


def from_results(path):
    import h5py  # only when a results file is given
    with h5py.File(path, "r") as f:
        if "timing" not in f:
            sys.exit(f" ERROR: {path} has no /timing group (written before issue 27), rerun the study to measure")
        g = f["timing"]
        names = [n.decode() if isinstance(n, bytes) else str(n) for n in g["phase"][()]]
        r0 = dict(zip(names, g["rank0_s"][()]))
        mx = dict(zip(names, g["max_s"][()]))
        if "units" not in g.attrs:
            sys.exit(f" ERROR: {path}'s /timing has no 'units' attribute (written before it was added), "
                     "give --units, --unit-ms, --serial-s and --post-s")
        units = int(g.attrs["units"])
        resumed = int(g.attrs.get("units_resumed", 0))
        ranks = int(f.attrs.get("ranks", 1))
    if ranks != 1:
        sys.exit(f" ERROR: {path} was written by {ranks} ranks; give a one-rank run's file (its compute is every unit's)")
    if resumed:
        sys.exit(f" ERROR: {path} is from a --resume run ({resumed} units came from the checkpoint); use a fresh run")
    serial = mx["mpi_start"] + mx["inputs"] + mx["structures"]
    post = r0["analysis"] + r0["report"] + r0.get("results_write", 0.0)
    return units, r0["compute"] / units, serial, post


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--service-us", type=float, required=True, help="master service time per unit (us)")
    ap.add_argument("--results", help="a one-rank results file of the study (its /timing gives the rest)")
    ap.add_argument("--units", type=int, help="work units of the study")
    ap.add_argument("--unit-ms", type=float, help="compute time of one unit on one core (ms)")
    ap.add_argument("--serial-s", type=float, help="every rank's start (MPI start + inputs + structures), s")
    ap.add_argument("--post-s", type=float, help="analysis + report + results write, s (default: from --results)")
    ap.add_argument("--write-s", type=float, default=0.0,
                    help="the results write, s: a file cannot hold the time of its own write, so with --results give "
                         "the 'results write' of the run's printed timing line")
    ap.add_argument("--mpi-start-s", type=float, default=0.0,
                    help="MPI start-up under mpirun, s (a one-rank run without mpirun has none)")
    ap.add_argument("--assemble-us", type=float, default=0.0,
                    help="rank 0's reading of the workers' checkpoint slices after the units, us per unit (0: none)")
    ap.add_argument("--ranks", default="1,2,16,64,1000", help="comma-separated rank counts")
    ap.add_argument("--label", default="", help="a name for the workload in the table's title")
    a = ap.parse_args()

    units, t, serial, post = (None, None, None, 0.0)
    if a.results:
        units, t, serial, post = from_results(a.results)
    post = (a.post_s if a.post_s is not None else post) + a.write_s
    serial = serial + a.mpi_start_s if serial is not None else None
    units = a.units if a.units is not None else units
    t = a.unit_ms / 1e3 if a.unit_ms is not None else t
    serial = a.serial_s if a.serial_s is not None else serial
    missing = [k for k, v in (("--units", units), ("--unit-ms", t), ("--serial-s", serial)) if v is None]
    if missing:
        sys.exit(f" ERROR: {', '.join(missing)} missing, give them or --results R1.h5 (a one-rank run's file)")
    s = a.service_us / 1e6
    for name, v in (("--service-us", s), ("--unit-ms", t), ("--units", units)):
        if not (v > 0 and math.isfinite(v)):
            sys.exit(f" ERROR: {name} must be a positive number, got {v}")
    if serial < 0 or post < 0 or a.write_s < 0 or a.mpi_start_s < 0 or not a.assemble_us >= 0:
        sys.exit(" ERROR: --serial-s, --post-s, --write-s, --mpi-start-s and --assemble-us must be >= 0")
    asm = a.assemble_us / 1e6
    try:
        ranks = [int(x) for x in a.ranks.split(",")]
        if any(p < 1 for p in ranks):
            raise ValueError
    except ValueError:
        sys.exit(f" ERROR: --ranks must be positive integers separated by commas, got '{a.ranks}'")

    def t_units(p):
        return max((units * t + units * s) / p, units * s, math.ceil(units / p) * t)

    def t_after(p):  # the assembly of the workers' units, then the analysis, report and write
        return units * asm * (p - 1) / p + post

    t1 = serial + t_units(1) + t_after(1)
    print(f"## Predicted scaling{': ' + a.label if a.label else ''}")
    print(f"units {units}, unit {t * 1e3:.3f} ms, master service {s * 1e6:.2f} us per unit, serial {serial:.3f} s, "
          f"after the units {post:.3f} s + assembly {a.assemble_us:.2f} us per worker unit; the master saturates at p* = (t + s) / s = {(t + s) / s:.0f} ranks\n")
    print("| ranks | units phase s | end to end s | speed-up | efficiency (end to end) | efficiency (units phase) | limited by |")
    print("|---|---|---|---|---|---|---|")
    for p in ranks:
        tu = t_units(p)
        total = serial + tu + t_after(p)
        terms = {"work": (units * t + units * s) / p, "master": units * s, "last wave": math.ceil(units / p) * t}
        limit = max(terms, key=terms.get)
        if serial + t_after(p) > tu:
            limit += ", serial part"
        print(f"| {p} | {tu:.4f} | {total:.4f} | {t1 / total:.2f} | {100 * t1 / (p * total):.1f} % | "
              f"{100 * units * t / (p * tu):.1f} % | {limit} |")


if __name__ == "__main__":
    main()
