#!/usr/bin/python3
"""The (l, h) bifurcation diagram of a heavy top from `lgi bifurcation` files
(experiments/EQUILIBRIA.md: /equilibria, every branch of relative equilibria).

Usage: bifurcation.py --out DIR [--l-range A:B] [--h-range A:B] [--k-range A:B] [--l-nonneg]
                      [--periodic P.h5 ...] BRANCHES.h5 ...

Writes DIR/bifurcation_<scene stem>.{pdf,png}: h against l along every branch,
coloured by Grammel's stability class (docs/atlas.md §3), folds (the cusps,
triangles) and changes of class along a branch (diamonds) marked, each branch
named by its asymptotic ends (/parameters branch_labels: hanging, upright,
+-e_i). The default window frames the folds and class changes (the cusps);
--l-range, --h-range and --l-nonneg (l >= 0 only: the diagram is symmetric)
set it. The legend is outside the axes. Where the scene is integrable in
closed form the known critical sets are drawn under the branches as grey
dashes: the free body's principal-axis rotations h = l²/(2A_i), and the
Lagrange top's carrousels and sleeping top (docs/atlas.md §5).

A file of `lgi bifurcation --appelrot L,...` (a Kovalevskaya top) also gives
DIR/appelrot_<file stem>.{pdf,png}: the (h, k) diagram at each l, in the scaled
values h/(J3 c) and k = K/c² (docs/atlas.md §9): the range of k on the energy
surfaces found by lgi (grey; white above it, "no motion"), the arcs of the
Appelrot families (k = 0, k = (h − l²/2)², the parametric family, and at l = 0
the line k = 1 + h²) that are realised as critical values of (H, K) on the
leaf (column /appelrot realised, found by lgi's critical-point solver; the rest
of the algebraic families is not drawn), the relative equilibria (black dots)
and the chambers between the arcs lettered A, B, ..., with their number of
Liouville tori where lgi's counts in them (/appelrot_regions) agree. A file written before
the realised column existed gets the older drawing: the arcs inside the
attained range (solid where they bound it, dotted inside). --l-range and
--l-nonneg choose the panels (values of l), --h-range and --k-range the window
(default: from the least energy to 1.5 above the highest relative equilibrium,
and the realised arcs' k there). --periodic P.h5 (repeatable; files of `lgi
periodic` on the same top) draws their orbits at each panel's l into it, one
line per family through its orbits' (h/(J3 c), k), coloured by stability
(appelrot_orbits.py): the critical orbits lie on the realised arcs.
"""
import os
import tomllib

import numpy as np

import appelrot_orbits
import lgi_plot_common as c

CLASSES = {0: ("linearly stable", "tab:blue"), 1: ("singly unstable", "tab:red"),
           2: ("doubly unstable", "tab:purple"), 3: ("complex unstable", "tab:orange")}


def branch_labels(f):
    """{branch id: its asymptotic ends} from /parameters branch_labels ("id: label" lines)."""
    text = c.attrs(f["parameters"]).get("branch_labels", "")
    out = {}
    for line in text.splitlines():
        if ":" in line:
            k, v = line.split(":", 1)
            out[int(k)] = v.strip()
    return out


def default_window(t, args):
    """(l0, l1, h0, h1): the folds, class changes and static equilibria framed with a
    margin; the 90th percentiles of |l| and h where there are none (the free body)."""
    marks = (t["fold"] == 1) | (t.get("class_change", np.zeros_like(t["fold"])) == 1)
    lm = np.abs(t["l"][marks])
    if len(lm) and lm.max() > 0:
        L = 1.5 * lm.max()
    else:
        L = np.percentile(np.abs(t["l"]), 90) if len(t["l"]) else 1.0
    l0, l1 = args.l_range if args.l_range else ((0.0 if args.l_nonneg else -L), L)
    if args.h_range:
        return l0, l1, args.h_range[0], args.h_range[1]
    inside = (t["l"] >= l0) & (t["l"] <= l1)
    hs = t["h"][inside]
    if not len(hs):
        return l0, l1, -1.0, 1.0
    lo = hs.min()
    hm = t["h"][marks & inside]
    hi = max(hm.max(), np.percentile(hs, 25)) if len(hm) else np.percentile(hs, 90)
    pad = 0.08 * (hi - lo if hi > lo else 1.0)
    return l0, l1, lo - pad, hi + 3 * pad


def merged(names):
    """Names of branches drawn on one curve: "+e2", "-e2" -> "±e2", others joined by ", "."""
    names = sorted(set(names))
    if len(names) == 2 and names[0][1:] == names[1][1:] and {names[0][0], names[1][0]} == {"+", "-"}:
        return "±" + names[0][1:]
    return ", ".join(names)


def label_branches(ax, t, labels, window):
    """Each curve's name once, at a point in view: a branch and its mirror l -> -l share a name,
    and branches drawn on one curve (the degenerate families +-e_i) get one merged label."""
    l0, l1, h0, h1 = window
    spots = []  # (l, h, [names])
    for b in np.unique(t["branch"]):
        name = labels.get(int(b))
        if not name or any(name in names for _, _, names in spots if name[0] not in "+-" or " " in name):
            continue
        sel = (t["branch"] == b) & (t["fold"] == 0) & (t["l"] > l0) & (t["l"] < l1) & (t["h"] > h0) & (t["h"] < h1)
        if sel.sum() < 2:
            continue
        k = np.flatnonzero(sel)[int(0.6 * (sel.sum() - 1))]
        scale = (l1 - l0) + (h1 - h0)
        for spot in spots:
            if abs(spot[0] - t["l"][k]) + abs(spot[1] - t["h"][k]) < 1e-6 * scale:
                spot[2].append(name)
                break
        else:
            spots.append((t["l"][k], t["h"][k], [name]))
    for l, h, names in spots:
        ax.annotate(merged(names), (l, h), fontsize=6, xytext=(3, 3), textcoords="offset points",
                    bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.8), zorder=5)


def body(f):
    """J (diagonal as given), m g chi, from the scene text stored in the file."""
    scene = tomllib.loads(c.attrs(f["parameters"])["scene_toml"])
    b = scene["body"]
    J = np.array(b.get("inertia", b.get("inertia_cm", [1, 1, 1])), dtype=float)
    g = scene.get("gravity", {}).get("g", 9.81) if "gravity" in scene else 0.0
    chi = np.array(b.get("center_of_mass", [0, 0, 0]), dtype=float)
    return J, b.get("mass", 0.0) * g * chi, scene.get("name", "")


def overlays(ax, J, w, l0, l1):
    l = np.linspace(l0, l1, 400)
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


FAMILIES = {0: ("k = 0", "tab:blue"), 1: ("$k = (h - \\ell^2/2)^2$", "tab:red"),
            2: ("parametric family", "tab:green"), 3: ("$k = 1 + h^2$ ($\\ell = 0$)", "tab:purple")}


def attained(h, k, rng_h, rng_lo, rng_hi, comps):
    """Per point: 2 on the boundary of the attained range (k_min or k_max of a component,
    to 1 % of the k scale), 1 inside it, 0 outside (no motion there)."""
    tol = 0.01 * max(1.0, np.nanmax(rng_hi) if len(rng_hi) else 1.0)
    out = np.zeros(len(h), dtype=int)
    for comp in np.unique(comps):
        sel = comps == comp
        hh, order = rng_h[sel], np.argsort(rng_h[sel])
        hh, lo, hi = hh[order], rng_lo[sel][order], rng_hi[sel][order]
        if len(hh) < 2:
            continue
        span = (h >= hh[0]) & (h <= hh[-1])
        klo, khi = np.interp(h, hh, lo), np.interp(h, hh, hi)
        inside = span & (k >= klo - tol) & (k <= khi + tol)
        edge = inside & ((np.abs(k - klo) <= tol) | (np.abs(k - khi) <= tol))
        out = np.maximum(out, np.where(edge, 2, np.where(inside, 1, 0)))
    return out


def chamber_map(walls, rng, r, hlim, klim, size=240):
    """The chambers of the (h, k) window: the connected parts of the attained range that the
    realised arcs (walls) cut apart, on a size × size raster. Returns (labels, count, hs, ks)."""
    from scipy import ndimage
    hs = np.linspace(hlim[0], hlim[1], size)
    ks = np.linspace(klim[0], klim[1], size)
    H, K = np.meshgrid(hs, ks)
    inside = np.zeros(H.shape, dtype=bool)
    for comp in np.unique(rng["component"][r]):
        sel = r & (rng["component"] == comp)
        order = np.argsort(rng["h_scaled"][sel])
        h, lo, hi = rng["h_scaled"][sel][order], rng["k_min"][sel][order], rng["k_max"][sel][order]
        if len(h) > 1:
            inside |= (H >= h[0]) & (H <= h[-1]) & (K > np.interp(H, h, lo)) & (K < np.interp(H, h, hi))
    wall = np.zeros(H.shape, dtype=bool)
    for h, k in walls:  # rasterise each arc, densified so that it leaves no holes
        ok = np.isfinite(k)
        for i in range(len(h) - 1):
            if not (ok[i] and ok[i + 1]):
                continue
            t = np.linspace(0.0, 1.0, 8)
            x = (h[i] + t * (h[i + 1] - h[i]) - hlim[0]) / (hlim[1] - hlim[0]) * (size - 1)
            y = (k[i] + t * (k[i + 1] - k[i]) - klim[0]) / (klim[1] - klim[0]) * (size - 1)
            sel = (x >= 0) & (x <= size - 1) & (y >= 0) & (y <= size - 1)
            wall[np.rint(y[sel]).astype(int), np.rint(x[sel]).astype(int)] = True
    wall = ndimage.binary_dilation(wall, iterations=2)
    labels, count = ndimage.label(inside & ~wall)
    return labels, count, hs, ks


def label_chambers(ax, walls, rng, r, regions, l, hlim, klim):
    """Letter each chamber between the realised arcs (A, B, ... in order of least h) at its
    point farthest from the walls, and add its number of Liouville tori when lgi's counts
    (/appelrot_regions) in it are resolved and agree ("A: 2"); chambers under 0.5 % of the
    window are left unlabelled."""
    from scipy import ndimage
    labels, count, hs, ks = chamber_map(walls, rng, r, hlim, klim)
    found = []
    for i in range(1, count + 1):
        cell = labels == i
        if cell.mean() < 0.005:
            continue
        depth = ndimage.distance_transform_edt(np.pad(cell, 1))[1:-1, 1:-1]  # the frame counts as a wall
        y, x = np.unravel_index(np.argmax(depth), depth.shape)
        found.append((hs[x], ks[y], i))
    found.sort()
    for letter, (h, k, i) in zip("ABCDEFGHIJKLMNOPQRSTUVWXYZ", found):
        text = letter
        if regions is not None:
            sel = (regions["l"] == l)
            px = np.rint((regions["h_scaled"][sel] - hlim[0]) / (hlim[1] - hlim[0]) * (len(hs) - 1)).astype(int)
            py = np.rint((regions["k"][sel] - klim[0]) / (klim[1] - klim[0]) * (len(ks) - 1)).astype(int)
            view = (px >= 0) & (px < len(hs)) & (py >= 0) & (py < len(ks))
            tori = regions["tori"][sel][view][labels[py[view], px[view]] == i]
            if len(tori) and np.all(tori > 0) and np.all(tori == tori[0]):
                text = f"{letter}: {int(tori[0])}"
        ax.text(h, k, text, fontsize=6.5, ha="center", va="center", color="0.15", zorder=5,
                bbox=dict(boxstyle="round,pad=0.2", fc="white", ec="0.5", lw=0.5))


def label_regions(ax, rng, r, hlim, klim, chambers=False):
    """Name the two kinds of region of the (h, k) plane at a column in view: "motion" inside the
    attained range (its widest point; not where the chambers carry letters),
    "no motion" above it."""
    hs = rng["h_scaled"][r]
    inview = r & (rng["h_scaled"] > hlim[0]) & (rng["h_scaled"] < hlim[1])
    if not np.any(inview):
        return
    target = hlim[0] + 0.6 * (hlim[1] - hlim[0])  # a column a little right of the middle
    k = int(np.argmin(np.where(inview, np.abs(rng["h_scaled"] - target), np.inf)))
    h, lo, hi = rng["h_scaled"][k], rng["k_min"][k], rng["k_max"][k]
    box = dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.7)
    if not chambers:
        ax.text(h, 0.5 * (lo + hi), "motion", fontsize=6.5, ha="center", va="center", color="0.25", bbox=box)
    top = hs.max() if len(hs) else hlim[1]
    above = hi + 0.12 * (klim[1] - klim[0])
    if above < klim[1] and h < top:
        ax.text(h, above, "no motion", fontsize=6.5, ha="center", va="bottom", color="0.45")


def appelrot_panel(ax, l, cur, eq, rng, regions, args):
    r = rng["l"] == l
    for comp in np.unique(rng["component"][r]):
        sel = r & (rng["component"] == comp)
        ax.fill_between(rng["h_scaled"][sel], rng["k_min"][sel], rng["k_max"][sel], color="0.85", lw=0,
                        label="attained $(h, k)$" if comp == 0 else None)
    kmax = rng["k_max"][r].max() if np.any(r) else 4.0
    drawn_k = []  # k of the arcs drawn: the window frames them
    walls = []  # the realised arcs, NaN where not realised: they bound the chambers
    for fam, (label, colour) in FAMILIES.items():
        for branch in (-1, 0, 1):
            sel = (cur["l"] == l) & (cur["family"] == fam) & (cur["branch"] == branch)
            if not np.any(sel):
                continue
            order = np.argsort(cur["s"][sel])
            h, k = cur["h_scaled"][sel][order], cur["k"][sel][order]
            first = branch != 1 or fam != 2
            if "realised" in cur:  # only the critical values lgi found (docs/atlas.md §9)
                real = cur["realised"][sel][order] == 1
                if np.any(real):
                    ax.plot(h, np.where(real, k, np.nan), color=colour, lw=1.3, label=label if first else None)
                    drawn_k.append((h[real], k[real]))
                    walls.append((h, np.where(real, k, np.nan)))
                continue
            where = attained(h, k, rng["h_scaled"][r], rng["k_min"][r], rng["k_max"][r], rng["component"][r])
            ax.plot(h, np.where(where == 2, k, np.nan), color=colour, lw=1.3, label=label if first else None)
            ax.plot(h, np.where(where == 1, k, np.nan), color=colour, lw=0.9, ls=":")
    e = eq["l"] == l
    ax.plot(eq["h_scaled"][e], eq["k"][e], "ko", ms=3, label="relative equilibria", zorder=4)
    appelrot_orbits.draw(ax, l, getattr(args, "appelrot_scale", 1.0), getattr(args, "periodic_tables", []))
    if args.h_range:
        h0, h1 = args.h_range
    elif np.any(r):  # from the least energy to 1.5 above the highest relative equilibrium: the critical arcs
        h0 = rng["h_scaled"][r].min() - 0.1
        h1 = min(rng["h_scaled"][r].max(), max(eq["h_scaled"][eq["l"] == l].max(initial=h0) + 1.5, h0 + 2.0))
    else:
        h0, h1 = -1.1, 5.0
    if args.k_range:
        k0, k1 = args.k_range
    else:
        view = r & (rng["h_scaled"] <= h1)
        kmax = rng["k_max"][view].max() if np.any(view) else kmax
        ks = [k[(h >= h0) & (h <= h1)] for h, k in drawn_k]
        ks = np.concatenate(ks) if ks else np.array([])
        if len(ks) and ks.max() > 0:  # frame the realised arcs
            kmax = ks.max()
        k0, k1 = -0.05 * kmax, 1.12 * kmax
    ax.set_xlim(h0, h1)
    ax.set_ylim(k0, k1)
    label_regions(ax, rng, r, (h0, h1), (k0, k1), chambers="realised" in cur)
    if "realised" in cur:
        label_chambers(ax, walls, rng, r, regions, l, (h0, h1), (k0, k1))
    ax.set_xlabel("$h / (J_3 c)$")
    ax.set_ylabel("$k = K / c^2$")
    ax.set_title(f"$\\ell$ = {c.num(l)} (scaled {c.num(cur['l_scaled'][cur['l'] == l][0])})", fontsize=8)


def appelrot_figure(f, stem, out, args):
    """The Kovalevskaya (h, k) diagram at each l of the file (scaled values)."""
    cur = {k: np.asarray(f["appelrot"][k][()]) for k in f["appelrot"]}
    eq = {k: np.asarray(f["appelrot_equilibria"][k][()]) for k in f["appelrot_equilibria"]}
    rng = {k: np.asarray(f["appelrot_range"][k][()]) for k in f["appelrot_range"]}
    regions = ({k: np.asarray(f["appelrot_regions"][k][()]) for k in f["appelrot_regions"]}
               if "appelrot_regions" in f else None)
    args.appelrot_scale = float(c.attrs(f["appelrot"]).get("J3", 1.0)) * float(c.attrs(f["appelrot"]).get("c", 1.0))
    ls = np.unique(cur["l"])
    if args.l_nonneg:
        ls = ls[ls >= 0]
    if args.l_range:
        ls = ls[(ls >= args.l_range[0]) & (ls <= args.l_range[1])]
    if not len(ls):
        c.die(f"{stem}: no value of l of the file in the chosen --l-range / --l-nonneg")
    cols = min(3, len(ls))
    rows = (len(ls) + cols - 1) // cols
    fig, axes = c.plt.subplots(rows, cols, figsize=(3.2 * cols, 2.9 * rows), squeeze=False)
    for ax, l in zip(axes.ravel(), ls):
        appelrot_panel(ax, l, cur, eq, rng, regions, args)
    for ax in axes.ravel()[len(ls):]:
        ax.axis("off")
    handles, labels = axes.ravel()[0].get_legend_handles_labels()
    if "realised" not in cur:
        handles.append(c.plt.Line2D([], [], color="0.3", ls=":"))
        labels.append("arc inside the attained range")
    if "realised" in cur:
        handles.append(c.plt.Line2D([], [], ls="none", marker="s", mfc="white", mec="0.5", ms=7))
        labels.append("A, B, ...: chambers between the realised arcs; A: n, n Liouville tori over each value")
    for handle, label in appelrot_orbits.legend_entries(getattr(args, "periodic_tables", [])):
        handles.append(handle)
        labels.append(label)
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=6.5, bbox_to_anchor=(0.5, -0.02))
    extra = max(0, -(-len(labels) // 3) - 3)  # room for a legend longer than three rows
    fig.tight_layout(rect=(0, (0.1 if rows == 1 else 0.06) + 0.06 * extra / rows, 1, 1))
    c.save(fig, out, f"appelrot_{stem}")


def draw_branches(ax, t, J, w, labels, window):
    """The branches of /equilibria t on ax, coloured by class, folds and class changes
    marked, named, with the closed-form overlays; the legend entries of the classes and
    marks. Also drawn under the families of scripts/plots/periodic.py."""
    l0, l1, h0, h1 = window
    overlays(ax, J, w, l0, l1)
    cc = t.get("class_change", np.zeros_like(t["fold"]))
    for b in np.unique(t["branch"]):
        sel = (t["branch"] == b) & (t["fold"] == 0)
        l, h, s = t["l"][sel], t["h"][sel], t["stability"][sel]
        for k in range(len(l) - 1):
            ax.plot(l[k:k + 2], h[k:k + 2], color=CLASSES[int(s[k])][1], lw=1.2, zorder=2)
    folds = t["fold"] == 1
    # Class changes often sit at the folds: open diamonds under the filled triangles, both visible.
    ax.plot(t["l"][cc == 1], t["h"][cc == 1], "D", mfc="white", mec="k", ms=6, mew=0.9, zorder=3,
            label="class change")
    ax.plot(t["l"][folds], t["h"][folds], "k^", ms=3.5, zorder=4, label="fold (cusp)")
    for k, (label, colour) in CLASSES.items():
        ax.plot([], [], color=colour, label=label)
    label_branches(ax, t, labels, window)


def bifurcation_figure(t, J, w, name, labels, args, stem):
    window = default_window(t, args)
    l0, l1, h0, h1 = window
    fig, ax = c.plt.subplots(figsize=(5.6, 3.6))
    draw_branches(ax, t, J, w, labels, window)
    ax.set_xlim(l0, l1)
    ax.set_ylim(h0, h1)
    ax.set_xlabel("$\\ell = \\Pi\\cdot\\Gamma$")
    ax.set_ylabel("$h$")
    ax.set_title(name, fontsize=8)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=6.5, borderaxespad=0)
    c.save(fig, args.out, f"bifurcation_{stem}")


def main():
    p = c.add_plane_options(c.parser(__doc__.split("\n\n")[0]), k_range=True)
    p.add_argument("--periodic", action="append", metavar="FILE",
                   help="an lgi periodic file of the same top: its orbits drawn into the (h, k) diagram (repeatable)")
    args = p.parse_args()
    args.periodic_tables = appelrot_orbits.load(args.periodic)
    if not args.files:
        c.die("give at least one file written by lgi bifurcation")
    for path in args.files:
        stem = os.path.splitext(os.path.basename(path))[0]
        with c.h5py.File(path, "r") as f:
            t = {k: np.asarray(f["equilibria"][k][()]) for k in f["equilibria"]}
            J, w, name = body(f)
            labels = branch_labels(f)
            if "appelrot" in f:
                appelrot_figure(f, stem, args.out, args)
        bifurcation_figure(t, J, w, name, labels, args, stem)


if __name__ == "__main__":
    main()
