#!/usr/bin/python3
"""Quantum spacing statistics beside the classical chaotic fraction, top by top
(experiments/QUANTUM.md "Measured", the comparison of four tops).

Usage: quantum_compare.py --out DIR [--name NAME] [--tex FILE] [--markdown FILE]
                          --case LABEL QUANTUM.h5 CHAOS.h5 [--case ...]

Each case is one top: QUANTUM.h5 from `lgi quantum --statistics --energy-window
LO:HI` at l = m hbar, CHAOS.h5 from `lgi chaos-map` at the same l over h in
[LO, HI]. The classical fraction is all chaotic orbits over all orbits of the
computed cells (the cells equally weighted, so h uniformly), with its 95 % Wilson
interval. The quantum side is the /statistics group: the spacings of every
symmetry class (each unfolded by its share of Weyl's law) pooled, their Brody
fit (the group's pooled_brody_* attributes) and Delta_3(L) averaged over the
classes (weighted by their levels). A window whose top lies above the highest
converged level is marked "cut" (fewer levels than the window holds).
Writes DIR/NAME.{pdf,png} (default NAME: quantum_compare): one panel per top
with its spacing histogram against Poisson, GOE and GUE, and a last panel with
the Brody parameter against the chaotic fraction; --tex writes the table as a
LaTeX tabular, --markdown the same table in Markdown.
"""
import math

import numpy as np

import lgi_plot_common as c


def wilson(k, n, z=1.959963984540054):
    """The 95 % Wilson score interval of k successes in n trials."""
    if n == 0:
        return float("nan"), float("nan")
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return max(0.0, centre - half), min(1.0, centre + half)


def classical(path):
    t = c.load_table(path, "chaos_map")
    if t is None:
        c.die(f"{path}: no /chaos_map group (give a file of lgi chaos-map)")
    ok = t["status"] == 0
    k, n = int(np.sum(t["chaotic"][ok])), int(np.sum(t["orbits"][ok]))
    lo, hi = wilson(k, n)
    return {"chaotic": k, "orbits": n, "fraction": k / n if n else float("nan"), "low": lo, "high": hi,
            "l": t["l"], "h": t["h"], "cells": int(np.count_nonzero(ok))}


def quantum(path):
    t = c.load_table(path, "statistics")
    if t is None:
        c.die(f"{path}: no /statistics group (give a file of lgi quantum --statistics)")
    a = c.load_attrs(path, "statistics")
    spec = c.load_table(path, "spectrum")
    pa = c.load_attrs(path, "parameters")
    ok = (t["levels"] >= 3) & np.all(np.isfinite(t["spacing_density"]), axis=1)
    if not np.any(ok):
        c.die(f"{path}: no class has enough levels in the window")
    w = t["levels"][ok] - 1
    top = float(np.max(spec["energy"][spec["converged"] == 1]))
    complex_h = pa.get("representation", "") == "complex hermitian"
    m = int(spec["m"][0])
    return {
        "hbar": float(pa.get("hbar", "nan")), "m": m,
        "low": float(a["energy_low"]), "high": float(a["energy_high"]),
        "cut": top < float(a["energy_high"]),
        "levels": int(np.sum(t["levels"][ok])), "classes": int(np.count_nonzero(ok)),
        "beta": float(a["pooled_brody_beta"]), "beta_error": float(a["pooled_brody_error"]),
        "spacings": int(a["pooled_spacings"]),
        "centres": t["bin_centre"], "density": np.average(t["spacing_density"][ok], axis=0, weights=w),
        "length": t["length"], "rigidity": np.average(t["rigidity"][ok], axis=0, weights=t["levels"][ok]),
        "poisson_rigidity": t["poisson_rigidity"], "goe_rigidity": t["goe_rigidity"],
        "gue_rigidity": t["gue_rigidity"], "ensemble": "GUE" if complex_h and m != 0 else "GOE",
    }


def at_length(q, key, length):
    i = int(np.argmin(np.abs(q["length"] - length)))
    return float(q[key][i])


def brody(s, beta):
    b = math.gamma((beta + 2) / (beta + 1)) ** (beta + 1)
    return (beta + 1) * b * s ** beta * np.exp(-b * s ** (beta + 1))


def draw_case(ax, label, q, k):
    width = q["centres"][1] - q["centres"][0]
    ax.bar(q["centres"], q["density"], width=width, color="0.82", edgecolor="0.5", lw=0.4,
           label=f"{q['spacings']} spacings")
    s = np.linspace(1e-4, q["centres"][-1] + width / 2, 400)
    ax.plot(s, np.exp(-s), "--", color="tab:blue", label="Poisson")
    ax.plot(s, np.pi / 2 * s * np.exp(-np.pi * s ** 2 / 4), "-.", color="tab:red", label="GOE")
    ax.plot(s, 32 / np.pi ** 2 * s ** 2 * np.exp(-4 * s ** 2 / np.pi), ":", color="tab:purple", lw=1.4, label="GUE")
    ax.plot(s, brody(s, q["beta"]), "-", color="k", lw=1.0, label=f"Brody $\\beta$ = {q['beta']:.2f}")
    ax.set_title(f"{label}: chaotic {k['fraction']:.2f}", fontsize=9)
    ax.set_xlabel("$s$")
    ax.set_ylabel("$P(s)$")
    ax.set_xlim(0, 3.5)
    ax.legend(frameon=False, fontsize=6.5)


def draw_summary(ax, cases):
    for i, (label, q, k) in enumerate(cases):
        colour = c.plt.get_cmap("tab10")(i)
        ax.errorbar([k["fraction"]], [q["beta"]], xerr=[[max(0.0, k["fraction"] - k["low"])], [max(0.0, k["high"] - k["fraction"])]],
                    yerr=[q["beta_error"]], fmt="o", ms=4, color=colour, capsize=2, label=label)
    ax.set_xlim(-0.05, 1.05)
    ax.set_ylim(-0.05, 1.15)
    ax.set_xlabel("classical chaotic fraction")
    ax.set_ylabel("Brody $\\beta$ (pooled classes)")
    ax.set_title("quantum against classical", fontsize=9)
    ax.legend(frameon=False, fontsize=6.5, loc="center")


def rows(cases):
    out = []
    for label, q, k in cases:
        out.append({
            "top": label, "window": f"{q['low']:g}..{q['high']:g}" + (" (cut)" if q["cut"] else ""),
            "hbar_m": f"{q['hbar']:g}, {q['m']}",
            "fraction": f"{k['fraction']:.3f} [{k['low']:.3f}, {k['high']:.3f}] ({k['chaotic']}/{k['orbits']})",
            "levels": f"{q['levels']} in {q['classes']}",
            "beta": f"{q['beta']:.2f} ± {q['beta_error']:.2f}",
            "d3": f"{at_length(q, 'rigidity', 10):.3f}" if np.isfinite(at_length(q, 'rigidity', 10)) else "–",
            "refs": f"{at_length(q, 'poisson_rigidity', 10):.3f}, {at_length(q, 'goe_rigidity', 10):.3f}, "
                    f"{at_length(q, 'gue_rigidity', 10):.3f}",
            "ensemble": q["ensemble"],
        })
    return out


HEAD = ["top", "h window", "ħ, m", "chaotic fraction [95 %] (orbits)", "levels in classes", "Brody β",
        "Δ₃(10)", "Δ₃(10) Poisson, GOE, GUE", "RMT class"]
KEYS = ["top", "window", "hbar_m", "fraction", "levels", "beta", "d3", "refs", "ensemble"]


def markdown(table):
    lines = ["| " + " | ".join(HEAD) + " |", "|" + " --- |" * len(HEAD)]
    lines += ["| " + " | ".join(r[k] for k in KEYS) + " |" for r in table]
    return "\n".join(lines) + "\n"


def tex(table, cases):
    """A complete tabular: one row per top, and the reference values of Delta_3(10) below."""
    def cell(v):
        for a, b in (("±", "$\\pm$"), ("..", "--"), ("%", "\\%"), ("nan", "--"), ("–", "--")):
            v = v.replace(a, b)
        return v
    keys = ["top", "hbar_m", "window", "fraction", "levels", "beta", "d3", "ensemble"]
    head = ["top", "$\\hbar$, $m$", "$h$", "chaotic fraction [95\\,\\%] (orbits)", "levels in classes",
            "Brody $\\beta$", "$\\Delta_3(10)$", "RMT"]
    lines = ["\\begin{tabular}{llllllll}", " & ".join(head) + " \\\\", "\\hline"]
    lines += [" & ".join(cell(r[k]) for k in keys) + " \\\\" for r in table]
    q = cases[0][1]
    refs = ", ".join(f"{at_length(q, k, 10):.3f}" for k in ("poisson_rigidity", "goe_rigidity", "gue_rigidity"))
    lines += ["\\hline", f"\\multicolumn{{6}}{{r}}{{$\\Delta_3(10)$ of Poisson, GOE, GUE:}} & "
              f"\\multicolumn{{2}}{{l}}{{{refs}}} \\\\", "\\end{tabular}"]
    return "\n".join(lines) + "\n"


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--name", default="quantum_compare", help="file name of the figure, without extension")
    p.add_argument("--case", nargs=3, action="append", metavar=("LABEL", "QUANTUM", "CHAOS"), required=True,
                   help="one top: its label, its lgi quantum --statistics file and its lgi chaos-map file")
    p.add_argument("--tex", help="write the table as a LaTeX tabular to this file")
    p.add_argument("--markdown", help="write the table in Markdown to this file")
    args = p.parse_args()
    if args.files:
        c.die("give the files with --case LABEL QUANTUM.h5 CHAOS.h5")
    cases = [(label, quantum(qf), classical(cf)) for label, qf, cf in args.case]
    n = len(cases) + 1
    cols = min(n, 3)
    nrows = (n + cols - 1) // cols
    fig, axes = c.plt.subplots(nrows, cols, figsize=(2.45 * cols, 2.3 * nrows), constrained_layout=True)
    axes = np.atleast_1d(axes).ravel()
    for ax, (label, q, k) in zip(axes, cases):
        draw_case(ax, label, q, k)
    draw_summary(axes[len(cases)], cases)
    for ax in axes[n:]:
        ax.set_visible(False)
    c.save(fig, args.out, args.name)
    table = rows(cases)
    if args.tex:
        with open(args.tex, "w") as f:
            f.write(tex(table, cases))
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(markdown(table))
    print(markdown(table), end="")


if __name__ == "__main__":
    main()
