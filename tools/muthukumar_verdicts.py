#!/usr/bin/env python3
"""Verdicts on Muthukumar & DesRoches (2006)'s findings, per configuration of a Muthukumar CSV.

  tools/muthukumar_verdicts.py docs/muthukumar_sensitivity.csv   (records_set,T2,kelvin_scale + rows)
  tools/muthukumar_verdicts.py docs/muthukumar.csv               (one configuration: all records, T2 1, x1)
  tools/muthukumar_verdicts.py --compact CSV                      one table, a row per configuration

Prints the Markdown tables of docs/validation.md ("Sensitivity"). The findings and the rules applied:
  F1  displacement amplification of stereomechanical, Kelvin, Hertzdamp (Lankarani-Nikravesh) within 12 % of
      each other (max/min - 1) at every level, T1/T2 and e            -> holds if the largest spread <= 12 %
  F2  amplification rises as T1/T2 falls (0.3 > 0.5 > 0.7), displacement, every level, model and e
  F3  displacement and acceleration amplification rise with PGA (low < moderate < high) at T1/T2 = 0.3, 0.5
  F4  Hertzdamp's acceleration amplification below Kelvin's at low and moderate PGA; Kelvin the least at high
      PGA: count of (T1/T2, e) groups with Hertzdamp < Kelvin per level; the paper's pattern is 6, 6, 0 of 6
  F5  e = 1 -> 0.6 reduces the displacement by 28, 16, 10 % and the acceleration by 27, 32, 18 %
      (stereomechanical, Kelvin, Hertzdamp; high PGA, T1/T2 = 0.3); Hertzdamp varies least with e
  C6  (abstract, not reported before) "energy loss is more significant at higher PGA": the displacement
      reduction from e = 1 to 0.6 at T1/T2 = 0.3 rises low -> moderate -> high, per model
  C7  (conclusions) "at low PGA the effects of energy loss are not significant for the Hertz model, so Hertz
      with e = 1 is recommended": Hertzdamp's displacement reduction at low PGA, largest over T1/T2, against
      the 10 % the paper itself reports at high PGA (which it calls significant)
Standard library only.
"""
import csv
import sys
from collections import OrderedDict

LEVELS = ["low", "moderate", "high"]
RATIOS = ["0.3", "0.5", "0.7"]
SHORT = {"low": "low", "moderate": "mod", "high": "high"}
TRIO = ["stereomechanical", "kelvin", "hertzdamp"]
ALL_MODELS = TRIO + ["hertzdamp-calibrated"]


def configs(path):
    out = OrderedDict()
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            key = (r.get("records_set", "all"), r.get("T2", "1"), r.get("kelvin_scale", "1"))
            r["period_ratio"] = str(float(r["period_ratio"]))
            r["e"] = str(float(r["e"]))
            out.setdefault(key, {})[(r["level"], r["period_ratio"], r["model"], r["e"])] = r
    return out


def val(t, lvl, rt, model, e, col):
    r = t.get((lvl, rt, model, e))
    return float(r[col]) if r else None


def red(t, lvl, rt, model, col):  # reduction (%) from e = 1 to 0.6
    a1, a6 = val(t, lvl, rt, model, "1.0", col), val(t, lvl, rt, model, "0.6", col)
    if model == "hertzdamp-calibrated":
        a1 = val(t, lvl, rt, "hertzdamp", "1.0", col)
    return None if a1 is None or a6 is None else 100.0 * (1.0 - a6 / a1)


def f1(t):
    worst = (0.0, "")
    for lvl in LEVELS:
        for rt in RATIOS:
            for e in ("1.0", "0.6"):
                v = [val(t, lvl, rt, m, e, "disp_amp") for m in TRIO]
                if None in v:
                    continue
                s = 100.0 * (max(v) / min(v) - 1.0)
                if s > worst[0]:
                    worst = (s, f"{lvl}, {rt}, e={e[:3]}")
    return ("holds" if worst[0] <= 12.0 else "FAILS") + f": max spread {worst[0]:.1f} % ({worst[1]})"


def f2(t):
    ok = n = 0
    for lvl in LEVELS:
        for m in ALL_MODELS:
            for e in ("1.0", "0.6"):
                v = [val(t, lvl, rt, m, e, "disp_amp") for rt in RATIOS]
                if None in v:
                    continue
                n += 1
                ok += v[0] > v[1] > v[2]
    return ("holds" if ok == n else "FAILS") + f": {ok}/{n} groups"


def f3(t):
    parts, full, total = [], True, 0
    for col, name in (("disp_amp", "disp"), ("acc_amp", "acc")):
        for a, b in (("low", "moderate"), ("moderate", "high")):
            c = n = 0
            for rt in ("0.3", "0.5"):
                for m in TRIO:
                    for e in ("1.0", "0.6"):
                        x, y = val(t, a, rt, m, e, col), val(t, b, rt, m, e, col)
                        if x is None or y is None:
                            continue
                        n += 1
                        c += y > x
            if n:
                parts.append(f"{name} {SHORT[a]}<{SHORT[b]} {c}/{n}")
                full = full and c == n
                total += n
    if not total:
        return "n/a"
    return ("holds: " if full else "partly: ") + ", ".join(parts)


def f4(t):
    counts, ok = [], True
    for lvl in LEVELS:
        c = n = 0
        for rt in RATIOS:
            for e in ("1.0", "0.6"):
                h, k = val(t, lvl, rt, "hertzdamp", e, "acc_amp"), val(t, lvl, rt, "kelvin", e, "acc_amp")
                if h is None or k is None:
                    continue
                n += 1
                c += h < k
        counts.append(f"{c}/{n}" if n else "n/a")
        if n:
            ok = ok and (c == 0 if lvl == "high" else c == n)
    return ("holds" if ok else "FAILS") + ": H<K " + ", ".join(counts)


def f5(t):
    d = [red(t, "high", "0.3", m, "disp_amp") for m in TRIO]
    a = [red(t, "high", "0.3", m, "acc_amp") for m in TRIO]
    if None in d or None in a:
        return "n/a"
    least = all(
        red(t, lvl, "0.3", "hertzdamp", "disp_amp") <= min(red(t, lvl, "0.3", m, "disp_amp") for m in TRIO[:2])
        for lvl in LEVELS if red(t, lvl, "0.3", "hertzdamp", "disp_amp") is not None)
    order = d[0] >= d[1] >= d[2]
    return (f"disp -{d[0]:.0f}/-{d[1]:.0f}/-{d[2]:.0f} % (28/16/10), acc -{a[0]:.0f}/-{a[1]:.0f}/-{a[2]:.0f} % "
            f"(27/32/18); disp order {'holds' if order else 'FAILS'}; H least {'holds' if least else 'FAILS'}")


def c6(t):
    out = []
    for m in TRIO:
        v = [red(t, lvl, "0.3", m, "disp_amp") for lvl in LEVELS]
        v = [x for x in v if x is not None]
        if len(v) < 2:
            return "n/a"
        mark = "rises" if all(a < b for a, b in zip(v, v[1:])) else "no"
        out.append(f"{m[:6]} {'/'.join(f'{x:.1f}' for x in v)} {mark}")
    return "; ".join(out)


def c7(t):
    v = [(red(t, "low", rt, "hertzdamp", "disp_amp"), rt) for rt in RATIOS]
    v = [x for x in v if x[0] is not None]
    if not v:
        return "n/a"
    worst = max(v)
    return ("supported" if worst[0] < 10.0 else "NOT supported") + f": Hertz e-effect at low PGA {worst[0]:.1f} % (T1/T2 {worst[1]})"


def compact(cfgs):
    print("| records | T2 (s) | Kelvin x | F1 max spread | F2 | F3 low<mod, mod<high (disp) | F4 H<K low, mod, high "
          "| F5 disp reduction s/K/H (28/16/10) | C6 rises with PGA | C7 Hertz e-effect, low PGA |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for (rs, t2, ks), t in cfgs.items():
        v1 = f1(t).split(": max spread ")
        cells = [f"{v1[1].split(' (')[0]} {'ok' if v1[0] == 'holds' else '**fails**'}"]
        v2 = f2(t)
        cells.append(v2.split(": ")[1].replace(" groups", "") + (" ok" if v2.startswith("holds") else " **fails**"))
        v3 = f3(t)
        cells.append(", ".join(p.split(" ", 2)[2] for p in v3.split(": ", 1)[1].split(", ") if p.startswith("disp"))
                     if v3 != "n/a" else "n/a")
        v4 = f4(t)
        cells.append(v4.split("H<K ")[1] + (" ok" if v4.startswith("holds") else " **fails**"))
        v5 = f5(t)
        cells.append(v5.split(" % (28")[0].replace("disp ", "") + " %" + ("" if "disp order holds" in v5 else " (order fails)"))
        v6 = c6(t)
        cells.append("n/a" if v6 == "n/a" else ", ".join(
            f"{m}: {'yes' if part.endswith('rises') else 'no'}"
            for m, part in zip(("S", "K", "H"), v6.split("; "))))
        v7 = c7(t)
        cells.append("n/a" if v7 == "n/a" else v7.split("low PGA ")[1].split(" (")[0] + (" ok" if v7.startswith("supported") else " **fails**"))
        print(f"| {rs} | {t2} | {ks} | " + " | ".join(cells) + " |")


def main():
    args = [a for a in sys.argv[1:] if a != "--compact"]
    if len(args) != 1:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
    cfgs = configs(args[0])
    if "--compact" in sys.argv:
        compact(cfgs)
        return
    cols = [("F1 spread <= 12 %", f1), ("F2 rises as T1/T2 falls", f2), ("F3 rises with PGA (0.3, 0.5)", f3),
            ("F4 Hertzdamp < Kelvin acc (low, mod, high)", f4), ("F5 e-reduction, high PGA, 0.3", f5),
            ("C6 e-effect rises with PGA (disp reduction %, T1/T2 0.3, by level present)", c6),
            ("C7 Hertz e = 1 adequate at low PGA", c7)]
    for name, fn in cols:
        print(f"\n**{name}**\n")
        print("| records | T2 (s) | Kelvin x | verdict |")
        print("|---|---|---|---|")
        for (rs, t2, ks), t in cfgs.items():
            print(f"| {rs} | {t2} | {ks} | {fn(t)} |")


if __name__ == "__main__":
    main()
