#!/usr/bin/python3
"""Chaos maps over the (l, h) plane, or a Cardan top's (key, h) plane, from `lgi chaos-map`
files (experiments/CHAOS_MAP.md: /chaos_map chaotic_fraction, megno_median, lyapunov_max,
status, h_min; `vary` and its attribute vary_key for a Cardan map).

Usage: chaos_map.py --out DIR [--branches BIFURCATION.h5] CHAOS.h5 ...

Writes DIR/chaos_map_<file stem>.{pdf,png}: two panels over the (l, h) grid, the
fraction of orbits whose MEGNO <Y>(t_end) exceeds the threshold stored in the file,
and the largest Lyapunov exponent of each cell; empty cells (h below the least energy
at l) are left white and the least energy is drawn as a dashed line. With --branches
(a file of `lgi bifurcation` for the same scene) the relative equilibria are drawn on
top, as in the (l, h) bifurcation diagram. A Cardan map (`lgi chaos-map --vary KEY=a:b:n`)
has the varied scene key on the horizontal axis and the least potential as the dashed line;
--branches is for (l, h) maps only.
"""
import numpy as np

import lgi_plot_common as c


def edges(v):
    """Cell edges around equally spaced centres (one centre: a unit cell)."""
    d = (v[-1] - v[0]) / (len(v) - 1) if len(v) > 1 else 1.0
    return np.concatenate([[v[0] - d / 2], v + d / 2])


def m_key(path):
    """The varied scene key of a Cardan map (the /chaos_map attribute vary_key)."""
    with c.h5py.File(path, "r") as f:
        key = f["chaos_map"].attrs.get("vary_key", "")
    return key.decode() if isinstance(key, bytes) else str(key)


def axis_label(key):
    """The axis label of a varied key: its meaning where known, else the key itself."""
    known = {"suspension.tilt": "frame tilt $\\alpha$ (rad), " + key,
             "suspension.outer_inertia": "outer ring's moment $C_o$, " + key}
    return known.get(key, key)


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--branches", help="an lgi bifurcation file whose branches are drawn on top")
    args = p.parse_args()
    if not args.files:
        c.die("give at least one file written by lgi chaos-map")
    branches = None
    if args.branches:
        branches = c.load_table(args.branches, "equilibria")
        if branches is None:
            c.die(f"{args.branches}: no /equilibria (not a file written by lgi bifurcation)")
    for path in args.files:
        with c.h5py.File(path, "r") as f:
            if "chaos_map" not in f:
                c.die(f"{path}: no /chaos_map (not a file written by lgi chaos-map)")
            m = {k: np.asarray(f["chaos_map"][k][()]) for k in f["chaos_map"]}
            par = c.attrs(f["parameters"])
        varied = "vary" in m
        if varied and branches is not None:
            c.die(f"{path}: --branches draws on (l, h) maps; this map varies {m_key(path)}")
        l, h = (m["vary"] if varied else m["l"]), m["h"]
        fig, axes = c.plt.subplots(1, 2, figsize=(8.4, 3.4), sharey=True)
        panels = ((m["chaotic_fraction"], "fraction of chaotic orbits", "magma_r", 0.0, 1.0),
                  (m["lyapunov_max"], "largest Lyapunov exponent", "viridis", 0.0, None))
        for ax, (value, label, cmap, vmin, vmax) in zip(axes, panels):
            shown = np.ma.masked_invalid(np.where(m["status"] == 0, value, np.nan))
            ax.grid(False)  # pcolormesh under a grid is deprecated (Matplotlib 3.5)
            mesh = ax.pcolormesh(edges(l), edges(h), shown.T, cmap=cmap, vmin=vmin, vmax=vmax, shading="flat")
            fig.colorbar(mesh, ax=ax, label=label)
            ax.plot(l, m["h_min"], color="0.55", ls="--", lw=0.8)  # seen on black cells too
            if branches is not None:
                for b in np.unique(branches["branch"]):
                    sel = (branches["branch"] == b) & (branches["fold"] == 0)
                    ax.plot(branches["l"][sel], branches["h"][sel], color="0.3", lw=0.6)
            ax.set_xlim(edges(l)[0], edges(l)[-1])
            ax.set_ylim(edges(h)[0], edges(h)[-1])
            ax.set_xlabel(axis_label(m_key(path)) if varied else "$\\ell = \\Pi\\cdot\\Gamma$")
        axes[0].set_ylabel("$h$")
        fig.suptitle(f"{c.scene_label(par)}: {par.get('ics')} orbits per cell to t = {par.get('t_end')}, "
                     f"chaotic where MEGNO > {par.get('threshold')}", fontsize=8)
        c.save(fig, args.out, f"chaos_map_{c.file_stem(path)}")


if __name__ == "__main__":
    main()
