#!/usr/bin/python3
"""Poincaré sections from `lgi poincare` files (experiments/POINCARE.md: /events
phi, theta, sheet; /sweep megno where computed).

Usage: poincare.py --out DIR [--colour orbit|megno|direction] [--dot-size S] [--zoom X0:X1:Y0:Y1]
                   [--periodic PERIODIC.h5 [--periodic-h-tol D]] SECTION.h5 ...

(MEGNO colours are drawn on a grey ground, where the chaotic orbits' yellow shows.)

Writes DIR/poincare_<file stem>.{pdf,png}: Richter's section drawn on the torus
of the two glued Poisson spheres (docs/atlas.md §6), phi against the torus
angle theta on the sheet +1 and 2 pi - theta on the sheet -1, one dot per
crossing, coloured by orbit (default), by the orbit's MEGNO <Y> (2: regular,
above: chaotic; needs a file made with --megno) or by the crossing's
direction (/events direction: in, dS/dt > 0, or out), with a colour bar. The
boundary of the accessible region U_l(Gamma) = h (docs/atlas.md §1, what lgi
region finds) is drawn on Richter's section as a black line: no crossing lies
outside it. A file of the gamma section (--section gamma) is drawn as phi
against theta (the angle of Pi from the axis). A file of a Cardan top
(docs/cardan.md section 9: /events piece, x, y) is drawn as the seed's four
pieces: the two copies of the shape torus (q3, q2), told apart by the sign
of dq3/dt, and the two cylinders (q3, psi) at q2 = 0 and pi, psi the
direction of the shape velocity; the title says what is fixed (p1 and h where
p1 is an integral, else h and the orbits' initial p1).

--periodic marks the orbits of an `lgi periodic` file (experiments/PERIODIC.md)
at the section's l, of each family the one nearest h within --periodic-h-tol,
where they cross the section (periodic_crossings.py): open circles elliptic,
red crosses hyperbolic or inverse hyperbolic, grey diamonds degenerate; where
the file has /manifolds (lgi periodic --manifolds) of an orbit drawn, the
section points of its unstable manifold are drawn in red and of its stable
manifold in blue. --zoom X0:X1:Y0:Y1 draws only that window of the (phi, torus angle)
plane (of a heavy top's section).
"""
import os
import sys
import tomllib

import numpy as np

import lgi_plot_common as c
import periodic_crossings as pc


PIECES = ((1, "torus copy $\\dot q_3 > 0$", "$q_2$"), (-1, "torus copy $\\dot q_3 < 0$", "$q_2$"),
          (2, "cylinder $q_2 = 0$", "$\\psi$"), (3, "cylinder $q_2 = \\pi$", "$\\psi$"))


def colour_values(args, ev, megno):
    """(values, colour map, vmin, vmax, colour-bar label, ticks) of --colour."""
    if args.colour == "megno":
        return np.clip(megno[ev["index"]], 0.0, 8.0), "viridis", 0.0, 8.0, \
            "MEGNO $\\langle Y\\rangle$ (clipped at 8; 2: regular)", None
    if args.colour == "direction":
        cmap = c.matplotlib.colors.ListedColormap(["tab:orange", "tab:blue"])
        return np.asarray(ev["direction"], dtype=float), cmap, -1.5, 1.5, "crossing", (-1, 1)
    return ev["index"] % 20, "tab20", -0.5, 19.5, "orbit index (mod 20)", range(0, 20, 4)


def background(ax, args):
    """MEGNO's yellow (chaotic) is lost on white: a grey ground under MEGNO colours."""
    if args.colour == "megno":
        ax.set_facecolor("0.55")
        ax.grid(color="0.7", alpha=0.4)


def add_colour_bar(fig, sc, axes, label, ticks):
    bar = fig.colorbar(sc, ax=axes, label=label, shrink=0.9)
    if ticks is not None:
        bar.set_ticks(list(ticks))
        if tuple(ticks) == (-1, 1):
            bar.set_ticklabels(["out ($\\dot S < 0$)", "in ($\\dot S > 0$)"])
    return bar


def draw_cardan(f, path, args):
    """The four pieces of the T^3 section, coloured by orbit, MEGNO or direction."""
    ev = {k: np.asarray(f["events"][k][()]) for k in ("index", "piece", "x", "y", "direction")}
    megno = np.asarray(f["sweep"]["megno"][()]) if "megno" in f["sweep"] else None
    par = c.attrs(f["parameters"])
    if args.colour == "megno" and megno is None:
        c.die(f"{path}: no /sweep/megno (run lgi poincare with --megno)")
    values, cmap, vmin, vmax, label, ticks = colour_values(args, ev, megno)
    fig, axes = c.plt.subplots(2, 2, figsize=(7.6, 6.0), layout="constrained")
    size = args.dot_size if args.dot_size else 2.5
    sc = None
    for ax, (piece, title, ylabel) in zip(axes.flat, PIECES):
        m = ev["piece"] == piece
        sc = ax.scatter(ev["x"][m], ev["y"][m], c=values[m], s=size, cmap=cmap, vmin=vmin, vmax=vmax, linewidths=0)
        background(ax, args)
        ax.set_xlim(0, 2 * np.pi)
        ax.set_ylim((0, 2 * np.pi) if piece in (1, -1) else (-np.pi, np.pi))
        ax.set_title(f"{title}: {int(m.sum())} crossings", fontsize=8)
        ax.set_xlabel("$q_3$")
        ax.set_ylabel(ylabel)
    add_colour_bar(fig, sc, axes.ravel().tolist(), label, ticks)
    fixed = (f"$p_1$ = {c.num(par.get('l', 0))} (an integral), h = {c.num(par.get('h', 0))}"
             if par.get("p1_conserved", "yes") == "yes" else
             f"h = {c.num(par.get('h', 0))}; $p_1$ is no integral here: "
             f"{c.num(par.get('l', 0))} at the start of each orbit only")
    fig.suptitle(f"{c.scene_label(par)}: {fixed}", fontsize=8)
    stem = os.path.splitext(os.path.basename(path))[0]
    c.save(fig, args.out, f"poincare_{stem}")


MARKS = {"elliptic": ("elliptic periodic orbit", "o", "white", "k"),
         "hyperbolic": ("hyperbolic periodic orbit", "X", "tab:red", "k"),
         "degenerate": ("degenerate periodic orbit (resonant torus)", "D", "0.6", "k")}


def mark_periodic(ax, par, path, args):
    """The crossings of the orbits of --periodic at this l and h (to --periodic-h-tol) with
    this section (periodic_crossings.py), one marker per class; how many are drawn."""
    try:
        table = c.load_table(args.periodic, "periodic")
        pars = c.load_attrs(args.periodic, "parameters")
    except OSError as e:
        c.die(f"--periodic: {args.periodic}: cannot read ({e})")
    need = ("family", "l", "h", "period", "angular_momentum", "gamma", "stability")
    if table is None or any(k not in table for k in need) or "scene_toml" not in pars:
        c.die(f"--periodic: {args.periodic}: no /periodic table with a scene (not a file written by lgi periodic)")
    table.setdefault("event", np.array(["none"] * len(table["h"]), dtype=object))
    table.setdefault("degenerate", np.zeros(len(table["h"]), dtype=int))
    l, h = float(par.get("l", 0.0)), float(par.get("h", 0.0))
    J, w = pc.body_of(pars["scene_toml"])
    J_sec, w_sec = pc.body_of(par["scene_toml"])
    if not (np.allclose(J, J_sec, rtol=1e-12, atol=0) and np.allclose(w, w_sec, rtol=1e-12, atol=0)):
        c.die(f"--periodic: {args.periodic}: another top than the section's {path} (inertia or m g chi differ)")
    e = np.array([float(par.get(f"axis_{k}", 0.0)) for k in (1, 2, 3)])
    e /= np.linalg.norm(e)
    richter = par.get("section", "richter") == "richter"
    rows = pc.orbits_at(table, l, h, args.periodic_h_tol)
    points = {k: [] for k in MARKS}
    for r in rows:
        x0 = np.concatenate([table["angular_momentum"].reshape(-1, 3)[r], table["gamma"].reshape(-1, 3)[r]])
        kind = ("degenerate" if table["degenerate"][r] else
                "elliptic" if table["stability"][r] == "elliptic" else "hyperbolic")
        for phi, theta, sheet in pc.crossings(x0, float(table["period"][r]), J, w, e, richter):
            points[kind].append((phi, theta if not richter or sheet > 0 else 2 * np.pi - theta))
    for kind, (label, marker, face, edge) in MARKS.items():
        if points[kind]:
            x, y = np.array(points[kind]).T
            ax.plot(x, y, marker, ls="none", mfc=face, mec=edge, ms=6, mew=0.9, zorder=5, label=label)
    draw_manifolds(ax, args.periodic, table, rows, richter)
    print(f"poincare.py: {path}: {len(rows)} periodic orbit(s) of {args.periodic} within "
          f"{c.num(args.periodic_h_tol)} of h = {c.num(h)} at l = {c.num(l)}", file=sys.stderr)
    return len(rows)


MANIFOLD_COLOURS = {"unstable": ("tab:red", "unstable manifold"), "stable": ("tab:blue", "stable manifold")}


def draw_manifolds(ax, path, table, rows, richter):
    """The /manifolds points of the orbits in `rows` (positions in /periodic), if the file has them."""
    with c.h5py.File(path, "r") as f:
        if "manifolds" not in f or not f["manifolds"]["phi"].shape or not f["manifolds"]["phi"].shape[0]:
            return  # none, or an empty table (no hyperbolic orbit among the seeds')
        m = {k: f["manifolds"][k][()] for k in ("family", "index", "branch", "phi", "theta", "sheet")}
    branch = np.array([b.decode() if isinstance(b, bytes) else b for b in m["branch"]])
    keep = np.zeros(len(branch), dtype=bool)
    for r in rows:
        keep |= (m["family"] == table["family"][r]) & (m["index"] == table["index"][r])
    for name, (colour, label) in MANIFOLD_COLOURS.items():
        sel = keep & (branch == name)
        if not np.any(sel):
            continue
        y = np.where(m["sheet"][sel] > 0, m["theta"][sel], 2 * np.pi - m["theta"][sel]) if richter else m["theta"][sel]
        ax.scatter(m["phi"][sel], y, s=1.2, color=colour, linewidths=0, zorder=4, label=label)


def region_boundary(ax, par):
    """U_l(Gamma(phi, theta)) = h on both sheets of Richter's torus (docs/atlas.md §1)."""
    scene = tomllib.loads(par["scene_toml"])
    J = c.inertia_of(scene)
    g = scene.get("gravity", {}).get("g", 9.81) if "gravity" in scene else 0.0
    b = scene.get("body", {})
    w = float(b.get("mass", 0.0)) * g * np.asarray(b.get("center_of_mass", [0, 0, 0]), dtype=float)
    e = np.array([float(par.get(f"axis_{k}", 0.0)) for k in (1, 2, 3)])
    if not np.linalg.norm(e):
        return
    f1, f2 = pc.section_frame(e / np.linalg.norm(e))
    phi, th = np.meshgrid(np.linspace(0, 2 * np.pi, 361), np.linspace(0, np.pi, 181))
    G = (np.sin(th) * np.cos(phi))[..., None] * f1 + (np.sin(th) * np.sin(phi))[..., None] * f2 \
        + np.cos(th)[..., None] * e
    l, h = float(par.get("l", 0.0)), float(par.get("h", 0.0))
    U = l * l / (2 * np.einsum("...i,ij,...j->...", G, J, G)) + G @ w
    if not U.min() < h < U.max():  # the whole sphere (or nothing) is accessible: no boundary
        return
    for y in (th, 2 * np.pi - th):
        ax.contour(phi, y, U, levels=[h], colors="k", linewidths=0.8)
    ax.plot([], [], color="k", lw=0.8, label="$U_\\ell = h$ (accessible region)")


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--colour", choices=("orbit", "megno", "direction"), default="orbit",
                   help="colour of the dots: the orbit's index (default), its MEGNO <Y>, or the crossing's direction")
    p.add_argument("--dot-size", type=float,
                   help="dot area in points^2 (default 0.6 by orbit, 1.2 by MEGNO or direction; 2.5 on the Cardan pieces)")
    p.add_argument("--periodic", metavar="PERIODIC.h5",
                   help="a file of lgi periodic: its orbits at the section's l and h marked where they cross it")
    p.add_argument("--periodic-h-tol", type=float, default=1e-2, metavar="D",
                   help="--periodic: the orbit of each family nearest h, if within D of it (default 0.01)")
    p.add_argument("--zoom", metavar="X0:X1:Y0:Y1",
                   help="draw only this window of the section (phi from X0 to X1, the vertical axis from Y0 to Y1)")
    args = p.parse_args()
    zoom = None
    if args.zoom:
        try:
            zoom = [float(v) for v in args.zoom.split(":")]
        except ValueError:
            zoom = []
        if len(zoom) != 4 or not all(np.isfinite(zoom)) or not (zoom[0] < zoom[1] and zoom[2] < zoom[3]):
            c.die(f"--zoom: '{args.zoom}': expected X0:X1:Y0:Y1, four numbers with X0 < X1 and Y0 < Y1")
    if not args.files:
        c.die("give at least one file written by lgi poincare")
    if not (args.periodic_h_tol >= 0 and np.isfinite(args.periodic_h_tol)):
        c.die(f"--periodic-h-tol: {args.periodic_h_tol}: expected a finite number >= 0")
    for path in args.files:
        with c.h5py.File(path, "r") as f:
            if "events" in f and "piece" in f["events"]:
                if args.periodic:
                    c.die(f"--periodic: {path} is a section of a Cardan top; periodic orbits are of heavy tops")
                draw_cardan(f, path, args)
                continue
            if "events" not in f or "phi" not in f["events"]:
                c.die(f"{path}: no /events/phi (not a file written by lgi poincare)")
            ev = {k: np.asarray(f["events"][k][()]) for k in ("index", "phi", "theta", "sheet", "direction")}
            megno = np.asarray(f["sweep"]["megno"][()]) if "megno" in f["sweep"] else None
            par = c.attrs(f["parameters"])
        if args.colour == "megno" and megno is None:
            c.die(f"{path}: no /sweep/megno (run lgi poincare with --megno)")
        richter = par.get("section", "richter") == "richter"
        y = np.where(ev["sheet"] > 0, ev["theta"], 2 * np.pi - ev["theta"]) if richter else ev["theta"]
        fig, ax = c.plt.subplots(figsize=(5.6, 4.2))
        values, cmap, vmin, vmax, label, ticks = colour_values(args, ev, megno)
        size = args.dot_size or (0.6 if args.colour == "orbit" else 1.2)  # one colour per orbit is read from lines
        sc = ax.scatter(ev["phi"], y, c=values, s=size, cmap=cmap, vmin=vmin, vmax=vmax,
                        linewidths=0)
        add_colour_bar(fig, sc, ax, label, ticks)
        background(ax, args)
        ax.set_xlim(0, 2 * np.pi)
        ax.set_ylim(0, 2 * np.pi if richter else np.pi)
        ax.set_xlabel("$\\varphi$")
        if richter:
            ax.axhline(np.pi, color="0.5", lw=0.5)
            ax.set_ylabel("$\\vartheta$ (sheet +1),  $2\\pi - \\vartheta$ (sheet $-1$)")
            region_boundary(ax, par)
        else:
            ax.set_ylabel("angle of $\\Pi$ from the axis")
        if args.periodic:
            mark_periodic(ax, par, path, args)
        if zoom:
            ax.set_xlim(zoom[0], zoom[1])
            ax.set_ylim(zoom[2], zoom[3])
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="lower right", fontsize=6.5)
        seeds = " (orbits from --seeds)" if par.get("seeds_file") else ""
        ax.set_title(f"{c.scene_label(par)}: $\\ell$ = {c.num(par.get('l', 0))}, h = {c.num(par.get('h', 0))}{seeds}",
                     fontsize=8)
        stem = os.path.splitext(os.path.basename(path))[0]
        c.save(fig, args.out, f"poincare_{stem}")


if __name__ == "__main__":
    main()
