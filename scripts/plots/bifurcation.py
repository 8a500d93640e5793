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


def main():
    args = c.parser(__doc__.split("\n\n")[0]).parse_args()
    if not args.files:
        c.die("give at least one file written by lgi bifurcation")
    for path in args.files:
        with c.h5py.File(path, "r") as f:
            t = {k: np.asarray(f["equilibria"][k][()]) for k in f["equilibria"]}
            J, w, name = body(f)
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
