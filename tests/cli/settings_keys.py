#!/usr/bin/python3
"""Every key a study file gives reaches its results file's /settings (issue 46, docs/runner-design.md section 6).

Usage: settings_keys.py STUDY.toml RESULTS.h5 [STUDY.toml RESULTS.h5 ...]; exit 1 listing each key that is lost.

A leaf key `k` of table `[a.b]` is found when one of these holds, in this order:
  1. /settings/<a.b> has the attribute k (the top level: /settings itself);
  2. ALIASES names where it is stored under another name (a building's resolved text, a list of one);
  3. TEXTS names an attribute whose text states it: the key's value (a number in any of its printed forms, or its
     string) must appear in that text.
Arrays of tables ([[bridge.frame]]) and keys that are only the study's own plumbing (NOT_SETTINGS, each with its
reason) are not asked. A key of a distribution's inline table ({lognormal = {median, cov}}) is found through its
parent key's resolved text (rule 2). The check fails when the rules hold nothing for a key: it was parsed but not
stored, so the report (which reads only the results file) cannot say it.
"""
import re
import sys
import tomllib

import h5py

# (section pattern, key) -> (section, attribute) candidates; "{b}" is the building's table name
ALIASES = {
    ("structures", "model"): [("structures.building{all}", "model")],
    ("structures", "storey_height"): [("structures.building{all}", "storey_height")],
    ("structures", "storeys"): [("structures.building{all}", "storeys")],
    ("structures", "kh"): [("structures", "kh")],
    ("structures.building*", "yield_coefficient"): [("{sec}", "yield")],
    ("structures.building*", "period"): [("{sec}", "period")],
    ("intensity", "period"): [("intensity", "periods")],
    ("records.motions", "supports"): [("records.motions", "positions")],
    ("records.motions", "loss"): [("records.motions", "beta")],  # the coherency loss resolved to Sobczyk's beta
    ("records.motions", "spectrum"): [("records.motions", "targets")],
}
# (section, key) -> attributes whose text must state the key's value
TEXTS = {
    ("records.motions", "loss"): ["records.motions/generator"],
    ("records.motions", "soil"): ["records.motions/generator"],
    ("records.motions", "spectrum"): ["records.motions/generator"],
    ("records.motions", "r"): ["records.motions/generator"],
    ("records.motions", "z"): ["records.motions/generator"],
    ("records.motions", "spacing"): ["records.motions/generator"],
}
# keys that are not settings of the analysis, with the reason
NOT_SETTINGS = {
    ("", "output"): "where the results file goes: the file itself",
    ("analysis", "threads"): "how the work runs, not what it computes (study.hpp: the bits do not depend on it)",
}


def numbers(v):
    """The printed forms of a number: 0.5, 0.50, 5e-01, 50 (%)."""
    out = {repr(v), str(v), f"{v:g}", f"{v:.4g}", f"{v:.3g}"}
    if isinstance(v, float) and v.is_integer():
        out.add(str(int(v)))
    return out


def leaves(table, section=""):
    """(section, key, value) of every leaf of a study's TOML; inline tables are leaves of their parent key."""
    for k, v in table.items():
        if isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            continue  # an array of tables ([[bridge.frame]]): its kind's own description
        if isinstance(v, dict) and _is_section(v, k):
            yield from leaves(v, f"{section}.{k}" if section else k)
        else:
            yield section, k, v


def _is_section(v, k):
    # a distribution ({lognormal = {...}}, {uniform = [...]}) or an inline value table stays a leaf of its key
    return not (len(v) == 1 and next(iter(v)) in ("lognormal", "normal", "uniform", "discrete", "value"))


def find(settings, section, key, value):
    def attr(sec, name):
        g = settings if sec == "" else settings.get(sec)
        return None if g is None or name not in g.attrs else g.attrs[name]

    if (section, key) in NOT_SETTINGS:
        return True
    if attr(section, key) is not None:
        return True
    for (pat, k), places in ALIASES.items():
        if k != key or not re.fullmatch(pat.replace(".", r"\.").replace("*", r"\d+"), section):
            continue
        for sec, name in places:
            if "{all}" in sec:  # every building's table holds it
                secs = [s for s in settings.keys() if re.fullmatch(r"structures\.building\d+", s)]
                if secs and all(attr(s, name) is not None for s in secs):
                    return True
            elif attr(sec.replace("{sec}", section), name) is not None:
                return True
    for place in TEXTS.get((section, key), []):
        sec, name = place.rsplit("/", 1)
        text = attr(sec, name)
        if text is None:
            continue
        text = str(text).lower()
        wanted = numbers(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else {str(value).lower()}
        if any(w.lower() in text for w in wanted):
            return True
    return False


def inline_text(settings, section, key, value):
    """An inline table ({bearing = "lead-rubber", k1 = ...}) stored as its key's resolved text: every value stated."""
    if "." not in section:
        return False
    parent, name = section.rsplit(".", 1)
    g = settings.get(parent)
    if g is None or name not in g.attrs or not isinstance(g.attrs[name], str):
        return False
    text = g.attrs[name].lower()
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return any(w.lower() in text for w in numbers(value))
    return str(value).lower() in text


def intensity_periods(settings, section, key, value):
    """[intensity.periods] min, max, count: the grid stored as /settings/intensity periods."""
    if section != "intensity.periods" or "intensity" not in settings or "periods" not in settings["intensity"].attrs:
        return False
    p = settings["intensity"].attrs["periods"]
    return {"min": abs(p[0] - value) <= 1e-12 * abs(value), "max": abs(p[-1] - value) <= 1e-12 * abs(value),
            "count": len(p) == value}.get(key, False)


def abutment_text(settings, section, key, value):
    """[bridge.abutment.left/right] (and .bearing): stated in /settings/bridge description's "Abutment <side>: ..."."""
    m = re.fullmatch(r"bridge\.abutment\.(left|right)(\.bearing)?", section)
    if not m or "bridge" not in settings or "description" not in settings["bridge"].attrs:
        return False
    text = str(settings["bridge"].attrs["description"])
    at = text.find(f"Abutment {m.group(1)}: ")
    if at < 0:
        return False
    part = text[at:].split(". ", 1)[0].lower()
    if m.group(2):
        part = part[part.find("bearing"):] if "bearing" in part else ""
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return any(w.lower() in part for w in numbers(value))
    return str(value).lower() in part


def main(argv):
    if len(argv) < 2 or len(argv) % 2:
        print(__doc__)
        return 2
    lost = []
    for toml_path, h5_path in zip(argv[0::2], argv[1::2]):
        with open(toml_path, "rb") as fh:
            study = tomllib.load(fh)
        with h5py.File(h5_path, "r") as f:
            for section, key, value in leaves(study):
                S = f["settings"]
                if not (find(S, section, key, value) or inline_text(S, section, key, value)
                        or intensity_periods(S, section, key, value) or abutment_text(S, section, key, value)):
                    lost.append(f"{toml_path}: [{section}] {key} = {value!r} is not in {h5_path}'s /settings")
    for line in lost:
        print(line)
    print(f"settings_keys: {len(argv) // 2} studies, {len(lost)} keys lost")
    return 1 if lost else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
