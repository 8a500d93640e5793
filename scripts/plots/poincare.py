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
manifold in blue (the section's dots then faded). On a Cardan top's section the periodic file must be of the
same Cardan top (its scene's mechanism, parameter for parameter): each orbit's
crossings of either factor of the section are computed from its point
(cardan_angles, cardan_momenta) over one period and marked at (x, y) in the
panel of their piece, an orbit seeded from the section (section_sheet its
piece) at its own point exactly; the manifold points (phi, theta, sheet: x,
y, piece) in the panels of their pieces. A periodic file of another top, or of
a heavy top on a Cardan section (or the reverse), is refused. Stderr says how
many orbits, crossings and manifold points were drawn, and DIR/poincare_<file
stem>_periodic.csv lists the crossings marked (family, index, h, period,
stability, mark: the marker's class, panel: 0 on a heavy top's section, else
the piece; x, y as drawn).
--zoom X0:X1:Y0:Y1 draws only that window of the (phi, torus angle) plane of a
heavy top's section, or of the (q3, q2) plane on a Cardan top's two torus
copies (the cylinders are drawn whole).
"""
import os
import sys
import tomllib

import numpy as np

import lgi_plot_common as c
import periodic_crossings as pc


PIECES = ((1, "torus copy $\\dot q_3 > 0$", "$q_2$"), (-1, "torus copy $\\dot q_3 < 0$", "$q_2$"),
          (2, "cylinder $q_2 = 0$", "$\\psi$"), (3, "cylinder $q_2 = \\pi$", "$\\psi$"))
PANEL_PIECES = tuple(piece for piece, _, _ in PIECES)


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


def draw_cardan(f, path, args, zoom):
    """The pieces of the T^3 section, coloured by orbit, MEGNO or direction (the two cylinders left out
    when nothing crosses them); with --periodic, the periodic orbits' crossings and their manifolds
    marked in their pieces."""
    ev = {k: np.asarray(f["events"][k][()]) for k in ("index", "piece", "x", "y", "direction")}
    megno = np.asarray(f["sweep"]["megno"][()]) if "megno" in f["sweep"] else None
    par = c.attrs(f["parameters"])
    if args.colour == "megno" and megno is None:
        c.die(f"{path}: no /sweep/megno (run lgi poincare with --megno)")
    stem = os.path.splitext(os.path.basename(path))[0]
    marks, manifolds = cardan_periodic(par, path, stem, args) if args.periodic else ([], None)
    drawn = {piece for piece in PANEL_PIECES if np.any(ev["piece"] == piece) or any(m[2] == piece for m in marks)
             or (manifolds is not None and np.any(manifolds["sheet"] == piece))}
    pieces = [row for row in PIECES if row[0] in (1, -1) or drawn & {2, 3}]
    values, cmap, vmin, vmax, label, ticks = colour_values(args, ev, megno)
    rows = len(pieces) // 2
    fig = c.plt.figure(figsize=(7.6, 0.5 + 2.75 * rows + (0.45 if args.periodic else 0)), layout="constrained")
    grid = fig.add_gridspec(rows + 1, 2, height_ratios=(1,) * rows + (0.13 if args.periodic else 1e-3,))
    axes = [fig.add_subplot(grid[i // 2, i % 2]) for i in range(len(pieces))]
    size = args.dot_size if args.dot_size else 2.5
    sc = None
    panels = {}
    for ax, (piece, title, ylabel) in zip(axes, pieces):
        m = ev["piece"] == piece
        sc = ax.scatter(ev["x"][m], ev["y"][m], c=values[m], s=size, cmap=cmap, vmin=vmin, vmax=vmax, linewidths=0,
                        gid="section")
        background(ax, args)
        ax.set_xlim(0, 2 * np.pi)
        ax.set_ylim((0, 2 * np.pi) if piece in (1, -1) else (-np.pi, np.pi))
        if zoom and piece in (1, -1):  # the window of the shape torus; the cylinders' psi is another axis
            ax.set_xlim(zoom[0], zoom[1])
            ax.set_ylim(zoom[2], zoom[3])
        ax.set_title(f"{title}: {int(m.sum())} crossings", fontsize=8)
        ax.set_xlabel("$q_3$")
        ax.set_ylabel(ylabel)
        panels[piece] = ax
    add_colour_bar(fig, sc, axes, label, ticks)
    if args.periodic:
        draw_marks(panels, marks)
        draw_manifolds(panels, manifolds, False, size=2.0)
        legend = fig.add_subplot(grid[rows, :])
        legend.axis("off")
        handles = {}
        for ax in axes:
            for h, lab in zip(*ax.get_legend_handles_labels()):
                handles.setdefault(lab, h)
        if handles:
            legend.legend(list(handles.values()), list(handles.keys()), loc="center", ncol=min(len(handles), 3),
                          fontsize=7, frameon=False, markerscale=1.0)
    fixed = (f"$p_1$ = {c.num(par.get('l', 0))} (an integral), h = {c.num(par.get('h', 0))}"
             if par.get("p1_conserved", "yes") == "yes" else
             f"h = {c.num(par.get('h', 0))}; $p_1$ is no integral here: "
             f"{c.num(par.get('l', 0))} at the start of each orbit only")
    cylinders = "" if len(pieces) == 4 else "\nno crossing on the cylinders $q_2 = 0, \\pi$ (not drawn)"
    fig.suptitle(f"{c.scene_label(par)}: {fixed}{cylinders}", fontsize=8)
    c.save(fig, args.out, f"poincare_{stem}")


MARKS = {"elliptic": ("elliptic periodic orbit", "o", "white", "k"),
         "hyperbolic": ("hyperbolic periodic orbit", "X", "tab:red", "k"),
         "degenerate": ("degenerate periodic orbit (resonant torus)", "D", "0.6", "k")}


def periodic_rows(par, path, args, cardan):
    """(table, rows) of --periodic: its /periodic table and the positions of the orbits to draw (of each
    family the one at the section's l nearest its h, within --periodic-h-tol); dies with one line on a
    file that is not lgi periodic's or is of another top than the section's (`cardan`: a Cardan top's)."""
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
    mine, theirs = pc.cardan_of(pars["scene_toml"]), pc.cardan_of(par["scene_toml"])
    if (mine is not None) != cardan:
        c.die(f"--periodic: {args.periodic} is of a {'Cardan' if mine is not None else 'heavy'} top; {path} is a "
              f"section of a {'Cardan' if cardan else 'heavy'} top")
    if cardan:
        if "cardan_angles" not in table or "cardan_momenta" not in table:
            c.die(f"--periodic: {args.periodic}: a Cardan scene but no /periodic cardan_angles, cardan_momenta")
        same = np.allclose(mine, theirs, rtol=1e-12, atol=0)
        what = "inertia, centre of mass, gravity, tilt or rings differ"
    else:
        (J, w), (J_sec, w_sec) = pc.body_of(pars["scene_toml"]), pc.body_of(par["scene_toml"])
        same = np.allclose(J, J_sec, rtol=1e-12, atol=0) and np.allclose(w, w_sec, rtol=1e-12, atol=0)
        what = "inertia or m g chi differ"
    if not same:
        c.die(f"--periodic: {args.periodic}: another top than the section's {path} ({what})")
    l, h = float(par.get("l", 0.0)), float(par.get("h", 0.0))
    return table, pc.orbits_at(table, l, h, args.periodic_h_tol)


def kind_of(table, r):
    return ("degenerate" if table["degenerate"][r] else
            "elliptic" if table["stability"][r] == "elliptic" else "hyperbolic")


def report_marks(path, args, par, table, marks, n_orbits, manifolds, stem):
    """The stderr line of --periodic, and DIR/poincare_<stem>_periodic.csv: one row per mark drawn
    (family, index, h, period, stability, the mark's class, its panel: 0 or the piece, x, y as drawn)."""
    def count(branch):
        return 0 if manifolds is None else int(np.sum(manifolds["branch"] == branch))

    out = c.claim(os.path.join(args.out, f"poincare_{stem}_periodic.csv"))
    with open(out, "w") as f:
        f.write("family,index,h,period,stability,mark,panel,x,y\n")
        for r, kind, panel, x, y in marks:
            f.write(f"{int(table['family'][r])},{int(table['index'][r])},{float(table['h'][r])!r},"
                    f"{float(table['period'][r])!r},{table['stability'][r]},{kind},{int(panel)},{float(x)!r},"
                    f"{float(y)!r}\n")
    print(f"poincare.py: {path}: {n_orbits} periodic orbit(s) of {args.periodic} within "
          f"{c.num(args.periodic_h_tol)} of h = {c.num(par.get('h', 0))} at l = {c.num(par.get('l', 0))}, "
          f"{len(marks)} crossing(s) marked (listed in {out}); {count('unstable')} unstable and "
          f"{count('stable')} stable manifold point(s)", file=sys.stderr)


def draw_marks(panels, marks):
    """marks [(row, class, panel, x, y)] on panels {panel: axes}, one marker per class."""
    for kind, (label, marker, face, edge) in MARKS.items():
        for panel, ax in panels.items():
            xy = [(x, y) for _, k, p, x, y in marks if k == kind and p == panel]
            if xy:
                x, y = np.array(xy).T
                ax.plot(x, y, marker, ls="none", mfc=face, mec=edge, ms=6, mew=0.9, zorder=5, label=label)


def mark_periodic(ax, par, path, stem, args):
    """The crossings of the orbits of --periodic at this l and h (to --periodic-h-tol) with
    this section (periodic_crossings.py), one marker per class; how many orbits are drawn."""
    table, rows = periodic_rows(par, path, args, cardan=False)
    J, w = pc.body_of(par["scene_toml"])
    e = np.array([float(par.get(f"axis_{k}", 0.0)) for k in (1, 2, 3)])
    e /= np.linalg.norm(e)
    richter = par.get("section", "richter") == "richter"
    marks = []
    for r in rows:
        x0 = np.concatenate([table["angular_momentum"].reshape(-1, 3)[r], table["gamma"].reshape(-1, 3)[r]])
        for phi, theta, sheet in pc.crossings(x0, float(table["period"][r]), J, w, e, richter):
            y = theta if not richter or sheet > 0 else 2 * np.pi - theta
            marks.append((r, kind_of(table, r), 0, phi, y))
    draw_marks({0: ax}, marks)
    manifolds = read_manifolds(args.periodic, table, rows)
    draw_manifolds({0: ax}, manifolds, richter)
    report_marks(path, args, par, table, marks, len(rows), manifolds, stem)
    return len(rows)


def cardan_periodic(par, path, stem, args):
    """As mark_periodic on a Cardan top's section (docs/cardan.md §9.2), before the figure is laid out:
    (marks, manifold points). Each orbit's crossings of either factor of S are computed from its point
    (cardan_angles, cardan_momenta) by periodic_crossings.py, to be marked at (x, y) of the panel of their
    piece; an orbit whose point lies on the section (section_sheet = its piece, lgi periodic
    --seeds-from-poincare) is marked there exactly, its own crossing not recomputed."""
    table, rows = periodic_rows(par, path, args, cardan=True)
    top = pc.cardan_of(par["scene_toml"])
    q, p = table["cardan_angles"].reshape(-1, 3), table["cardan_momenta"].reshape(-1, 3)
    sheet = table.get("section_sheet", np.zeros(len(table["h"]), dtype=int))
    marks = []
    for r in rows:
        kind = kind_of(table, r)
        points = pc.cardan_crossings(top, q[r], p[r], float(table["period"][r]))
        if sheet[r] in PANEL_PIECES:  # the point's own crossing, as lgi periodic located it
            own = (float(table["section_phi"][r]), float(table["section_theta"][r]), int(sheet[r]))
            points = [pt for pt in points if not (pt[2] == own[2] and abs(pt[0] - own[0]) < 1e-6
                                                  and abs(pt[1] - own[1]) < 1e-6)] + [own]
        marks += [(r, kind, piece, x, y) for x, y, piece in points]
    manifolds = read_manifolds(args.periodic, table, rows)
    report_marks(path, args, par, table, marks, len(rows), manifolds, stem)
    return marks, manifolds


MANIFOLD_COLOURS = {"unstable": ("tab:red", "unstable manifold"), "stable": ("tab:blue", "stable manifold")}


def read_manifolds(path, table, rows):
    """The /manifolds points (family, index, branch, phi, theta, sheet) of the orbits in `rows` (positions
    in /periodic), None if the file has none for them (on a Cardan top phi, theta, sheet hold x, y, piece)."""
    with c.h5py.File(path, "r") as f:
        if "manifolds" not in f or not f["manifolds"]["phi"].shape or not f["manifolds"]["phi"].shape[0]:
            return None  # none, or an empty table (no hyperbolic orbit among the seeds')
        m = {k: f["manifolds"][k][()] for k in ("family", "index", "branch", "phi", "theta", "sheet")}
    m["branch"] = np.array([b.decode() if isinstance(b, bytes) else b for b in m["branch"]])
    keep = np.zeros(len(m["branch"]), dtype=bool)
    for r in rows:
        keep |= (m["family"] == table["family"][r]) & (m["index"] == table["index"][r])
    return {k: v[keep] for k, v in m.items()} if np.any(keep) else None


def draw_manifolds(panels, m, richter, size=1.2):
    """Manifold points m (read_manifolds) on panels {panel: axes}: {0: the heavy top's one}, or a Cardan
    top's {piece: axes}, each point in the panel of its piece; the unstable branch red, the stable blue,
    the section's dots already drawn faded."""
    if m is None:
        return
    for ax in panels.values():  # the orbits' dots faded: their own reds and blues would pass for manifolds
        for dots in ax.collections:
            if dots.get_gid() == "section":  # not U = h's contour
                dots.set_alpha(0.35)
    for name, (colour, label) in MANIFOLD_COLOURS.items():
        for panel, ax in panels.items():
            sel = (m["branch"] == name) & ((m["sheet"] == panel) if panel else True)
            if not np.any(sel):
                continue
            y = (np.where(m["sheet"][sel] > 0, m["theta"][sel], 2 * np.pi - m["theta"][sel]) if richter
                 else m["theta"][sel])
            ax.scatter(m["phi"][sel], y, s=size, color=colour, linewidths=0, zorder=4)
            ax.plot([], [], "o", ls="none", color=colour, ms=3.5, label=label)  # a legend entry one can see


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
                   help="draw only this window of the section (phi from X0 to X1, the vertical axis from Y0 to Y1; "
                        "on a Cardan section: q3 and q2 on the torus copies)")
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
                draw_cardan(f, path, args, zoom)
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
                        linewidths=0, gid="section")
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
        stem = os.path.splitext(os.path.basename(path))[0]
        if args.periodic:
            mark_periodic(ax, par, path, stem, args)
        if zoom:
            ax.set_xlim(zoom[0], zoom[1])
            ax.set_ylim(zoom[2], zoom[3])
        if ax.get_legend_handles_labels()[0]:
            ax.legend(loc="lower right", fontsize=6.5)
        seeds = " (orbits from --seeds)" if par.get("seeds_file") else ""
        ax.set_title(f"{c.scene_label(par)}: $\\ell$ = {c.num(par.get('l', 0))}, h = {c.num(par.get('h', 0))}{seeds}",
                     fontsize=8)
        c.save(fig, args.out, f"poincare_{stem}")


if __name__ == "__main__":
    main()
