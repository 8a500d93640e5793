#!/usr/bin/python3
"""Tilt-energy chaos maps of Cardan tops side by side, from `lgi chaos-map --vary
suspension.tilt=...` files (experiments/CHAOS_MAP.md "Cardan tops": /chaos_map vary, h,
h_min, chaotic_fraction, status).

Usage: cardan_chaos_maps.py --out DIR --name NAME [--title LABEL ...] CHAOS.h5 ...

Writes DIR/NAME.{pdf,png}: one panel per file, the chaotic fraction (MEGNO above the
file's threshold, microcanonical draws on each energy surface) over the frame tilt alpha
and the energy h, one colour scale for all panels; cells without orbits (h at or below
the least potential) white, the least potential dashed red. --title gives each panel's label
(in the order of the files; default: the scene's name).
"""
import numpy as np

import lgi_plot_common as c
from chaos_map import edges


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--name", required=True, help="the figure's file name, without extension")
    p.add_argument("--title", action="append", default=[], help="a panel label, once per file")
    args = p.parse_args()
    if not args.files:
        c.die("give at least one file written by lgi chaos-map --vary")
    if args.title and len(args.title) != len(args.files):
        c.die(f"--title given {len(args.title)} times for {len(args.files)} files")
    n = len(args.files)
    fig, axes = c.plt.subplots(1, n, figsize=(3.3 * n + 0.8, 3.4), squeeze=False, constrained_layout=True)
    image = None
    for i, (ax, path) in enumerate(zip(axes[0], args.files)):
        with c.h5py.File(path, "r") as f:
            if "chaos_map" not in f or "vary" not in f["chaos_map"]:
                c.die(f"{path}: no /chaos_map/vary (not a file of lgi chaos-map --vary)")
            m = {k: np.asarray(f["chaos_map"][k][()]) for k in f["chaos_map"]}
            par = c.attrs(f["parameters"])
            threshold = float(f["chaos_map"].attrs.get("threshold", 3.0))
        frac = np.where(m["status"] == 0, m["chaotic_fraction"], np.nan)
        ax.grid(False)
        image = ax.pcolormesh(edges(m["vary"]), edges(m["h"]), frac.T, cmap="viridis", vmin=0, vmax=1,
                              shading="flat")
        ax.plot(edges(m["vary"])[[0, -1]] if np.ptp(m["h_min"]) == 0 else m["vary"],
                [m["h_min"][0]] * 2 if np.ptp(m["h_min"]) == 0 else m["h_min"], "--", color="tab:red", lw=1.4)
        ax.set_xlim(edges(m["vary"])[0], edges(m["vary"])[-1])
        ax.set_ylim(edges(m["h"])[0], edges(m["h"])[-1])
        ax.set_xlabel("frame tilt $\\alpha$ (rad)")
        if i == 0:
            ax.set_ylabel("energy $h$")
        label = args.title[i] if args.title else c.scene_label(par)
        ax.set_title(f"{label}\n{int(par.get('ics', 0))} orbits per cell, $t$ = {c.num(float(par.get('t_end', 0)))}",
                     fontsize=8)
    cb = fig.colorbar(image, ax=axes[0].tolist(), shrink=0.9, pad=0.02)
    cb.set_label(f"chaotic fraction (MEGNO $> {c.num(threshold)}$)")
    c.save(fig, args.out, args.name)


if __name__ == "__main__":
    main()
