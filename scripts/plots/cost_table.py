"""Cost at equal error, from lgi work-precision files: the CPU time at which a
scheme's work-precision curve reaches a target error, and the paper's table of
the cheapest scheme of each family at 1e-6, 1e-8 and 1e-10 on every heavy-top
scene (imported by make_tables.py)."""
import numpy as np

import lgi_plot_common as c

COST_TARGETS = (1e-6, 1e-8, 1e-10)
CAP_COST = ("Cost at equal error: per heavy-top scene and scheme family, the cheapest scheme and its CPU time "
            "(minimum over the timed repeats, log-log interpolated between the runs that bracket the target) "
            "to reach a global error of $10^{-6}$, $10^{-8}$ and $10^{-10}$ at $t_{\\mathrm{end}}$; "
            "compositions count with the family of their base method, baselines by chart. A dash: no run "
            "of the family reached the error. Produced by \\texttt{scripts/plots/make\\_tables.py} from the "
            "\\texttt{lgi work-precision} files of Figure~\\ref{fig:wp}.")


def breakable(name):
    """A scheme name with a permitted line break after each "@" and "/" (TeX never
    hyphenates typewriter type: a composition's or a baseline's name may then
    break in a narrow column or a sentence; make_tables.tt uses it too)."""
    return name.replace("@", "@\\allowbreak{}").replace("/", "/\\allowbreak{}")


def cpu_at_error(errs, cpus, target):
    """CPU time at which one scheme's work-precision curve reaches `target`:
    log-log interpolation between the bracketing runs (ordered by CPU time),
    or the cheapest run below target if none is above it; None if no run reaches it."""
    pts = sorted((cp, e) for e, cp in zip(errs, cpus) if np.isfinite(e) and np.isfinite(cp) and e > 0 and cp > 0)
    below = [cp for cp, e in pts if e <= target]
    if not below:
        return None
    best = min(below)
    for (c0, e0), (c1, e1) in zip(pts, pts[1:]):
        if e0 > target >= e1 and e0 != e1:
            w = np.log(e0 / target) / np.log(e0 / e1)
            best = min(best, float(np.exp(np.log(c0) + w * np.log(c1 / c0))))
    return best


def family_of(name, info):
    """The family a scheme counts in, from its `lgi schemes --json` facts (`info`),
    never its name: its registry family; a composition ("kind" "composition"),
    its "base" scheme's; a baseline's family names its chart ("baseline quat")."""
    facts = {s["name"]: s for s in info}
    s = facts.get(name, {})
    if s.get("kind") == "composition" and s.get("base") in facts:
        s = facts[s["base"]]
    return s.get("family") or "other"


def is_heavy_top(path):
    """A work-precision file whose scene has gravity and no other torque."""
    toml = c.load_attrs(path, "parameters").get("scene_toml", "")
    return "[gravity]" in toml and not any(k in toml for k in ("[spring]", "[drive]", "[magnetic]", "[damper]"))


def cost_rows(load, files, info, cpu_column="cpu_seconds_min"):
    """Rows of the cost table (scene, family, then per target "scheme ms"), from the
    heavy-top files among `files`; `load` is make_tables.load_work_precision."""
    rows = []
    kinds = {s["name"]: s.get("kind") for s in info}
    for p in files:
        if not is_heavy_top(p):
            continue
        tab, scene, ok = load(p)
        cpu = tab[cpu_column] if cpu_column in tab else tab["cpu_seconds_median"]
        best = {}  # family -> [(seconds, scheme) per target]
        baseline_families = set()
        for name in dict.fromkeys(tab["scheme"]):
            sel = np.array([x == name for x in tab["scheme"]]) & ok
            fam = family_of(name, info)
            if kinds.get(name) == "baseline":
                baseline_families.add(fam)
            cells = best.setdefault(fam, [None] * len(COST_TARGETS))
            for k, target in enumerate(COST_TARGETS):
                v = cpu_at_error(tab["error"][sel], cpu[sel], target)
                if v is not None and (cells[k] is None or v < cells[k][0]):
                    cells[k] = (v, name)
        first = True
        for fam in sorted(best, key=lambda f: (f in baseline_families, f)):
            cells = ["--" if cell is None else f"\\texttt{{{breakable(cell[1])}}} {cell[0] * 1e3:.3g}" for cell in best[fam]]
            label = f"\\texttt{{{scene.replace('_', ' ')}}}" if first else ""
            rows.append(f"{label} & {fam} & " + " & ".join(cells) + " \\\\")
            first = False
        rows.append("\\midrule")
    if rows:
        rows.pop()
    return rows
