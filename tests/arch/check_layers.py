#!/usr/bin/env python3
"""ctest arch.layers: the module layers of docs/architecture.md cannot erode.

Reads every `#include "pounding/<module>/..."` in include/ and src/ and fails when
  - a module includes a module it may not (ALLOWED below, the table of docs/architecture.md),
  - a header sits directly in include/pounding/ instead of a module folder (except the transitional
    FLAT headers, each named with the module it belongs to),
  - the allowed graph itself has a cycle,
  - a third-party header leaks where it must not: <mpi.h> outside src/parallel/mpi_executor.cpp,
    <hdf5.h> outside src/io/hdf5.cpp; fmt, toml++, CLI11, iostream, cstdio or fstream in the kernel,
    contact and model layers (their headers and sources); toml++ outside the config module (src/config/,
    include/pounding/config/) except the files of TOML_OUTSIDE_CONFIG, a list that may only fall.
Each problem is printed as file:line and the rule it breaks; exit 1 when there is any.
"""
import argparse
import os
import re
import sys

# module -> modules it may include (itself always allowed). The command line (src/cli) may include anything.
ALLOWED = {
    "core": set(),
    "config": {"core"},
    "kernel": {"core"},
    "contact": {"kernel", "core"},
    "model": {"kernel", "core"},
    "physics": {"contact", "model", "kernel", "core"},
    "io": {"core"},
    "parallel": {"core"},
    "motion": {"kernel", "config", "core"},
    "sampling": {"physics", "model", "contact", "kernel", "config", "core"},
    "inventory": {"physics", "model", "contact", "kernel", "motion", "config", "core"},
    "results": {"io", "core"},
    "study": {"physics", "contact", "model", "kernel", "motion", "sampling", "parallel", "results", "config", "core"},
    "analysis": {"results", "motion", "kernel", "config", "core"},  # motion: design spectra (code_displacement)
    "report": {"analysis", "results", "study", "physics", "contact", "model", "kernel", "motion", "sampling",
               "io", "config", "core"},
    "accuracy": {"physics", "contact", "model", "kernel", "motion", "sampling", "analysis", "config", "core"},
    "workloads": {"physics", "contact", "model", "kernel", "motion", "core"},
    "cli": None,  # anything
    "python": None,  # anything
}
# Transitional exceptions (none today): headers directly in include/pounding/ with the module they belong to,
# sources directly in src/, and single (file, include) pairs allowed against the table. Each entry needs a
# reason in docs/architecture.md.
FLAT: dict = {}
FLAT_SOURCES: set = set()
TRANSITIONAL_INCLUDES: set = set()
# Layers that must stay free of I/O, parsing and third-party formatting.
PURE = {"kernel", "contact", "model"}
PURE_BANNED = re.compile(r'#\s*include\s*<(fmt/|toml\+\+|CLI/|iostream|cstdio|fstream)')
CONFINED = {"mpi.h": "src/parallel/mpi_executor.cpp", "hdf5.h": "src/io/hdf5.cpp"}
# toml++ is config's (docs/runner-design.md section 6: a TableReader over an opaque table). The files that still
# include it directly, until their parsers take a config::TableReader; an entry whose file no longer includes it is
# a problem too, so the list only falls.
TOML = re.compile(r'#\s*include\s*<toml\+\+/')
TOML_HOME = ("src/config/", "include/pounding/config/")
TOML_OUTSIDE_CONFIG = {
    "include/pounding/sampling/bridge.hpp", "include/pounding/sampling/building.hpp",
    "include/pounding/sampling/code_factors.hpp", "include/pounding/sampling/sampler.hpp",
    "include/pounding/study/intensity.hpp", "include/pounding/study/target_spectrum.hpp",
    "src/cli/commands/sample.cpp", "src/motion/suite.cpp", "src/study/study.cpp", "src/study/study_sections.cpp",
    "src/study/study_sections.hpp",
    "src/cli/commands/inventory_run.cpp",  # main's inventory run (after this list was made): reads [inventory] itself
}
INCLUDE = re.compile(r'#\s*include\s*"pounding/([^"]+)"')
SYSTEM = re.compile(r'#\s*include\s*<([^>]+)>')


def module_of(rel):
    """Module of a file path relative to the source dir, or None for files outside src/ and include/."""
    parts = rel.split("/")
    if parts[0] == "include" and len(parts) >= 3 and parts[1] == "pounding":
        return FLAT.get(parts[2]) if len(parts) == 3 else parts[2]
    if parts[0] == "src" and len(parts) >= 3:
        return parts[1]
    if parts[0] == "src":
        return "cli"  # a flat src/*.cpp would be a problem reported below
    return None


def included_module(target):
    parts = target.split("/")
    return FLAT.get(parts[0], "?" + parts[0]) if len(parts) == 1 else parts[0]


def find_cycle(graph):
    state = {}

    def visit(n, path):
        state[n] = 1
        for m in sorted(graph.get(n) or ()):
            if state.get(m) == 1:
                return path + [n, m]
            if m not in state:
                c = visit(m, path + [n])
                if c:
                    return c
        state[n] = 2
        return None

    for n in sorted(graph):
        if n not in state:
            c = visit(n, [])
            if c:
                return c
    return None


def check(source_dir, toml_outside=None):
    toml_outside = TOML_OUTSIDE_CONFIG if toml_outside is None else toml_outside
    problems = []
    toml_seen = set()
    cycle = find_cycle({k: v for k, v in ALLOWED.items() if v is not None})
    if cycle:
        problems.append("the allowed-dependency table has a cycle: " + " -> ".join(cycle))
    for top in ("include", "src"):
        for root, dirs, files in os.walk(os.path.join(source_dir, top)):
            dirs.sort()
            for f in sorted(files):
                if not f.endswith((".hpp", ".cpp", ".h")):
                    continue
                rel = os.path.relpath(os.path.join(root, f), source_dir).replace(os.sep, "/")
                mod = module_of(rel)
                parts = rel.split("/")
                if parts[0] == "include" and len(parts) == 3 and parts[2] not in FLAT:
                    problems.append(f"{rel}: a header outside a module folder (include/pounding/<module>/)")
                if parts[0] == "src" and len(parts) == 2 and rel not in FLAT_SOURCES:
                    problems.append(f"{rel}: a source outside a module folder (src/<module>/)")
                if mod is not None and mod not in ALLOWED:
                    problems.append(f"{rel}: unknown module '{mod}' (add it to ALLOWED and docs/architecture.md)")
                    continue
                with open(os.path.join(root, f), encoding="utf-8", errors="replace") as fh:
                    lines = fh.readlines()
                for no, line in enumerate(lines, 1):
                    m = INCLUDE.search(line)
                    if m and mod is not None and ALLOWED[mod] is not None:
                        dep = included_module(m.group(1))
                        if (rel, m.group(1)) in TRANSITIONAL_INCLUDES:
                            continue
                        if dep != mod and dep not in ALLOWED[mod]:
                            problems.append(f"{rel}:{no}: {mod} may not include {dep} ({m.group(1)})")
                    s = SYSTEM.search(line)
                    if s:
                        header = s.group(1)
                        if header in CONFINED and rel != CONFINED[header]:
                            problems.append(f"{rel}:{no}: <{header}> only in {CONFINED[header]}")
                        if mod in PURE and PURE_BANNED.search(line):
                            problems.append(f"{rel}:{no}: <{header}> in the {mod} layer (no I/O, parsing or fmt)")
                        if TOML.search(line) and not rel.startswith(TOML_HOME):
                            toml_seen.add(rel)
                            if rel not in toml_outside:
                                problems.append(f"{rel}:{no}: <{header}> outside the config module (read the "
                                                "table through config::TableReader)")
    for rel in sorted(set(toml_outside) - toml_seen):
        if os.path.exists(os.path.join(source_dir, rel)):
            problems.append(f"{rel}: listed in TOML_OUTSIDE_CONFIG but includes no toml++ now: remove the entry")
    return problems


def self_test():
    """The checker must catch planted violations (a test that cannot fail is a defect)."""
    import tempfile
    planted = {
        "include/pounding/kernel/a.hpp": '#include "pounding/study/b.hpp"\n',
        "include/pounding/study/b.hpp": '#include "pounding/kernel/a.hpp"\n',
        "include/pounding/loose.hpp": "\n",
        "src/parallel/serial.cpp": "#include <mpi.h>\n",
        "src/contact/law.cpp": "#include <fmt/format.h>\n",
        "src/study/reader.cpp": "#include <toml++/toml.h>\n",
        "src/config/reader.cpp": "#include <toml++/toml.h>\n",
        "src/study/listed.cpp": "\n",
    }
    expected = ["kernel may not include study", "outside a module folder", "<mpi.h> only in",
                "in the contact layer", "src/study/reader.cpp:1: <toml++/toml.h> outside the config module",
                "src/study/listed.cpp: listed in TOML_OUTSIDE_CONFIG"]
    with tempfile.TemporaryDirectory() as d:
        for rel, text in planted.items():
            os.makedirs(os.path.join(d, os.path.dirname(rel)), exist_ok=True)
            with open(os.path.join(d, rel), "w") as fh:
                fh.write(text)
        found = check(d, {"src/study/listed.cpp"})
    missed = [e for e in expected if not any(e in p for p in found)]
    allowed_ok = not any("study may not include kernel" in p or "src/config/reader.cpp" in p for p in found)
    if missed or not allowed_ok:
        print("arch.layers self-test failed: missed", missed, "or flagged an allowed include; found:", found)
        return 1
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source-dir", required=True)
    a = ap.parse_args()
    if self_test():
        return 1
    problems = check(a.source_dir)
    for p in problems:
        print(p)
    if problems:
        print(f"arch.layers: {len(problems)} problem(s)")
        return 1
    print("arch.layers: every include follows the module table")
    return 0


if __name__ == "__main__":
    sys.exit(main())
