#!/usr/bin/env python3
"""ctest docs.paths: the user documents cannot point at files that are not there, and the README stays one screen.

Fails (exit 1, one line per problem, file:line and the path) when
  - README.md is longer than MAX_README_LINES lines,
  - a repository path named in README.md, CHANGELOG.md or docs/*.md does not exist. A path is
      * the target of a Markdown link or image, [text](target) (relative to the document's folder;
        http(s)/mailto links and #anchors are not paths),
      * a `code span` that starts with a top-level folder of the repository (src/, include/, tests/, tools/,
        docs/, studies/, records/, bench/, cmake/, .ci/) or is a top-level file (README.md, CHANGELOG.md,
        CMakeLists.txt, STYLE.md), relative to the repository root.
    Spans with a wildcard or a placeholder (*, ?, <, >, {, }, $, ...) and spans with spaces (commands) are not
    paths; a trailing ':line', '#anchor' or '/' is dropped.
  - a document links to another document's heading (#anchor) that the other document does not have.
The self-test (--self-test) plants a missing path, a missing anchor and a long README in a temporary tree and
checks that each is reported: a check that cannot fail is a defect.
"""
import argparse
import os
import re
import sys
import tempfile

MAX_README_LINES = 150
TOP_DIRS = ("src/", "include/", "tests/", "tools/", "docs/", "studies/", "records/", "bench/", "cmake/", ".ci/")
TOP_FILES = {"README.md", "CHANGELOG.md", "CMakeLists.txt", "STYLE.md"}
LINK = re.compile(r'!?\[[^\]]*\]\(([^)\s]+)(?:\s+"[^"]*")?\)')
CODE = re.compile(r'`([^`\n]+)`')
PLACEHOLDER = re.compile(r'[*?<>{}$\[\]|=,;()]|\.\.\.')


def documents(root):
    docs = [os.path.join(root, "README.md")]
    if os.path.exists(os.path.join(root, "CHANGELOG.md")):
        docs.append(os.path.join(root, "CHANGELOG.md"))
    for dirpath, _, files in os.walk(os.path.join(root, "docs")):
        docs += [os.path.join(dirpath, f) for f in sorted(files) if f.endswith(".md")]
    return docs


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    s = heading.strip().lower()
    s = re.sub(r'[^\w\- ]', '', s)
    return s.replace(' ', '-')


def anchors(path):
    out = set()
    in_fence = False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if line.startswith("```"):
                in_fence = not in_fence
            elif not in_fence and line.startswith("#"):
                out.add(slug(line.lstrip("#")))
    return out


def modules(root):
    out = set()
    for d in ("include/pounding", "src"):
        if os.path.isdir(os.path.join(root, d)):
            out |= {e for e in os.listdir(os.path.join(root, d)) if os.path.isdir(os.path.join(root, d, e))}
    return out


def clean(target):
    target = target.split("#", 1)[0]
    target = re.sub(r':\d+(-\d+)?$', '', target)
    return target.rstrip("/")


def check(root):
    problems = []
    readme = os.path.join(root, "README.md")
    with open(readme, encoding="utf-8") as f:
        n = sum(1 for _ in f)
    if n > MAX_README_LINES:
        problems.append(f"README.md: {n} lines, more than {MAX_README_LINES}: move the rest to docs/")
    anchor_cache = {}
    for doc in documents(root):
        rel_doc = os.path.relpath(doc, root)
        base = os.path.dirname(doc)
        in_fence = False
        with open(doc, encoding="utf-8") as f:
            for lineno, line in enumerate(f, 1):
                if line.startswith("```"):
                    in_fence = not in_fence
                    continue
                if in_fence or line.startswith("    "):  # code blocks: commands and output, not references
                    continue
                for m in LINK.finditer(line):
                    raw = m.group(1)
                    if re.match(r'^[a-z]+:', raw):
                        continue
                    path_part, _, anchor = raw.partition("#")
                    target = os.path.normpath(os.path.join(base, path_part)) if path_part else doc
                    if path_part and not os.path.exists(target):
                        problems.append(f"{rel_doc}:{lineno}: link to '{raw}': {os.path.relpath(target, root)} does not exist")
                        continue
                    if anchor and target.endswith(".md"):
                        if target not in anchor_cache:
                            anchor_cache[target] = anchors(target)
                        if anchor not in anchor_cache[target]:
                            problems.append(f"{rel_doc}:{lineno}: link to '{raw}': {os.path.relpath(target, root)} "
                                            f"has no heading with the anchor #{anchor}")
                for m in CODE.finditer(LINK.sub("", line)):
                    span = m.group(1).strip()
                    if " " in span or PLACEHOLDER.search(span):
                        continue
                    path = clean(span)
                    if not (path.startswith(TOP_DIRS) or path in TOP_FILES):
                        # `module/file.hpp` (or .cpp): a file of a module, under include/pounding/ or src/
                        first = path.split("/", 1)[0]
                        if (re.fullmatch(r'[a-z_]+(/[\w.-]+)+\.(hpp|cpp)', path)
                                and first in modules(root)
                                and not any(os.path.exists(os.path.join(root, d, path))
                                            for d in ("include/pounding", "src"))):
                            problems.append(f"{rel_doc}:{lineno}: `{span}`: neither include/pounding/{path} "
                                            f"nor src/{path} exists")
                        continue
                    if not os.path.exists(os.path.join(root, path)):
                        problems.append(f"{rel_doc}:{lineno}: `{span}`: {path} does not exist in the repository")
    return problems


def self_test():
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "docs"))
        os.makedirs(os.path.join(root, "src"))
        open(os.path.join(root, "src", "here.cpp"), "w").close()
        os.makedirs(os.path.join(root, "include", "pounding", "mod"))
        open(os.path.join(root, "include", "pounding", "mod", "a.hpp"), "w").close()
        with open(os.path.join(root, "docs", "guide.md"), "w") as f:
            f.write("# Guide\n\n## Real heading\n\nSee `src/here.cpp`, `src/gone.cpp` and [x](../README.md#nope).\n"
                    "Module files: `mod/a.hpp` is there, `mod/b.hpp` is not.\n"
                    "And [y](missing.md), [z](guide.md#real-heading), `build/pounding`, `src/*.cpp`.\n")
        with open(os.path.join(root, "README.md"), "w") as f:
            f.write("# R\n" + "line\n" * MAX_README_LINES)
        found = check(root)
        expect = ["more than", "src/gone.cpp", "#nope", "missing.md", "mod/b.hpp"]
        missed = [e for e in expect if not any(e in p for p in found)]
        if missed or len(found) != len(expect):
            print("self-test failed: planted problems " + str(expect) + ", reported: " + str(found))
            return 1
    return 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source-dir", required=True)
    args = ap.parse_args()
    if self_test():
        return 1
    problems = check(args.source_dir)
    for p in problems:
        print(p)
    if problems:
        print(f"{len(problems)} problem(s): fix the path or the document")
        return 1
    print("README.md and docs/*.md: every repository path exists; README within the line limit")
    return 0


if __name__ == "__main__":
    sys.exit(main())
