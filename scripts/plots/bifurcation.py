#!/usr/bin/python3
"""The (l, h) bifurcation diagram of a heavy top from `lgi bifurcation` files
(experiments/EQUILIBRIA.md: /equilibria, every branch of relative equilibria).

Usage: bifurcation.py --out DIR BRANCHES.h5 ...   (one file per scene)

Writes DIR/bifurcation_<scene stem>.{pdf,png}: h against l along every branch,
coloured by Grammel's stability class (docs/atlas.md §3), folds (the cusps)
marked. Where the scene is integrable in closed form the known critical sets
are drawn under the branches as grey dashes: the free body's principal-axis
rotations h = l²/(2A_i), and the Lagrange top's carrousels and sleeping top
(docs/atlas.md §5).

A file of `lgi bifurcation --appelrot L,...` (a Kovalevskaya top) also gives
DIR/appelrot_<file stem>.{pdf,png}: the (h, k) diagram at each l, in the scaled
values h/(J3 c) and k = K/c² (docs/atlas.md §9): the Appelrot families (k = 0,
k = (h − l²/2)², the parametric family, and at l = 0 the line k = 1 + h²), the
range of k on the energy surfaces found by lgi (grey: where orbits exist) and the
relative equilibria (black dots).
"""
import os
import tomllib

import numpy as np

import lgi_plot_common as c

CLASSES = {0: ("linearly stable", "tab:blue"), 1: ("singly unstable", "tab:red"),
           2: ("doubly unstable", "tab:purple"), 3: ("complex unstable", "tab:orange")}


def body(f):
    """J (diagonal as given), m g chi, from the scene text stored in the file."""
    scene = tomllib.loads(c.attrs(f["parameters"])["scene_toml"])
    b = scene["body"]
    J = np.array(b.get("inertia", b.get("inertia_cm", [1, 1, 1])), dtype=float)
    g = scene.get("gravity", {}).get("g", 9.81) if "gravity" in scene else 0.0
    chi = np.array(b.get("center_of_mass", [0, 0, 0]), dtype=float)
    return J, b.get("mass", 0.0) * g * chi, scene.get("name", "")


def overlays(ax, J, w, lmax):
    l = np.linspace(-lmax, lmax, 400)
    if not np.any(w):  # Euler: rotations about the principal axes
        for A in J:
            ax.plot(l, l * l / (2 * A), color="0.6", ls="--", lw=0.8, zorder=1)
        return
    A, C, z = J[0], J[2], w[2]
    if J[0] == J[1] and w[0] == 0 and w[1] == 0 and C != A:  # Lagrange
        ax.plot(l, l * l / (2 * C) + z, color="0.6", ls="--", lw=0.8, zorder=1)   # sleeping, upright
        ax.plot(l, l * l / (2 * C) - z, color="0.6", ls="--", lw=0.8, zorder=1)   # sleeping, hanging
        u = np.concatenate([np.linspace(-0.999, -1e-3, 400), np.linspace(1e-3, 0.999, 400)])
        a = A + (C - A) * u * u
        l2 = z * a * a / ((C - A) * u)
        ok = l2 >= 0
        h = z * (a / (2 * (C - A) * u) + u)
        for s in (1, -1):
            ax.plot(s * np.sqrt(l2[ok]), h[ok], color="0.6", ls="--", lw=0.8, zorder=1)


FAMILIES = {0: ("k = 0", "tab:blue"), 1: ("$k = (h - \\ell^2/2)^2$", "tab:red"),
            2: ("parametric family", "tab:green"), 3: ("$k = 1 + h^2$ ($\\ell = 0$)", "tab:purple")}


def appelrot_figure(f, stem, out):
    """The Kovalevskaya (h, k) diagram at each l of the file (scaled values)."""
    cur = {k: np.asarray(f["appelrot"][k][()]) for k in f["appelrot"]}
    eq = {k: np.asarray(f["appelrot_equilibria"][k][()]) for k in f["appelrot_equilibria"]}
    rng = {k: np.asarray(f["appelrot_range"][k][()]) for k in f["appelrot_range"]}
    ls = np.unique(cur["l"])
    cols = min(3, len(ls))
    rows = (len(ls) + cols - 1) // cols
    fig, axes = c.plt.subplots(rows, cols, figsize=(3.2 * cols, 2.8 * rows), squeeze=False)
    for ax, l in zip(axes.ravel(), ls):
        r = rng["l"] == l
        for comp in np.unique(rng["component"][r]):
            sel = r & (rng["component"] == comp)
            ax.fill_between(rng["h_scaled"][sel], rng["k_min"][sel], rng["k_max"][sel], color="0.82", lw=0,
                            label="range of k" if comp == 0 else None)
        kmax = rng["k_max"][r].max() if np.any(r) else 4.0
        for fam, (label, colour) in FAMILIES.items():
            for branch in (-1, 0, 1):
                sel = (cur["l"] == l) & (cur["family"] == fam) & (cur["branch"] == branch)
                if np.any(sel):
                    order = np.argsort(cur["s"][sel])
                    ax.plot(cur["h_scaled"][sel][order], cur["k"][sel][order], color=colour, lw=0.9,
                            label=label if branch != 1 or fam != 2 else None)
        e = eq["l"] == l
        ax.plot(eq["h_scaled"][e], eq["k"][e], "ko", ms=3, label="relative equilibria")
        ax.set_xlim(cur["h_scaled"].min(), cur["h_scaled"].max())
        ax.set_ylim(-0.05 * kmax, 1.1 * kmax)
        ax.set_xlabel("$h / (J_3 c)$")
        ax.set_ylabel("$k = K / c^2$")
        ax.set_title(f"$\\ell$ = {l:g} (scaled {cur['l_scaled'][cur['l'] == l][0]:.3g})", fontsize=8)
    for ax in axes.ravel()[len(ls):]:
        ax.axis("off")
    axes.ravel()[0].legend(fontsize=6, loc="upper left")
    fig.tight_layout()
    c.save(fig, out, f"appelrot_{stem}")


def main():
    args = c.parser(__doc__.split("\n\n")[0]).parse_args()
    if not args.files:
        c.die("give at least one file written by lgi bifurcation")
    for path in args.files:
        with c.h5py.File(path, "r") as f:
            t = {k: np.asarray(f["equilibria"][k][()]) for k in f["equilibria"]}
            J, w, name = body(f)
            if "appelrot" in f:
                appelrot_figure(f, os.path.splitext(os.path.basename(path))[0], args.out)
        fig, ax = c.plt.subplots(figsize=(4.6, 3.4))
        lmax = np.percentile(np.abs(t["l"]), 90) if len(t["l"]) else 1.0
        overlays(ax, J, w, lmax)
        for b in np.unique(t["branch"]):
            sel = (t["branch"] == b) & (t["fold"] == 0)
            l, h, s = t["l"][sel], t["h"][sel], t["stability"][sel]
            for k in range(len(l) - 1):
                ax.plot(l[k:k + 2], h[k:k + 2], color=CLASSES[int(s[k])][1], lw=1.2, zorder=2)
        folds = t["fold"] == 1
        ax.plot(t["l"][folds], t["h"][folds], "k^", ms=4, zorder=3, label="fold")
        for k, (label, colour) in CLASSES.items():
            ax.plot([], [], color=colour, label=label)
        ax.set_xlim(-lmax, lmax)
        hs = t["h"][np.abs(t["l"]) <= lmax]
        if len(hs):
            ax.set_ylim(hs.min() - 0.05 * np.ptp(hs), np.percentile(hs, 90))
        ax.set_xlabel("$\\ell = \\Pi\\cdot\\Gamma$")
        ax.set_ylabel("$h$")
        ax.set_title(name, fontsize=8)
        ax.legend(loc="upper center", fontsize=6.5, ncol=3)
        stem = os.path.splitext(os.path.basename(path))[0]
        c.save(fig, args.out, f"bifurcation_{stem}")


if __name__ == "__main__":
    main()
