#!/usr/bin/python3
"""The quantum top's semiclassics and statistics from `lgi quantum` files
(experiments/QUANTUM.md): (a) EBK against exact levels of the Lagrange top,
(c) EBK of the Euler top and (b) the spacing distribution beside the Brody,
Poisson, GOE and GUE curves.

Usage: quantum.py --out DIR [--name NAME] FILE.h5 ...

Files with /ebk (`lgi quantum --ebk`, one per hbar) make panel (a): the levels
E_exact against E_EBK, and (E_EBK - E_exact)/hbar^2 against E_exact, which
collapse onto one curve where the error is second order (docs/quantum.md
section 7). Files with /ebk of a free body (`lgi quantum --ebk` on a free_body
scene, one j each) make panel (c): the relative error divided by
(hbar/|L|)^2, |L| = hbar (j + 1/2), against E/|L|^2, which collapses onto one
curve away from the separatrix (docs/quantum.md section 9). Files with /statistics (`lgi quantum --statistics`) make panel (b): the
spacing histogram of all their classes pooled (weighted by their spacings), with
Brody's P(s) at the pooled maximum-likelihood beta (the classes' estimates
averaged by inverse variance), e^{-s}, Wigner's surmise (GOE) and the GUE
surmise (32/pi^2) s^2 e^{-4 s^2/pi} (the class of a top whose Hamiltonian has
no antiunitary symmetry, docs/quantum.md section 3).
Writes DIR/NAME.{pdf,png} (default NAME: quantum).
"""
import math

import numpy as np

import lgi_plot_common as c


def brody(s, beta):
    b = math.gamma((beta + 2) / (beta + 1)) ** (beta + 1)
    return (beta + 1) * b * s ** beta * np.exp(-b * s ** (beta + 1))


def hbar_of(path):
    return float(c.load_attrs(path, "parameters").get("hbar", "nan"))


def draw_ebk(ax_levels, ax_error, files):
    for k, path in enumerate(files):
        t = c.load_table(path, "ebk")
        h = hbar_of(path)
        colour = c.plt.get_cmap("viridis")(k / max(len(files) - 1, 1))
        ax_levels.plot(t["energy_ebk"], t["energy_exact"], "o", ms=3, color=colour, label=f"$\\hbar$ = {h:g}")
        ax_error.plot(t["energy_exact"], t["difference"] / h ** 2, "o", ms=3, color=colour, label=f"$\\hbar$ = {h:g}")
    lo, hi = ax_levels.get_xlim()
    ax_levels.plot([lo, hi], [lo, hi], color="0.5", lw=0.6)
    ax_levels.set_xlabel("$E_{\\mathrm{EBK}}$")
    ax_levels.set_ylabel("$E_{\\mathrm{exact}}$")
    ax_levels.set_title("(a) Lagrange top: EBK against exact")
    ax_levels.legend(frameon=False)
    ax_error.set_xlabel("$E_{\\mathrm{exact}}$")
    ax_error.set_ylabel("$(E_{\\mathrm{EBK}} - E_{\\mathrm{exact}})/\\hbar^2$")
    ax_error.set_title("(a') the error is second order")


def is_free(path):
    t = c.load_table(path, "ebk")
    return "j" in t and bool(np.all(t["j"] >= 0))


def draw_euler(ax, files):
    moments = sorted(float(x) for x in str(c.load_attrs(files[0], "parameters").get("moments", "nan nan nan"))
                     .replace(",", " ").strip("[]() ").split())
    sep = 0.5 / moments[1]  # the separatrix energy over |L|^2, 1/(2 J_mid)
    far = []
    for k, path in enumerate(files):
        t = c.load_table(path, "ebk")
        h = hbar_of(path)
        L = h * (t["j"][0] + 0.5)
        colour = c.plt.get_cmap("plasma")(0.85 * k / max(len(files) - 1, 1))
        rel = t["difference"] / t["energy_exact"] / (h / L) ** 2
        ax.plot(t["energy_exact"] / L ** 2, rel, "o", ms=2.5, color=colour, label=f"$j$ = {t['j'][0]}")
        far.extend(rel[np.isfinite(rel) & (np.abs(t["energy_exact"] / L ** 2 - sep) > 0.05)])
    ax.axvline(sep, color="0.5", lw=0.6, ls="--")
    if far:  # frame the tori away from the separatrix, where the error is O(hbar^2)
        lo, hi = min(min(far), 0.0), max(max(far), 0.0)
        ax.set_ylim(lo - 0.5 * (hi - lo), hi + 0.5 * (hi - lo))
    ax.set_xlabel("$E/|L|^2$")
    ax.set_ylabel("$(E_{\\mathrm{EBK}}/E_{\\mathrm{exact}} - 1)\\,(|L|/\\hbar)^2$")
    ax.set_title("(c) Euler top at $|L| = \\hbar(j + 1/2)$")
    ax.legend(frameon=False, fontsize=7)


def draw_spacings(ax, files):
    density, weights, betas, errors, centres, width = [], [], [], [], None, None
    for path in files:
        t = c.load_table(path, "statistics")
        centres = t["bin_centre"]
        width = centres[1] - centres[0]
        for i in range(len(t["levels"])):
            if t["levels"][i] < 3 or not np.all(np.isfinite(t["spacing_density"][i])):
                continue
            density.append(t["spacing_density"][i])
            weights.append(t["levels"][i] - 1)
            betas.append(t["brody_beta"][i])
            errors.append(t["brody_error"][i])
    if not density:
        c.die("no class with statistics in the /statistics files given")
    pooled = np.average(np.array(density), axis=0, weights=weights)
    inv = 1.0 / np.array(errors) ** 2
    beta = float(np.sum(inv * np.array(betas)) / np.sum(inv))
    ax.bar(centres, pooled, width=width, color="0.8", edgecolor="0.5", lw=0.4,
           label=f"levels ({sum(weights)} spacings)")
    s = np.linspace(1e-4, centres[-1] + width / 2, 400)
    ax.plot(s, np.exp(-s), "--", color="tab:blue", label="Poisson")
    ax.plot(s, np.pi / 2 * s * np.exp(-np.pi * s ** 2 / 4), "-.", color="tab:red", label="GOE (Wigner)")
    ax.plot(s, 32 / np.pi ** 2 * s ** 2 * np.exp(-4 * s ** 2 / np.pi), ":", color="tab:purple", lw=1.4,
            label="GUE")
    ax.plot(s, brody(s, beta), "-", color="k", label=f"Brody, $\\beta$ = {beta:.2f}")
    ax.set_xlabel("$s$")
    ax.set_ylabel("$P(s)$")
    ax.set_title("(b) nearest-neighbour spacings")
    ax.legend(frameon=False)


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--name", default="quantum", help="file name of the figure, without extension")
    args = p.parse_args()
    ebk_all = [f for f in args.files if c.load_table(f, "ebk") is not None]
    euler = sorted((f for f in ebk_all if is_free(f)), key=hbar_of, reverse=True)
    ebk = [f for f in ebk_all if f not in euler]
    stats = [f for f in args.files if c.load_table(f, "statistics") is not None]
    if not ebk_all and not stats:
        c.die("give files written by lgi quantum --ebk or --statistics")
    panels = (2 if ebk else 0) + (1 if euler else 0) + (1 if stats else 0)
    fig, axes = c.plt.subplots(1, panels, figsize=(3.3 * panels, 3.0), constrained_layout=True)
    axes = list(np.atleast_1d(axes))
    if ebk:
        draw_ebk(axes.pop(0), axes.pop(0), sorted(ebk, key=hbar_of, reverse=True))
    if euler:
        draw_euler(axes.pop(0), euler)
    if stats:
        draw_spacings(axes.pop(0), stats)
    c.save(fig, args.out, args.name)


if __name__ == "__main__":
    main()
