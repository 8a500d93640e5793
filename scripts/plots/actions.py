#!/usr/bin/python3
"""Energy surfaces in action representation from `lgi actions --h H` files
(experiments/ACTIONS.md: /tori with method, actions, h, frequencies, ...).

Usage: actions.py --out DIR [--name NAME] ACTIONS.h5 ...

Every file becomes one 3-D panel of DIR/NAME.{pdf,png} (default NAME: actions), side
by side as on the slide "Energy surfaces in action representation" of Richter's
colloquium (seed 003, docs/sources.md): the Lagrange top's closed-form tori as the
surface (l, L3, I_theta) over the (l, L3) grid, the Euler top's as (l, G, I_l), and
numerical tori (any top, e.g. Kovalevskaya) as points (l, I_a, I_b) coloured by l.
Only tori with ok = 1 are drawn.
"""
import numpy as np

import lgi_plot_common as c

AXES = {0: ("$\\ell$", "$L_3$", "$I_\\theta$"), 1: ("$\\ell$", "$G$", "$I_l$"), 2: ("$\\ell$", "$I_a$", "$I_b$")}
TITLES = {0: "Lagrange (closed form)", 1: "Euler (closed form)", 2: "numerical tori"}


def read(path):
    t = c.load_table(path, "tori")
    if t is None:
        c.die(f"{path}: no /tori (not a file written by lgi actions)")
    return t, c.load_attrs(path, "parameters")


def draw(ax, t, par):
    keep = t["ok"] == 1
    method = int(t["method"][keep][0]) if keep.any() else 2
    I = t["actions"][keep]
    if method in (0, 1) and len(I) >= 3:
        ax.plot_trisurf(I[:, 0], I[:, 1], I[:, 2], cmap="viridis", linewidth=0.1, antialiased=True, alpha=0.9)
    elif len(I):
        ax.scatter(I[:, 0], I[:, 1], I[:, 2], c=I[:, 0], cmap="viridis", s=6)
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
    fig = c.plt.figure(figsize=(3.4 * len(data), 3.2))
    for i, (t, par) in enumerate(data):
        ax = fig.add_subplot(1, len(data), i + 1, projection="3d")
        draw(ax, t, par)
    fig.tight_layout()
    c.save(fig, args.out, args.name)


if __name__ == "__main__":
    main()
