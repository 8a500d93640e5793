#!/usr/bin/python3
"""The Euler-angle singularity study from an `lgi singularity` file
(experiments/SINGULARITY.md): /scenes/<scene>/runs/<run>/{center_of_mass,
com_deviation, step_history, euler_zxz/{time, psi, theta, phi}} and /results.

Usage: singularity.py --out DIR STUDY.h5

Writes DIR/singularity.{pdf,png}: one row per scene; left, the spin angle φ of
the Euler-angle runs as integrated (jumps by π where θ passes near π); middle,
the deviation of every run's centre of mass R χ from the reference on a common
grid; right, the accepted step sizes (a controlled stepper shrinks its step
near the singular set of the chart; a Lie-group scheme does not see it).
"""
import h5py
import numpy as np

import lgi_plot_common as c


def text(g, k, default=""):
    v = g.attrs.get(k, default)
    return v.decode() if isinstance(v, bytes) else (v.item() if isinstance(v, np.ndarray) and v.shape == () else v)


def main():
    args = c.parser(__doc__.split("\n\n")[0]).parse_args()
    if len(args.files) != 1:
        c.die("give exactly one singularity study file")
    with h5py.File(args.files[0], "r") as f:
        if "scenes" not in f:
            c.die(f"{args.files[0]}: no /scenes group")
        scenes = list(f["scenes"])
        fig, axes = c.plt.subplots(len(scenes), 3, figsize=(7.2, 2.5 * len(scenes) + 0.6), squeeze=False)
        handles = {}
        for row, key in enumerate(scenes):
            g = f["scenes"][key]
            grid = g["grid/time"][:] if "grid" in g else None
            runs = g["runs"]
            for n, label in enumerate(runs):
                r = runs[label]
                method = text(r, "method", label)
                guard = text(r, "guard", "-")
                outcome = text(r, "outcome", "?")
                baseline = text(r, "family", "") == "baseline"
                name = method + (" (guard off)" if guard == "off" and "unguarded" not in method else "") + ("" if outcome == "ok" else " ✗")
                st = c.scheme_style(method)
                ls = ":" if guard == "off" else st["linestyle"]
                if "euler_zxz" in r and guard == "off":
                    e = r["euler_zxz"]
                    axes[row, 0].plot(e["time"][:], e["phi"][:], color=st["color"], lw=0.8, ls="-")
                if "com_deviation" in r and grid is not None:
                    dev = r["com_deviation"][:]
                    m = min(len(dev), len(grid))
                    h, = axes[row, 1].semilogy(grid[:m], np.maximum(dev[:m], 1e-16), color=st["color"], ls=ls,
                                               lw=0.9 if baseline else 1.3, label=name)
                    handles.setdefault(name, h)
                if "step_history" in r:
                    sh = r["step_history"]
                    axes[row, 2].semilogy(sh["time"][:], sh["step_size"][:], color=st["color"], ls=ls, lw=0.7)
            scene_name = text(g, "scene_file", key)
            axes[row, 0].set_title(f"{c.scene_label(scene_name)}: φ as integrated", loc="left", fontsize=7.5)
            axes[row, 1].set_title("|P − P$_{\\rm ref}$| of the centre of mass", loc="left", fontsize=7.5)
            axes[row, 2].set_title("accepted step sizes", loc="left", fontsize=7.5)
            axes[row, 0].set_ylabel("φ (rad)")
            axes[row, 1].set_ylabel("deviation (m)")
            axes[row, 2].set_ylabel("h (s)")
            for ax in axes[row]:
                ax.set_xlabel("t (s)")
    c.legend_below(fig, handles, ncol=4, fontsize=5.8)
    fig.tight_layout()
    c.save(fig, args.out, "singularity")


if __name__ == "__main__":
    main()
