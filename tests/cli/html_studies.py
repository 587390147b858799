#!/usr/bin/python3
"""Helpers of the html_studies fixture (tests/cli/html_studies.sh).
  same-form SHIPPED.toml REDUCED.toml   exit 1 unless the reduced study has exactly the shipped one's tables and keys
                                        (values may differ; [records] limit may be added, output removed): the same sections, so the
                                        same report sections and figure kinds
  figures R.html                        exit 1 when the report left a figure out (prints the reasons), else prints
                                        the number of figures"""
import re
import sys
import tomllib


def paths(d, prefix=()):
    out = set()
    for k, v in d.items():
        p = prefix + (k,)
        out.add(p)
        if isinstance(v, dict):
            out |= paths(v, p)
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):  # [[array of tables]]
            for x in v:
                out |= paths(x, p)
    return out


def same_form(shipped, reduced):
    a, b = (paths(tomllib.load(open(f, "rb"))) for f in (shipped, reduced))
    missing, added = a - b - {("output",)}, b - a - {("records", "limit")}
    bad = [f"{reduced}: key {'.'.join(p)} of {shipped} is missing" for p in sorted(missing)]
    bad += [f"{reduced}: key {'.'.join(p)} is not in {shipped}" for p in sorted(added)]
    for line in bad:
        print(f"FAIL: {line}")
    return 1 if bad else 0


def figures(html):
    s = open(html, encoding="utf-8").read()
    left = re.findall(r'<ul class="left-out">(.*?)</ul>', s, re.S)
    if left:
        print(f"FAIL: {html} left figures out: " + "; ".join(re.sub("<[^>]+>", " ", x).strip() for x in left))
        return 1
    print(len(re.findall(r"<figure\b", s)))
    return 0


if __name__ == "__main__":
    cmd = sys.argv[1]
    sys.exit(same_form(*sys.argv[2:4]) if cmd == "same-form" else figures(sys.argv[2]))
