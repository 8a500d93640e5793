#!/usr/bin/python3
"""Check that no test or script parses a scheme name.

Usage: scripts/check_scheme_names.py [REPO_ROOT]   (default: the parent of scripts/)

What a scheme is comes from the registry's facts, never from the '@' of a
composition (BASE@METHOD) or the '/' of a baseline (COORDS/STEPPER): in C++
SchemeInfo::base_scheme, properties.baseline, family (integrators/registry/registry.hpp);
in `lgi schemes --json` and Python's lgi.schemes() the records' "kind",
"base" and "family" (experiments/SCHEMES.md). This script reads every C++,
Python and shell file under tests/ and scripts/ and prints one line per
line that looks for '@' or '/' in a string, "file:line: text", exiting 1 if
any:

  C++     find('@'), find("@x"), rfind("x/"), starts_with("x@"), ends_with("/x"), == '/'
  Python  "@" in x, '/' in x, .split("@"), .rsplit("/"), .partition("@"),
          startswith("x/"), endswith("/x")
  shell   ${x%%/*}, ${x#*@} and the like

ALLOWED lists the lines that handle paths or benchmark names (SCENE/SCHEME,
google-benchmark's), with the reason; a new hit must use the facts instead.
Prints "check_scheme_names: N files, no scheme name parsed" and exits 0
otherwise. Standard library only (Debian's /usr/bin/python3).
"""
import os
import re
import sys

from check_report import report

SEP = r"""[@/]"""
PATTERNS = [
    # a literal that is a separator, starts with one (find("@bcm"), ends_with("/bs")) or ends with
    # one (starts_with("euler-zxz/")); a whole name searched for (find("quat/rk4")) is no parse
    re.compile(r"""\b(r?find|(starts|ends)_?with)\(\s*r?['"]""" + SEP),
    re.compile(r"""\b(r?find|(starts|ends)_?with)\(\s*r?['"][^'"]*""" + SEP + r"""['"]"""),
    re.compile(r"""==\s*'""" + SEP + "'"),                                  # C++ ch == '/'
    re.compile(r"""['"]""" + SEP + r"""['"]\s+(not\s+)?in\b"""),            # Python "@" in name
    re.compile(r"""\.(r?split|r?partition)\(\s*r?['"]""" + SEP + r"""['"]"""),  # Python .split("/")
    re.compile(r"""\$\{\w+(%%?|##?)[^}]*""" + SEP),                         # shell ${x%%/*}, ${x#*@}
]
# (file, text on the line): path or benchmark-name handling, never a scheme name.
ALLOWED = [
    ("tests/test_baselines_singularity.cpp", "if (ch == '/') ch = '_';"),  # a file name from a scheme name
    ("scripts/plots/sweep_scaling.py", 'name.rsplit("/", 1)'),              # a scene file's path
    ("scripts/check_docs.py", 'target.startswith("//")'),                   # a link target
    ("scripts/check_layers.py", 'rel.split("/")'),                          # a source file's path
    ("scripts/check_layers.py", 'name.startswith("experiments/")'),
    ("scripts/check_layers.py", 'local.startswith("experiments/")'),
    ("scripts/check_layers.py", 'rel.startswith("experiments/")'),
    ("tests/test_h5md_writer.cpp", 'p.ends_with("/step")'),                 # an HDF5 dataset's path
    ("scripts/benchmark_ratios.py", 'name.rsplit("/", 1)[1]'),              # benchmark names ...
    ("scripts/benchmark_ratios.py", 'name.startswith("limits/vector_peak/")'),
    ("scripts/benchmark_ratios.py", 'b["name"].startswith("ensemble/")'),
    ("scripts/benchmark_ratios.py", 'b["name"].startswith("limits/")'),
    ("scripts/benchmark_ratios.py", 'b["name"].startswith("newton/")'),
    ("scripts/benchmark_ratios.py", 'base, isa = name.rsplit("/", 1)'),
    ("scripts/benchmark_ratios.py", 'b["name"].startswith("tangent/")'),
    ("scripts/benchmark_ratios.py", 'b["name"].split("/", 1)'),             # SCENE/SCHEME: the scheme kept whole
    ("scripts/benchmark_ratios.py", 'name.rsplit("/", 1)[0]'),
]
SOURCES = (".cpp", ".hpp", ".h", ".py", ".sh")
SELF = "scripts/check_scheme_names.py"


def files(root):
    for top in ("tests", "scripts"):
        for d, dirs, names in os.walk(os.path.join(root, top)):
            dirs[:] = sorted(x for x in dirs if not x.startswith(".") and x != "__pycache__")
            for n in sorted(names):
                if n.endswith(SOURCES):
                    yield os.path.relpath(os.path.join(d, n), root).replace(os.sep, "/")


def hits(root, rel):
    with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
        for i, line in enumerate(f, 1):
            if not any(p.search(line) for p in PATTERNS):
                continue
            if any(rel == a and text in line for a, text in ALLOWED):
                continue
            yield i, line.strip()


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
    checked = [rel for rel in files(root) if rel != SELF]
    problems = [f"{rel}:{i}: {text}" for rel in checked for i, text in hits(root, rel)]
    return report(problems,
                  f"check_scheme_names: {len(problems)} line(s) look for '@' or '/' in a string; read the scheme's "
                  "facts (kind, base, family) instead, or add a path-handling line to ALLOWED with its reason",
                  f"check_scheme_names: {len(checked)} files, no scheme name parsed")


if __name__ == "__main__":
    sys.exit(main())
