#!/usr/bin/python3
"""Check the layering of experiments/.

Usage: scripts/check_layers.py [REPO_ROOT]   (default: the parent of scripts/)

experiments/ is built in layers, lowest first:

  errors/    the error types and exit statuses
  io/        scene reading, HDF5 and CSV output, number formats, observers
  analysis/  numerics on results (reference solutions, error measures)
  cli/       the command line: options, run settings, the command table
  commands/  one file per subcommand, with its helpers in subfolders
  main.cpp   (experiments/ top level) the lgi executable

A file may include headers of its own layer and of lower layers, and every
layer may include lgi's own integrators/ and lie/ headers, which in turn
never include experiments/. The tests (tests/) may include any layer.

Reads every C++ file under experiments/, tests/, integrators/ and lie/,
follows its #include "experiments/..." lines (and quoted includes relative
to the file that name a file under experiments/), and prints one line per
violation, "file:line: what", exiting 1 if any:

  - an include of a header in a higher layer;
  - an #include "experiments/..." of a file that does not exist;
  - a C++ file under experiments/ outside the layers (other than main.cpp);
  - an include cycle among the files under experiments/;
  - a call from a lower layer of experiments/ to a function declared only in
    a header of a higher layer;
  - a function declared in a header of a lower layer but defined in a .cpp of
    a higher one (e.g. add_sweep_subcommand() declared in cli/ and defined in
    commands/, which cli/ then calls): a call up the layers that the include
    check does not see.

integrators/ is sorted by role (README, "Layout"), and its folders are
ranked too: tableaus/ and system/ (data and physics) < core/ (the loop) <
schemes/ and baselines/ < registry/ and ensemble/. A header of a lower role
that includes one of a higher role (the loop including a scheme, a scheme
including the registry) is a violation, and so is a C++ file at the top
level of integrators/, outside every role.

Prints "check_layers: N files, M includes of experiments/, layering clean"
and exits 0 otherwise. Standard library only (Debian's /usr/bin/python3).
"""
import os
import re
import sys

from check_report import report

THIS = os.path.abspath(__file__)

LAYERS = ["errors", "io", "analysis", "cli", "commands"]
TOP = len(LAYERS)           # experiments/main.cpp
TESTS = TOP + 1             # tests/: may include anything
BELOW = -1                  # integrators/, lie/: may include nothing of experiments/
SCANNED = {"experiments": None, "tests": TESTS, "integrators": BELOW, "lie": BELOW}
CXX = (".hpp", ".cpp", ".h", ".hh", ".hxx", ".cc", ".cxx", ".ipp", ".inl", ".tpp")
INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def layer_name(layer):
    if layer == BELOW:
        return "integrators/lie"
    if layer == TESTS:
        return "tests"
    if layer == TOP:
        return "experiments top level"
    return LAYERS[layer] + "/"


def layer_of(rel):
    """The layer of a file given relative to the repository root, or None."""
    parts = rel.split("/")
    if parts[0] != "experiments":
        return SCANNED.get(parts[0])
    if len(parts) == 2:
        return TOP if parts[1] == "main.cpp" else None
    return LAYERS.index(parts[1]) if parts[1] in LAYERS else None


def cxx_files(root):
    files = []
    for top in SCANNED:
        for d, dirs, names in os.walk(os.path.join(root, top)):
            dirs[:] = sorted(x for x in dirs if not x.startswith(".") and x != "build")
            for n in sorted(names):
                if n.endswith(CXX):
                    files.append(os.path.relpath(os.path.join(d, n), root).replace(os.sep, "/"))
    return files


def includes(root, rel):
    """(line number, included file relative to the root, as written) for each
    include of a file under experiments/."""
    out = []
    try:
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
            lines = f.read().splitlines()
    except OSError:
        return out
    here = os.path.dirname(rel)
    for no, line in enumerate(lines, 1):
        m = INCLUDE.match(line)
        if not m:
            continue
        name = m.group(1)
        if name.startswith("experiments/"):
            out.append((no, os.path.normpath(name).replace(os.sep, "/"), name))
            continue
        local = os.path.normpath(os.path.join(here, name)).replace(os.sep, "/")
        if local.startswith("experiments/") and os.path.isfile(os.path.join(root, local)):
            out.append((no, local, name))
    return out


DECLARATION = re.compile(r"^[A-Za-z_][\w:<>,&*\s]*?[\s&*]([A-Za-z_]\w*)\s*\(")
KEYWORDS = {"if", "for", "while", "switch", "return", "sizeof", "static_assert", "decltype", "operator"}


def declared_functions(root, files):
    """{function name: (layer, header)} for the functions declared at the start of a line
    in the headers of each layer of experiments/."""
    out = {}
    for rel in files:
        layer = layer_of(rel)
        if not rel.startswith("experiments/") or layer is None or not rel.endswith(".hpp"):
            continue
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
            for line in f:
                m = DECLARATION.match(line)
                if m and m.group(1) not in KEYWORDS and not line.lstrip().startswith(("//", "#", "return")):
                    out.setdefault(m.group(1), (layer, rel))
    return out


def upward_calls(root, files):
    """A problem line per call, in a file of experiments/, of a function that only a header
    of a higher layer declares."""
    declared = declared_functions(root, files)
    names = {n: v for n, v in declared.items() if v[0] > 0}
    if not names:
        return []
    pattern = re.compile(r"\b(" + "|".join(sorted(map(re.escape, names), key=len, reverse=True)) + r")\s*\(")
    problems = []
    for rel in files:
        layer = layer_of(rel)
        if not rel.startswith("experiments/") or layer is None or layer >= TOP:
            continue
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
            for no, line in enumerate(f, 1):
                code = line.split("//")[0]
                for m in pattern.finditer(code):
                    owner, header = names[m.group(1)]
                    lower_decl = [other_rel for other_rel in files
                                  if other_rel.startswith("experiments/") and layer_of(other_rel) is not None
                                  and layer_of(other_rel) <= layer and other_rel.endswith(".hpp")
                                  and m.group(1) in declared_in(root, other_rel)]
                    if owner > layer and not lower_decl:
                        problems.append(f"{rel}:{no}: {layer_name(layer)} calls {m.group(1)}(), declared in "
                                        f"{header} of the higher layer {layer_name(owner)}")
    return problems


DEFINITION = re.compile(r"^(?!static\b)[A-Za-z_][\w:<>,&*\s]*?[\s&*]([A-Za-z_]\w*)\s*\([^;]*$")


def defined_upward(root, files):
    """A problem line per function declared in a header of one layer and defined (at the start
    of a line, not static) in a .cpp of a higher layer."""
    declared = {}
    for rel in files:
        layer = layer_of(rel)
        if rel.startswith("experiments/") and layer is not None and rel.endswith(".hpp"):
            for name in declared_in(root, rel):
                declared.setdefault(name, []).append((layer, rel))
    problems = []
    for rel in files:
        layer = layer_of(rel)
        if not rel.startswith("experiments/") or layer is None or not rel.endswith(".cpp"):
            continue
        depth, anonymous = 0, []  # brace depth; depths at which anonymous namespaces opened
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
            for no, line in enumerate(f, 1):
                code = line.split("//")[0]
                if re.match(r"^\s*namespace\s*\{", code):
                    anonymous.append(depth)
                m = DEFINITION.match(line) if not anonymous else None
                depth += code.count("{") - code.count("}")
                while anonymous and depth <= anonymous[-1]:
                    anonymous.pop()
                if not m or m.group(1) in KEYWORDS:
                    continue
                homes = declared.get(m.group(1), [])
                if homes and all(l < layer for l, _ in homes):
                    low, header = min(homes)
                    problems.append(f"{rel}:{no}: {m.group(1)}() is declared in {header} ({layer_name(low)}) "
                                    f"but defined in the higher layer {layer_name(layer)}")
    return problems


ROLES = {"tableaus": 0, "system": 0, "core": 1, "schemes": 2, "baselines": 2, "registry": 3, "ensemble": 3}
ROLE_INCLUDE = re.compile(r'^\s*#\s*include\s*"integrators/([^"/]+)/[^"]*"')


def integrator_roles(root, files):
    """A problem line per file of integrators/ outside the role folders, and per include of a
    header of a higher role (ROLES)."""
    problems = []
    for rel in files:
        parts = rel.split("/")
        if parts[0] != "integrators":
            continue
        if len(parts) == 2 or parts[1] not in ROLES:
            problems.append(f"{rel}:1: in no role folder of integrators/ ({', '.join(r + '/' for r in ROLES)})")
            continue
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
            for no, line in enumerate(f, 1):
                m = ROLE_INCLUDE.match(line)
                if m and ROLES.get(m.group(1), -1) > ROLES[parts[1]]:
                    problems.append(f'{rel}:{no}: integrators/{parts[1]}/ includes "integrators/{m.group(1)}/..." '
                                    f"of the higher role {m.group(1)}/")
    return problems


_DECLARED = {}


def declared_in(root, rel):
    """The function names declared at the start of a line in one header (cached)."""
    if rel not in _DECLARED:
        names = set()
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
            for line in f:
                m = DECLARATION.match(line)
                if m and m.group(1) not in KEYWORDS:
                    names.add(m.group(1))
        _DECLARED[rel] = names
    return _DECLARED[rel]


def find_cycles(graph):
    """One cycle (a list of nodes, first == last) per strongly connected
    component that has one (Tarjan's algorithm, iterative)."""
    index, low, on_stack, stack, sccs = {}, {}, set(), [], []
    counter = 0
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph.get(start, ()))))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            advanced = False
            for child in children:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                    advanced = True
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                scc = []
                while True:
                    n = stack.pop()
                    on_stack.discard(n)
                    scc.append(n)
                    if n == node:
                        break
                if len(scc) > 1 or node in graph.get(node, ()):
                    sccs.append(set(scc))
    cycles = []
    for scc in sccs:
        first = min(scc)
        # Shortest path back to `first` inside the component (breadth first).
        prev, queue, found = {first: None}, [first], None
        while queue and found is None:
            nxt = []
            for n in queue:
                for c in sorted(graph.get(n, ())):
                    if c == first:
                        found = n
                        break
                    if c in scc and c not in prev:
                        prev[c] = n
                        nxt.append(c)
                if found is not None:
                    break
            queue = nxt
        path, n = [], found
        while n is not None:
            path.append(n)
            n = prev[n]
        cycles.append(list(reversed(path)) + [first])
    return cycles


def main(argv):
    if len(argv) > 1 and argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0
    root = os.path.abspath(argv[1] if len(argv) > 1 else os.path.join(os.path.dirname(THIS), ".."))
    if not os.path.isdir(os.path.join(root, "experiments")):
        print(f"check_layers: {root}: no experiments/ folder", file=sys.stderr)
        return 2
    problems, graph, lines, n_includes = [], {}, {}, 0
    files = cxx_files(root)
    for rel in files:
        layer = layer_of(rel)
        if layer is None:
            problems.append(f"{rel}:1: in no layer of experiments/ ({', '.join(l + '/' for l in LAYERS)})")
        for no, target, written in includes(root, rel):
            n_includes += 1
            if not os.path.isfile(os.path.join(root, target)):
                problems.append(f'{rel}:{no}: includes "{written}", which does not exist')
                continue
            if rel.startswith("experiments/"):
                graph.setdefault(rel, set()).add(target)
                lines.setdefault((rel, target), no)
            to = layer_of(target)
            if layer is None:
                continue
            if to is None:
                problems.append(f'{rel}:{no}: includes "{written}", which is in no layer')
            elif to > layer:
                problems.append(f'{rel}:{no}: {layer_name(layer)} includes "{written}" of the higher layer '
                                f"{layer_name(to)}")
    for cycle in find_cycles(graph):
        problems.append(f"{cycle[0]}:{lines[(cycle[0], cycle[1])]}: include cycle: {' -> '.join(cycle)}")
    problems += upward_calls(root, files)
    problems += defined_upward(root, files)
    problems += integrator_roles(root, files)
    return report(problems, f"check_layers: {len(problems)} violation(s) in {len(files)} files",
                  f"check_layers: {len(files)} files, {n_includes} includes of experiments/, layering clean")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
