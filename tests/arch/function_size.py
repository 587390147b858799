#!/usr/bin/env python3
"""ctest arch.function_size: no function in src/ or include/ over 80 lines (C14), no file over 800 lines, and no
mutable function-level static (the guards of docs/runner-design.md section 1), and every file opens with a
one-line comment saying what it holds (issue 46, "Names that explain themselves").

Functions and files already over their limit sit on falling lists (LONG_FUNCTIONS, LONG_FILES) with the length
they had when the list was made: a listed one may shrink but never grow, and leaves the list once within the
limit (the check says so). A function-level `static` that is not const or constexpr is hidden shared state
(state that outlives the call and that threads share): MUTABLE_STATICS lists the one allowed, with its reason.

A function's length runs from the line its declaration starts on to the line of its closing brace, so
lambdas, local classes and everything else nested in the body count toward the enclosing function. The
scanner is C++ aware enough for that: comments, string literals (raw strings included), character literals
and preprocessor lines are blanked before braces are matched, and digit separators (1'000) are not taken for
character literals. A `{` at namespace or class scope opens a function body when the text since the
previous `;`, `{` or `}` has a parameter list and does not start with namespace/class/struct/union/enum
(a brace initialiser `= {` is not a body). Each violation is printed as file:line, the name and the length;
exit 1 when there is any.
"""
import argparse
import os
import re
import sys

LIMIT = 80

# Files being rewritten by other branches at the same time (kernel redesign; results/driver redesign).
# They are checked once those land: the integrator empties this list when merging.
EXCLUDED: set = set()  # no file is exempt (the kernel redesign split the last long functions)

FILE_LIMIT = 800
# (file, function) -> lines when listed; may only fall (docs/runner-design.md step 8 splits them)
LONG_FUNCTIONS = {
}
# file -> lines when listed; may only fall (runner-design.md steps 2-4 take run.cpp to 500 lines)
LONG_FILES = {
    "src/cli/commands/simulate.cpp": 1632,
    "src/report/report.cpp": 1080,
    "src/analysis/stripes.cpp": 938,
    "include/pounding/physics/steppers/system_central_difference.hpp": 860,
    "src/io/hdf5.cpp": 889,
    "src/config/study_keys.cpp": 905,
}
# (file, variable): a function-level static that is not const, and why it may stay
MUTABLE_STATICS = {
    ("src/results/results.cpp", "mutex"): "guards the interned per-building field names (results::floor_field)",
    ("src/results/results.cpp", "texts"): "the interned per-building field names: any building count (a bridge's frames)",
}
# `static` followed by a declaration without a parameter list up to its `;`, `=` or `{` (a variable, not a
# function): `static std::mutex m;`, `static int n = 0;`; const and constexpr are immutable and allowed
STATIC_VAR = re.compile(r"\bstatic\s+(?!const\b|constexpr\b|constinit\s+const\b)([^;=(){}]*?)([A-Za-z_][A-Za-z_0-9]*)\s*(?:;|=|\{)")

SUFFIXES = (".cpp", ".cc", ".hpp", ".h")
NOT_A_FUNCTION = re.compile(r"^(template\s*<.*>\s*)?(namespace|class|struct|union|enum|extern)\b", re.S)
CTOR_INIT = re.compile(r"\)\s*(noexcept\s*)?:(?!:)")
NAME_BEFORE_PAREN = re.compile(r"([A-Za-z_~][A-Za-z_0-9]*(?:\s*::\s*~?[A-Za-z_][A-Za-z_0-9]*)*)\s*(?:<[^()]*>)?\s*$")


def blank(text):
    """Return text with comments, literals and preprocessor lines replaced by spaces (newlines kept)."""
    out = list(text)
    i, n = 0, len(text)

    def wipe(a, b):
        for k in range(a, b):
            if out[k] != "\n":
                out[k] = " "

    at_line_start = True
    while i < n:
        c = text[i]
        if c == "\n":
            at_line_start = True
            i += 1
            continue
        if at_line_start and c == "#":  # preprocessor line, with backslash continuations
            j = i
            while j < n and (text[j] != "\n" or text[j - 1] == "\\"):
                j += 1
            wipe(i, j)
            i = j
            continue
        if not c.isspace():
            at_line_start = False
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            wipe(i, j)
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            wipe(i, j)
            i = j
        elif c == '"':
            # raw string: R"delim( ... )delim", the R possibly prefixed by u8, u, U or L
            m = re.match(r'(?:u8|u|U|L)?R$', text[max(0, i - 3):i][-3:]) if i > 0 and text[i - 1] == "R" else None
            starts_token = m and (i - len(m.group(0)) == 0 or not (text[i - len(m.group(0)) - 1].isalnum()
                                                                  or text[i - len(m.group(0)) - 1] == "_"))
            if starts_token:
                paren = text.find("(", i)
                delim = text[i + 1:paren]
                end = text.find(")" + delim + '"', paren)
                j = n if end < 0 else end + len(delim) + 2
            else:
                j = i + 1
                while j < n and text[j] != '"':
                    j += 2 if text[j] == "\\" else 1
                j += 1
            wipe(i + 1, j - 1)
            i = j
        elif c == "'":
            k = i - 1
            while k >= 0 and (text[k].isalnum() or text[k] == "_" or text[k] == "."):
                k -= 1
            if k + 1 < i and text[k + 1].isdigit():  # digit separator inside a number
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != "'":
                j += 2 if text[j] == "\\" else 1
            wipe(i + 1, j)
            i = j + 1
        else:
            i += 1
    return "".join(out)


def function_header(header):
    """The function's name if `header` (text before a `{` outside any body) declares a function, else None."""
    h = header.strip()
    if not h or NOT_A_FUNCTION.match(h) or "(" not in h:
        return None
    if h.endswith("=") or h.endswith(","):
        return None  # a brace initialiser
    depth, first_paren = 0, None
    for k, ch in enumerate(h):
        if ch == "(" and depth == 0 and first_paren is None:
            first_paren = k
        depth += ch == "("
        depth -= ch == ")"
    if depth != 0:
        return None
    before = h[:first_paren].rstrip()
    if before.endswith("]"):
        return "lambda"
    m = NAME_BEFORE_PAREN.search(before)
    return m.group(1).replace(" ", "") if m else None


def functions(text):
    """Yield (start_line, end_line, name) for every function definition (outermost bodies only)."""
    b = blank(text)
    stack = []  # per open brace: "scope" (namespace/class/initialiser) or "function"
    header_start = 0
    body_open = None  # (start offset of header, name) of the function being scanned
    line_of = lambda off: b.count("\n", 0, off) + 1
    for i, ch in enumerate(b):
        if ch not in "{};":
            continue
        in_function = "function" in stack
        if ch == "{":
            if in_function:
                stack.append("block")
                continue
            header = b[header_start:i]
            if CTOR_INIT.search(header) and re.search(r"[A-Za-z_0-9>]\s*$", header):
                stack.append("member-init")  # a_{x} in a constructor's initialiser list, not the body
                continue
            name = function_header(header)
            if name is not None:
                lead = len(header) - len(header.lstrip())
                body_open = (header_start + lead, name)
                stack.append("function")
            else:
                stack.append("scope")
            header_start = i + 1
        elif ch == "}":
            kind = stack.pop() if stack else "scope"
            if kind == "function" and "function" not in stack:
                start, name = body_open
                yield line_of(start), line_of(i), name
            if "function" not in stack and kind != "member-init":
                header_start = i + 1
        elif not in_function:
            header_start = i + 1


def check_text(rel, text, problems, seen):
    """Append the problems of one file's text: long functions, its length, mutable function-level statics."""
    lines = text.count("\n") + (0 if text.endswith("\n") else 1)
    listed = LONG_FILES.get(rel)
    if listed is not None:
        seen.add(("file", rel))
        if lines > listed:
            problems.append(f"{rel}: {lines} lines, more than the {listed} it had when listed in LONG_FILES (it may only fall)")
        elif lines <= FILE_LIMIT:
            problems.append(f"{rel}: {lines} lines, within {FILE_LIMIT}: remove it from LONG_FILES")
    elif lines > FILE_LIMIT:
        problems.append(f"{rel}: {lines} lines (limit {FILE_LIMIT}): split it by what its parts do")
    opening = [l for l in text.split("\n") if l.strip() and l.strip() != "#pragma once"][:1]
    if not opening or not opening[0].startswith("//"):
        problems.append(f"{rel}:1: no opening comment: begin the file with one `// ...` line saying what it holds")
    blanked = blank(text).split("\n")
    for start, end, name in functions(text):
        length = end - start + 1
        limit = LONG_FUNCTIONS.get((rel, name))
        if limit is not None:
            seen.add(("function", rel, name))
            if length > limit:
                problems.append(f"{rel}:{start}: {name} is {length} lines, more than the {limit} it had when listed")
        elif length > LIMIT:
            problems.append(f"{rel}:{start}: {name} is {length} lines (limit {LIMIT})")
        body = "\n".join(blanked[start - 1:end])
        for m in STATIC_VAR.finditer(body, body.find("{") + 1 if "{" in body else 0):
            var = m.group(2)
            if (rel, var) in MUTABLE_STATICS:
                seen.add(("static", rel, var))
                continue
            line = start + body.count("\n", 0, m.start())
            problems.append(f"{rel}:{line}: `static ... {var}` in {name} is mutable state shared by every call and "
                            "thread: make it const, a member, or a parameter")


def check(source_dir, excluded):
    problems, seen = [], set()
    for top in ("src", "include"):
        for root, dirs, files in os.walk(os.path.join(source_dir, top)):
            dirs.sort()
            for f in sorted(files):
                if not f.endswith(SUFFIXES):
                    continue
                rel = os.path.relpath(os.path.join(root, f), source_dir).replace(os.sep, "/")
                if rel in excluded:
                    continue
                with open(os.path.join(root, f), encoding="utf-8", errors="replace") as fh:
                    check_text(rel, fh.read(), problems, seen)
    for rel in LONG_FILES:
        if ("file", rel) not in seen and rel not in excluded:
            problems.append(f"{rel}: listed in LONG_FILES but not found: remove it from the list")
    for rel, name in LONG_FUNCTIONS:
        if ("function", rel, name) not in seen and rel not in excluded:
            problems.append(f"{rel}: {name} listed in LONG_FUNCTIONS but not found (within the limit now?): remove it")
    for rel, var in MUTABLE_STATICS:
        if ("static", rel, var) not in seen and rel not in excluded:
            problems.append(f"{rel}: static {var} listed in MUTABLE_STATICS but not found: remove it from the list")
    return problems


def self_test():
    """Planted cases: braces in literals and comments, lambdas, classes, initialisers, raw strings."""
    filler = "  x();\n" * 79
    cases = {
        # 1 + 79 + 1 = 81 lines, with a brace in a string, a char, a comment and a raw string
        "long": ("void long_one(int a) {\n" + filler.replace("x();", 'x("}"); // }', 1) + "}\n", ["long_one"]),
        "exact": ("int ok() {\n" + "  x();\n" * 78 + "}\n", []),
        "lambda": ("auto f() {\n  auto g = [] {\n" + filler + "  };\n}\n", ["f"]),
        "member": ("struct S {\n  int m() const noexcept {\n" + filler + "  }\n};\n", ["m"]),
        "ctor": ("S::S(int a) : a_(a), b_{a} {\n" + filler + "}\n", ["S::S"]),
        "literals": ("const char* t = R\"X({{{{)X\"; char c = '{'; int n = 1'000;\n"
                     "namespace a { int f() {\n" + "  x();\n" * 78 + "} }\n", []),
        "init": ("constexpr int tab[] = {\n" + "  1,\n" * 90 + "};\n", []),
    }
    bad = []
    for label, (text, expected) in cases.items():
        found = [name for start, end, name in functions(text) if end - start + 1 > LIMIT]
        if found != expected:
            bad.append(f"{label}: expected {expected}, found {found}")
    planted = {
        "static": ("int f() {\n  static int calls = 0;\n  return ++calls;\n}\n", ["calls"]),
        "static-ok": ("int f() {\n  static const int k = 1;\n  static constexpr int j = 2;\n  return k + j;\n}\n"
                      "struct S {\n  static int g(int a) { return a; }\n};\n", []),
        "static-map": ("void f() {\n  static std::map<int, std::pair<int, int>> m{};\n}\n", ["m"]),
    }
    for label, (text, expected) in planted.items():
        problems = []
        check_text("planted.cpp", text, problems, set())
        found = [re.search(r"static \.\.\. (\w+)", p).group(1) for p in problems if "static ..." in p]
        if found != expected:
            bad.append(f"{label}: expected {expected}, found {found}")
    problems = []
    check_text("planted.cpp", "#pragma once\n\n#include <x>\nint y;\n", problems, set())
    if len(problems) != 1 or "no opening comment" not in problems[0]:
        bad.append(f"opening comment: expected one problem, found {problems}")
    problems = []
    check_text("planted.cpp", "// A file.\n" + "int x;\n" * (FILE_LIMIT + 1), problems, set())
    if len(problems) != 1 or "limit 800" not in problems[0]:
        bad.append(f"file length: expected one problem, found {problems}")
    if bad:
        print("arch.function_size self-test failed:", "; ".join(bad))
        return 1
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source-dir", required=True)
    ap.add_argument("--all", action="store_true", help="check the excluded files too")
    a = ap.parse_args()
    if self_test():
        return 1
    problems = check(a.source_dir, set() if a.all else EXCLUDED)
    for p in problems:
        print(p)
    if problems:
        print(f"arch.function_size: {len(problems)} problem(s)")
        return 1
    print(f"arch.function_size: no function in src/ or include/ over {LIMIT} lines, no file over {FILE_LIMIT} lines "
          f"({len(LONG_FUNCTIONS)} functions and {len(LONG_FILES)} files on falling lists), no mutable function-level "
          f"static but the {len(MUTABLE_STATICS)} listed, every file with an opening comment"
          + (f" ({len(EXCLUDED)} files excluded while being rewritten)" if EXCLUDED and not a.all else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
