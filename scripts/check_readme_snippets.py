#!/usr/bin/python3
"""Checks that every code block marked <!-- verbatim: PATH --> in README.md and
docs/extending.md appears word for word in PATH (after removing the block's
common indentation and each line's leading whitespace), so the "Adding a
scheme" and "Adding a potential" steps and the out-of-tree walkthrough quote
code that the build compiles.

Usage: check_readme_snippets.py [REPO_ROOT]   (default: the parent of scripts/)
Prints one line per problem and exits 1 if there is any, else prints a summary.
"""
import pathlib
import re
import sys

MARK = re.compile(r"<!--\s*verbatim:\s*(\S+)\s*-->")


def blocks(readme_lines):
    """Yields (line number, path, code lines) for each marked block."""
    i = 0
    while i < len(readme_lines):
        m = MARK.search(readme_lines[i])
        if m:
            j = i + 1
            if j >= len(readme_lines) or not readme_lines[j].strip().startswith("```"):
                yield i + 1, m.group(1), None
                i = j
                continue
            k = j + 1
            code = []
            while k < len(readme_lines) and not readme_lines[k].strip().startswith("```"):
                code.append(readme_lines[k])
                k += 1
            yield i + 1, m.group(1), code
            i = k
        i += 1


def normalise(lines):
    return [line.strip() for line in lines if line.strip()]


def main(argv):
    if len(argv) > 1 and argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0
    root = pathlib.Path(argv[1]) if len(argv) > 1 else pathlib.Path(__file__).resolve().parent.parent
    problems, checked = [], 0
    for doc in ("README.md", "docs/extending.md"):
        lines = (root / doc).read_text(encoding="utf-8").splitlines()
        for line, path, code in blocks(lines):
            if code is None:
                problems.append(f"{doc}:{line}: a verbatim mark must be followed by a code block")
                continue
            target = root / path
            if not target.is_file():
                problems.append(f"{doc}:{line}: {path} does not exist")
                continue
            want = normalise(code)
            have = normalise(target.read_text(encoding="utf-8").splitlines())
            found = any(have[s:s + len(want)] == want for s in range(len(have) - len(want) + 1))
            if not want or not found:
                problems.append(f"{doc}:{line}: the block is not in {path} word for word")
            checked += 1
    for p in problems:
        print(p)
    if not problems:
        print(f"{checked} snippets of README.md and docs/extending.md found word for word in the files they quote")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
