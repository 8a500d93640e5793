#!/usr/bin/python3
"""Energy surfaces in action representation from `lgi actions --h H` files
(experiments/ACTIONS.md: /tori with method, actions, h, frequencies, ...).

Usage: actions.py --out DIR [--name NAME] ACTIONS.h5 ...

Every file becomes one 3-D panel of DIR/NAME.{pdf,png} (default NAME: actions), side
by side as on the slide "Energy surfaces in action representation" of Richter's
colloquium (seed 003, docs/sources.md): the Lagrange top's closed-form tori as the
surface (l, L3, I_theta) over the (l, L3) grid, the Euler top's as (l, G, I_l), and
numerical tori (any top, e.g. Kovalevskaya) as a surface (l, I_a, I_b) too: at each l
the tori are chained into a curve (nearest neighbours from the torus of least I_a,
broken where a step is much longer than the typical one, e.g. between two families of
tori), and the curves of neighbouring l are joined by triangles between points of equal
fractional arc length. Only tori with ok = 1 are drawn; the tori themselves are shown as
dots, coloured by l; tori cut by different sections (the `section` column) get separate
surfaces, their cycles being different. Numerical tori are drawn in the basis whose rotation number is in
(-1/2, 1/2]: cycle b + n a with n = round(rho), I_b + n I_a (the file keeps the basis of
docs/actions.md §3, whose rho is lifted where the section curve winds about the phi-circle).
"""
import numpy as np

import lgi_plot_common as c

BREAK = 4.0  # a step of a chain longer than BREAK times the median step starts a new curve

AXES = {0: ("$\\ell$", "$L_3$", "$I_\\theta$"), 1: ("$\\ell$", "$G$", "$I_l$"), 2: ("$\\ell$", "$I_a$", "$I_b$")}
TITLES = {0: "Lagrange (closed form)", 1: "Euler (closed form)", 2: "numerical tori"}


def read(path):
    t = c.load_table(path, "tori")
    if t is None:
        c.die(f"{path}: no /tori (not a file written by lgi actions)")
    return t, c.load_attrs(path, "parameters")


def chains(P):
    """The points P (n x 2, in (I_a, I_b) scaled) of one l chained by nearest neighbours
    from the one of least I_a; returns index lists, one per curve (a new one after a
    step longer than BREAK times the median step)."""
    left = list(range(len(P)))
    order = [left.pop(int(np.argmin(P[left, 0])))]
    while left:
        d = np.linalg.norm(P[left] - P[order[-1]], axis=1)
        order.append(left.pop(int(np.argmin(d))))
    steps = np.linalg.norm(np.diff(P[order], axis=0), axis=1)
    if not len(steps):
        return [order]
    cut = BREAK * max(np.median(steps), 1e-300)
    out, cur = [], [order[0]]
    for k, s in zip(order[1:], steps):
        if s > cut:
            out.append(cur)
            cur = []
        cur.append(k)
    out.append(cur)
    return out


def ribbon(A, B):
    """Triangles joining two curves A, B (arrays of 3-D points) by fractional arc length."""
    def frac(X):
        s = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(X, axis=0), axis=1))])
        return s / s[-1] if s[-1] > 0 else np.linspace(0, 1, len(X))
    fa, fb = frac(A), frac(B)
    i = j = 0
    tris = []
    while i < len(A) - 1 or j < len(B) - 1:
        if j == len(B) - 1 or (i < len(A) - 1 and fa[i + 1] <= fb[j + 1]):
            tris.append((A[i], A[i + 1], B[j]))
            i += 1
        else:
            tris.append((A[i], B[j + 1], B[j]))
            j += 1
    return tris


def numerical_surface(ax, I):
    """The tori (l, I_a, I_b) as per-l curves joined into a surface (see the module doc)."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection
    ls = np.unique(I[:, 0])
    scale = np.ptp(I[:, 1:], axis=0)
    scale[scale == 0] = 1
    curves = {}
    for l in ls:
        P = I[I[:, 0] == l]
        parts = [P[k] for k in chains(P[:, 1:] / scale) if len(k) >= 2]
        curves[l] = max(parts, key=len) if parts else None
        for part in parts:
            ax.plot(part[:, 0], part[:, 1], part[:, 2], color="0.25", lw=0.6)
    tris = []
    for a, b in zip(ls[:-1], ls[1:]):
        if curves[a] is not None and curves[b] is not None:
            A, B = curves[a], curves[b]
            if np.linalg.norm(A[0, 1:] - B[-1, 1:]) + np.linalg.norm(A[-1, 1:] - B[0, 1:]) < \
                    np.linalg.norm(A[0, 1:] - B[0, 1:]) + np.linalg.norm(A[-1, 1:] - B[-1, 1:]):
                B = B[::-1]
            tris += ribbon(A, B)
    if tris:
        z = np.array([np.mean([p[2] for p in t]) for t in tris])
        cmap = c.plt.get_cmap("viridis")
        colours = cmap((z - z.min()) / max(np.ptp(z), 1e-300))
        ax.add_collection3d(Poly3DCollection(tris, facecolors=colours, edgecolors="0.4", linewidths=0.2, alpha=0.75))
    ax.scatter(I[:, 0], I[:, 1], I[:, 2], c=I[:, 0], cmap="plasma", s=5, depthshade=False)


def draw(ax, t, par):
    keep = t["ok"] == 1
    method = int(t["method"][keep][0]) if keep.any() else 2
    I = t["actions"][keep]
    if method in (0, 1) and len(I) >= 3:
        ax.plot_trisurf(I[:, 0], I[:, 1], I[:, 2], cmap="viridis", linewidth=0.1, antialiased=True, alpha=0.9)
    elif len(I):
        I = I.copy()
        I[:, 0] = np.round(I[:, 0], 9)  # l of the tori is Pi.Gamma of their states: 1e-16 apart
        n = np.round(t["rotation_number"][keep])
        I[:, 2] += n * I[:, 1]
        # Tori cut by different sections have different cycles a: one surface per section.
        sec = t["section"][keep] if "section" in t else np.zeros(len(I), dtype=int)
        for k in np.unique(sec):
            numerical_surface(ax, I[sec == k])
    x, y, z = AXES[method]
    ax.set_xlabel(x)
    ax.set_ylabel(y)
    ax.set_zlabel(z)
    h = par.get("h", "?")
    ax.set_title(f"{c.scene_label(par)}: {TITLES[method]}, h = {float(h):.4g}" if h != "?" else c.scene_label(par),
                 fontsize=8)


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--name", default="actions", help="figure name (without extension)")
    args = p.parse_args()
    if not args.files:
        c.die("give at least one file written by lgi actions --h")
    data = [read(path) for path in args.files]
    # Numerical panels are larger: several sheets, one per section, share them.
    widths = [5.5 if (t["method"] == 2).all() else 3.4 for t, _ in data]
    fig = c.plt.figure(figsize=(sum(widths), 3.2 if max(widths) < 5 else 5.0))
    for i, (t, par) in enumerate(data):
        ax = fig.add_subplot(1, len(data), i + 1, projection="3d")
        draw(ax, t, par)
    fig.tight_layout()
    c.save(fig, args.out, args.name)


if __name__ == "__main__":
    main()
