#!/usr/bin/python3
"""Seed 000 (docs/sources.md), Figures 4 and 9: the book's body angular velocity against time for
the three book scenes (spin about axis 1, 2, 3), a Lie-group scheme beside the
exact solution (lgi's `exact` scheme: Jacobi elliptic functions).

Usage: dzhanibekov.py --out DIR TRAJ.h5 ...   (trajectories of
dzhanibekov_book_axis{1,2,3}.toml; files of the scheme `exact` are drawn as the
reference, every other scheme as the numerical solution)

Writes DIR/dzhanibekov_omega.{pdf,png}: one row per scene, Ω1, Ω2, Ω3 against t
(numerical solid, exact dashed), and on the right the deviation
|Ω − Ω_exact| of the numerical solution, interpolated to the exact file's times.
"""
import numpy as np

import lgi_plot_common as c

COMP_COLORS = ["tab:blue", "tab:orange", "tab:green"]


def main():
    args = c.parser(__doc__.split("\n\n")[0]).parse_args()
    runs = [c.load_trajectory(p) for p in args.files]
    scenes = sorted({c.scene_label(r["parameters"]) for r in runs})
    if not scenes:
        c.die("no trajectory files given")
    fig, axes = c.plt.subplots(len(scenes), 2, figsize=(7.0, 1.75 * len(scenes) + 0.35), squeeze=False,
                               gridspec_kw={"width_ratios": [2.5, 1], "wspace": 0.28}, sharex=True)
    for row, scene in enumerate(scenes):
        mine = [r for r in runs if c.scene_label(r["parameters"]) == scene]
        exact = next((r for r in mine if r["scheme"] == "exact"), None)
        numeric = [r for r in mine if r["scheme"] != "exact"]
        ax, axd = axes[row]
        for r in numeric:
            for i in range(3):
                ax.plot(r["t"], r["Omega"][:, i], color=COMP_COLORS[i], lw=1.3,
                        label=f"$\\Omega_{i+1}$ ({r['scheme']})" if row == 0 else None)
        if exact is not None:
            for i in range(3):
                ax.plot(exact["t"], exact["Omega"][:, i], color="k", ls=(0, (3, 2)), lw=0.7,
                        label="exact" if (row == 0 and i == 0) else None)
            for r in numeric:
                dev = np.zeros_like(exact["t"])
                for i in range(3):
                    dev = np.maximum(dev, np.abs(np.interp(exact["t"], r["t"], r["Omega"][:, i]) - exact["Omega"][:, i]))
                axd.semilogy(exact["t"], np.maximum(dev, 1e-17), color=c.scheme_style(r["scheme"])["color"],
                             lw=0.8, label=r["scheme"])
        w0 = (mine[0]["scene"].get("initial", {}).get("angular_velocity"))
        title = scene.replace("dzhanibekov_book_", "book, ").replace("axis", "spin about axis ")
        if w0 is not None:
            title += "  ($\\Omega_0$ = (" + ", ".join(f"{x:g}" for x in w0) + ") rad/s)"
        ax.set_title(title, loc="left")
        ax.set_ylabel("$\\Omega$ (rad/s)")
        axd.set_ylabel("$|\\Omega-\\Omega^{\\rm exact}|_\\infty$ (rad/s)")
        axd.set_title("deviation from exact", loc="left")
        if row == 0:
            fig.legend(*ax.get_legend_handles_labels(), ncol=4, loc="lower left", bbox_to_anchor=(0.08, 0.94),
                       frameon=False)
            axd.legend(fontsize=6.5, loc="lower right")
    axes[-1][0].set_xlabel("t (s)")
    axes[-1][1].set_xlabel("t (s)")
    fig.subplots_adjust(top=0.895, hspace=0.32)
    fig.align_ylabels()
    c.save(fig, args.out, "dzhanibekov_omega")


if __name__ == "__main__":
    main()
