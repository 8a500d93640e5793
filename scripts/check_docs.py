#!/usr/bin/python3
"""Check that the repository's documentation is self-contained.

Usage: scripts/check_docs.py [REPO_ROOT]   (default: the parent of scripts/)

Scans every tracked text file, and every untracked file git does not ignore,
and reports one line per offence, "file:line: text", exiting 1 if any:

  - a citation of a file outside the repository: the shared specification,
    design and seed folders (spelled with or without a leading "../"), an
    absolute /work/ path, or a bare name of one of the original documents
    (conventions.md, math.md, cli.md, ...) that does not resolve next to the
    citing file;
  - a relative markdown link [text](path) in a *.md file whose target does
    not exist, leaves the repository, or names a heading (#anchor) the target
    markdown file does not have;
  - a citation "docs/NAME.md" of a file that does not exist, or
    "docs/NAME.md §N" of a section the file does not number;
  - team-process words ("issue:", "the issue's", "colleague") in the text.

Prints "check_docs: N files clean" and exits 0 otherwise. Standard library
only (Debian's /usr/bin/python3).
"""
import os
import re
import subprocess
import sys

from check_report import report

THIS = os.path.abspath(__file__)

# Citations of files outside the repository.
OUTSIDE = [
    re.compile(r"(?<![\w-])shared/"),
    re.compile(r"(?<![\w./-])(?:spec|design|seeds)/[\w.-]"),
    re.compile(r"/work/"),
]
# Bare names of the original documents; allowed only where they resolve
# relative to the citing file (e.g. math.md inside docs/).
BARE = re.compile(
    r"(?<![\w/.-])((?:conventions|math|cli|output-file|scene-file|schemes|scenes"
    r"|atlas|atlas-and-sweeps|architecture)\.md)\b"
)
PROCESS = re.compile(r"\bissue:|\bthe issue's\b|\bcolleague", re.IGNORECASE)
MD_LINK = re.compile(r"!?\[[^\]]*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
DOCS_CITE = re.compile(r"(?<![\w.-])docs/([\w.-]+\.md)(?:\s*§\s*(\d+))?")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")


def list_files(root):
    """Tracked files plus untracked, non-ignored ones; a walk without git."""
    try:
        out = subprocess.run(
            ["git", "-C", root, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
            check=True, capture_output=True,
        ).stdout.decode("utf-8", "surrogateescape")
        names = sorted({n for n in out.split("\0") if n})
    except (OSError, subprocess.CalledProcessError):
        names = []
        for d, dirs, files in os.walk(root):
            dirs[:] = [x for x in dirs if x not in (".git", "build")]
            names += [os.path.relpath(os.path.join(d, f), root) for f in files]
        names.sort()
    return [n for n in names if os.path.isfile(os.path.join(root, n))]


def read_text(path):
    try:
        with open(path, "rb") as f:
            data = f.read()
    except OSError:
        return None
    if b"\0" in data[:8192]:
        return None
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        return None


def slug(text):
    """GitHub's anchor for a heading's text."""
    text = re.sub(r"`([^`]*)`", r"\1", text)
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    s = "".join(c for c in text.lower() if c.isalnum() or c in " -_")
    return s.replace(" ", "-")


_anchor_cache = {}


def anchors_and_sections(path):
    """The anchors of a markdown file's headings, and its numbered sections."""
    if path not in _anchor_cache:
        anchors, sections, seen = set(), set(), {}
        text = read_text(path) or ""
        fence = False
        for line in text.splitlines():
            if line.lstrip().startswith(("```", "~~~")):
                fence = not fence
                continue
            m = None if fence else HEADING.match(line)
            if not m:
                continue
            a = slug(m.group(2))
            n = seen.get(a, 0)
            seen[a] = n + 1
            anchors.add(a if n == 0 else f"{a}-{n}")
            num = re.match(r"(\d+)[.)]?\s", m.group(2))
            if num:
                sections.add(num.group(1))
        _anchor_cache[path] = (anchors, sections)
    return _anchor_cache[path]


def inside(root, path):
    root = os.path.realpath(root)
    path = os.path.realpath(path)
    return path == root or path.startswith(root + os.sep)


def check_link(root, rel, target):
    """None if the markdown link target is fine, else what is wrong."""
    if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target) or target.startswith("//"):
        return None  # URL (http:, https:, mailto:, ...)
    path, _, anchor = target.partition("#")
    here = os.path.dirname(os.path.join(root, rel))
    dest = os.path.normpath(os.path.join(here, path)) if path else os.path.join(root, rel)
    if not inside(root, dest):
        return f"link leaves the repository: {target}"
    if not os.path.exists(dest):
        return f"link to a missing file: {target}"
    if anchor and dest.endswith(".md") and os.path.isfile(dest):
        if anchor not in anchors_and_sections(dest)[0]:
            return f"link to a missing heading: {target}"
    return None


def check_file(root, rel, text):
    problems = []
    is_md = rel.endswith(".md")
    here = os.path.dirname(os.path.join(root, rel))
    fence = False
    for no, line in enumerate(text.splitlines(), 1):
        why = []
        for pat in OUTSIDE:
            if pat.search(line):
                why.append("cites a file outside the repository")
                break
        for m in BARE.finditer(line):
            if not os.path.isfile(os.path.join(here, m.group(1))):
                why.append(f"cites {m.group(1)}, not in the repository (use docs/...)")
        for m in DOCS_CITE.finditer(line):
            doc = os.path.join(root, "docs", m.group(1))
            if not os.path.isfile(doc):
                why.append(f"cites docs/{m.group(1)}, which does not exist")
            elif m.group(2) and m.group(2) not in anchors_and_sections(doc)[1]:
                why.append(f"cites docs/{m.group(1)} §{m.group(2)}, which has no such section")
        if PROCESS.search(line):
            why.append("team-process words")
        if is_md:
            if line.lstrip().startswith(("```", "~~~")):
                fence = not fence
            elif not fence:
                for m in MD_LINK.finditer(re.sub(r"`[^`]*`", "", line)):
                    w = check_link(root, rel, m.group(1))
                    if w:
                        why.append(w)
        for w in dict.fromkeys(why):
            problems.append(f"{rel}:{no}: {w}: {line.strip()}")
    return problems


def main(argv):
    root = os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(THIS), ".."))
    if not os.path.isdir(root):
        print(f"check_docs: {root}: not a directory", file=sys.stderr)
        return 2
    problems, n = [], 0
    for rel in list_files(root):
        path = os.path.join(root, rel)
        if os.path.realpath(path) == os.path.realpath(THIS):
            continue  # this file spells out the patterns it looks for
        text = read_text(path)
        if text is None:
            continue
        n += 1
        problems += check_file(root, rel, text)
    return report(problems, f"check_docs: {len(problems)} problem(s) in {n} files", f"check_docs: {n} files clean")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
