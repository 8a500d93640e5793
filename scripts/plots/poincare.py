#!/usr/bin/python3
"""Poincaré sections from `lgi poincare` files (experiments/POINCARE.md: /events
phi, theta, sheet; /sweep megno where computed).

Usage: poincare.py --out DIR [--colour orbit|megno] SECTION.h5 ...

Writes DIR/poincare_<file stem>.{pdf,png}: Richter's section drawn on the torus
of the two glued Poisson spheres (docs/atlas.md §6), phi against the torus
angle theta on the sheet +1 and 2 pi - theta on the sheet -1, one dot per
crossing, coloured by orbit (default) or by the orbit's MEGNO <Y> (2: regular,
above: chaotic; needs a file made with --megno). A file of the gamma section
(--section gamma) is drawn as phi against theta (the angle of Pi from the axis).
A file of a Cardan top (docs/cardan.md section 9: /events piece, x, y) is drawn
as the seed's four pieces: the two copies of the shape torus (q3, q2), told
apart by the sign of dq3/dt, and the two cylinders (q3, psi) at q2 = 0 and pi,
psi the direction of the shape velocity.
"""
import os

import numpy as np

import lgi_plot_common as c


PIECES = ((1, "torus copy $\\dot q_3 > 0$", "$q_2$"), (-1, "torus copy $\\dot q_3 < 0$", "$q_2$"),
          (2, "cylinder $q_2 = 0$", "$\\psi$"), (3, "cylinder $q_2 = \\pi$", "$\\psi$"))


def draw_cardan(f, path, args):
    """The four pieces of the T^3 section, coloured by orbit or MEGNO."""
    ev = {k: np.asarray(f["events"][k][()]) for k in ("index", "piece", "x", "y")}
    megno = np.asarray(f["sweep"]["megno"][()]) if "megno" in f["sweep"] else None
    par = c.attrs(f["parameters"])
    if args.colour == "megno" and megno is None:
        c.die(f"{path}: no /sweep/megno (run lgi poincare with --megno)")
    fig, axes = c.plt.subplots(2, 2, figsize=(7.0, 6.0))
    for ax, (piece, title, ylabel) in zip(axes.flat, PIECES):
        m = ev["piece"] == piece
        if args.colour == "megno":
            col = np.clip(megno[ev["index"][m]], 0.0, 8.0)
            ax.scatter(ev["x"][m], ev["y"][m], c=col, s=0.4, cmap="viridis", vmin=0.0, vmax=8.0, linewidths=0)
        else:
            ax.scatter(ev["x"][m], ev["y"][m], c=ev["index"][m] % 20, s=0.4, cmap="tab20", vmin=0, vmax=19,
                       linewidths=0)
        ax.set_xlim(0, 2 * np.pi)
        ax.set_ylim((0, 2 * np.pi) if piece in (1, -1) else (-np.pi, np.pi))
        ax.set_title(f"{title}: {int(m.sum())} crossings", fontsize=8)
        ax.set_xlabel("$q_3$")
        ax.set_ylabel(ylabel)
    fig.suptitle(f"{c.scene_label(par)}: $p_1$ = {float(par.get('l', 0)):g}, h = {float(par.get('h', 0)):g}", fontsize=8)
    fig.tight_layout()
    stem = os.path.splitext(os.path.basename(path))[0]
    c.save(fig, args.out, f"poincare_{stem}")


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--colour", choices=("orbit", "megno"), default="orbit",
                   help="colour of the dots: the orbit's index (default) or its MEGNO <Y>")
    args = p.parse_args()
    if not args.files:
        c.die("give at least one file written by lgi poincare")
    for path in args.files:
        with c.h5py.File(path, "r") as f:
            if "events" in f and "piece" in f["events"]:
                draw_cardan(f, path, args)
                continue
            if "events" not in f or "phi" not in f["events"]:
                c.die(f"{path}: no /events/phi (not a file written by lgi poincare)")
            ev = {k: np.asarray(f["events"][k][()]) for k in ("index", "phi", "theta", "sheet")}
            megno = np.asarray(f["sweep"]["megno"][()]) if "megno" in f["sweep"] else None
            par = c.attrs(f["parameters"])
        if args.colour == "megno" and megno is None:
            c.die(f"{path}: no /sweep/megno (run lgi poincare with --megno)")
        richter = par.get("section", "richter") == "richter"
        y = np.where(ev["sheet"] > 0, ev["theta"], 2 * np.pi - ev["theta"]) if richter else ev["theta"]
        fig, ax = c.plt.subplots(figsize=(5.2, 4.2))
        if args.colour == "megno":
            col = np.clip(megno[ev["index"]], 0.0, 8.0)
            sc = ax.scatter(ev["phi"], y, c=col, s=0.4, cmap="viridis", vmin=0.0, vmax=8.0, linewidths=0)
            fig.colorbar(sc, ax=ax, label="MEGNO $\\langle Y\\rangle$ (clipped at 8)")
        else:
            ax.scatter(ev["phi"], y, c=ev["index"] % 20, s=0.4, cmap="tab20", vmin=0, vmax=19, linewidths=0)
        ax.set_xlim(0, 2 * np.pi)
        ax.set_ylim(0, 2 * np.pi if richter else np.pi)
        ax.set_xlabel("$\\varphi$")
        if richter:
            ax.axhline(np.pi, color="0.5", lw=0.5)
            ax.set_ylabel("$\\vartheta$ (sheet +1),  $2\\pi - \\vartheta$ (sheet $-1$)")
        else:
            ax.set_ylabel("angle of $\\Pi$ from the axis")
        ax.set_title(f"{c.scene_label(par)}: $\\ell$ = {par.get('l', 0):g}, h = {par.get('h', 0):g}", fontsize=8)
        stem = os.path.splitext(os.path.basename(path))[0]
        c.save(fig, args.out, f"poincare_{stem}")


if __name__ == "__main__":
    main()
