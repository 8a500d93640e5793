#!/usr/bin/python3
"""Families of periodic orbits from `lgi periodic` files (experiments/PERIODIC.md:
/periodic, one row per orbit).

Usage: periodic.py --out DIR [--branches BIFURCATION.h5] [--l-range A:B] [--h-range A:B] [--l-nonneg]
                   PERIODIC.h5 ...

Writes, for each file, DIR/periodic_period_<stem>.{pdf,png}: the period T
against h along every family, coloured by the stability class of the orbits
(elliptic, hyperbolic, inverse hyperbolic), the events of the file (rows with
event fold, period_doubling, class_change) marked by open symbols, the families
started at a period doubling dashed and named with their parent (with more
than six families each is labelled by its number, named in the legend; T on
a log axis where it spans more than a factor 4); and
DIR/periodic_trace_<stem>.{pdf,png}: tr P (`reduced_trace`, the trace of the
reduced 2x2 monodromy) against h with the lines tr P = +-2 where the class
changes (|tr P| < 2 elliptic; the axis is linear within +-4 and logarithmic
beyond, so that strongly hyperbolic orbits stay in view).

And, for all the files together, DIR/periodic_plane_<stem of the first
file>.{pdf,png}: the families in the (l, h) plane, each a vertical segment at
its l from its least to its largest h, coloured by class along it, events
marked. With --branches (a file of `lgi bifurcation`) the segments are drawn
over its bifurcation diagram (scripts/plots/bifurcation.py's drawing; the
window as there, or --l-range / --h-range / --l-nonneg), beside a panel that
enlarges the families. Families of one file share an l: each is drawn a
little to the right of the previous one, so that overlapping families stay
apart (the offset is a drawing aid, not a value of l), a dotted line tying
its first orbit to its true (l, h), a black dot.

Refused with one line on stderr and exit 2: a file without /periodic (or
unreadable), a stability class other than the four, a --branches file
without /equilibria.
"""
import os
import sys

import numpy as np

import lgi_plot_common as c

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import bifurcation as bif  # noqa: E402

# Colours and marks apart from those of the equilibria (bifurcation.py), since both share a figure.
STABILITY = {"elliptic": ("elliptic", "tab:green"), "hyperbolic": ("hyperbolic", "tab:brown"),
             "inverse_hyperbolic": ("inverse hyperbolic", "deeppink"), "complex": ("complex", "tab:olive")}
# Open symbols: the curve through an event stays visible under its mark.
EVENTS = {"fold": ("fold", "v", "none", "k"), "period_doubling": ("period doubling", "s", "none", "k"),
          "class_change": ("class change", "P", "gold", "k")}
REQUIRED = ("family", "l", "h", "period", "stability")


def load(path):
    """The /periodic table of path with its defaults (event none, parent -1); dies on a
    file that is not one of lgi periodic or holds no orbit."""
    t = c.load_periodic(path, REQUIRED, "not a file written by lgi periodic")
    n = len(t["h"])
    if n == 0:
        c.die(f"{path}: /periodic holds no orbit")
    t.setdefault("event", np.array(["none"] * n, dtype=object))
    t.setdefault("parent", -np.ones(n, dtype=int))
    t.setdefault("equilibrium", -np.ones(n, dtype=int))
    unknown = sorted(set(t["stability"]) - set(STABILITY))
    if unknown:
        c.die(f"{path}: /periodic/stability holds '{unknown[0]}' (expected one of {', '.join(STABILITY)})")
    return t


def families(t):
    """[(family id, row positions in file order)], the order along each family."""
    return [(int(f), np.flatnonzero(t["family"] == f)) for f in np.unique(t["family"])]


def segment_classes(t, rows):
    """The class of each piece rows[k] -> rows[k+1]: that of its end that is no event row
    (an event sits on the border of two classes)."""
    out = []
    for a, b in zip(rows[:-1], rows[1:]):
        out.append(t["stability"][b] if t["event"][a] != "none" else t["stability"][a])
    return out


def draw_coloured(ax, x, y, t, rows, dashed, lw=1.3):
    """The polyline (x[rows], y[rows]) coloured by class, one line per run of one class (so
    that a dashed family's dashes run on); a single orbit as a dot."""
    if len(rows) == 1:
        r = rows[0]
        ax.plot(x[r], y[r], "o", ms=3, color=STABILITY[t["stability"][r]][1], zorder=3)
        return
    classes = segment_classes(t, rows)
    start = 0
    for k in range(1, len(classes) + 1):
        if k == len(classes) or classes[k] != classes[start]:
            run = rows[start:k + 1]
            ax.plot(x[run], y[run], color=STABILITY[classes[start]][1], ls=(0, (4, 2)) if dashed else "-", lw=lw,
                    zorder=3, solid_capstyle="butt")
            start = k


def draw_events(ax, x, y, t, rows=None):
    rows = np.arange(len(t["h"])) if rows is None else rows
    for name, (_, marker, face, edge) in EVENTS.items():
        sel = rows[t["event"][rows] == name]
        if len(sel):
            ax.plot(x[sel], y[sel], marker, ls="none", mfc=face, mec=edge, ms=5, mew=0.9, zorder=5)


def legend_handles(t, extra=(), prefix=""):
    """Handles for the classes present, the events present (their labels after prefix) and
    extra (handle, label) pairs."""
    H = c.plt.Line2D
    present = set(t["stability"])
    out = [(H([], [], color=STABILITY[s][1], lw=1.5), STABILITY[s][0]) for s in STABILITY if s in present]
    out += [(H([], [], marker=m, ls="none", mfc=fc, mec=ec, ms=5, mew=0.9), label)
            for name, (label, m, fc, ec) in EVENTS.items() if name in set(t["event"])]
    if len(t["parent"]) and np.any(t["parent"] >= 0):
        out.append((H([], [], color="0.3", ls="--", lw=1.3), "doubled family (from a period doubling)"))
    out = [(h, prefix + label) for h, label in out] + list(extra)
    return [h for h, _ in out], [label for _, label in out]


def family_name(t, fam, rows):
    parent = int(t["parent"][rows[0]])
    if parent >= 0:
        return f"{fam} (doubled, parent {parent})"
    eq = int(t["equilibrium"][rows[0]])
    return f"{fam} (eq. {eq})" if eq >= 0 else f"{fam}"


def label_family(ax, x, y, t, fam, rows, short=False):
    """The family's name (or, short, its number) at its last orbit."""
    r = rows[-1]
    ax.annotate(str(fam) if short else family_name(t, fam, rows), (x[r], y[r]), fontsize=6, xytext=(3, 2),
                textcoords="offset points", bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.8),
                zorder=6)


def title(path, t):
    par = c.load_attrs(path, "parameters")
    return f"{c.scene_label(par) if par.get('scene_file') else c.file_stem(path)}: $\\ell$ = {c.num(t['l'][0])}"


def period_figure(path, t, stem, out):
    fig, ax = c.plt.subplots(figsize=(5.6, 3.6))
    many = len(families(t)) > 6  # long names of many families overlap: numbers, and a list in the legend
    for fam, rows in families(t):
        draw_coloured(ax, t["h"], t["period"], t, rows, t["parent"][rows[0]] >= 0)
        label_family(ax, t["h"], t["period"], t, fam, rows, short=many)
    draw_events(ax, t["h"], t["period"], t)
    ax.set_xlabel("$h$")
    ax.set_ylabel("period $T$")
    if np.max(t["period"]) > 4 * np.min(t["period"]):  # doubled families far above the rest: T on a log axis
        ax.set_yscale("log")  # (its ticks: lgi_plot_common.fix_log_ticks)
    ax.set_title(title(path, t) + "; labels: family" + ("" if many else " (its equilibrium, or its parent)"),
                 fontsize=8)
    extra = [(c.plt.Line2D([], [], ls="none"), family_name(t, fam, rows)) for fam, rows in families(t)] if many else []
    handles, labels = legend_handles(t, extra)
    ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=6.5, borderaxespad=0)
    c.save(fig, out, f"periodic_period_{stem}")


def symlog_ticks(ax, top):
    """A y axis linear within +-4 (the classes change at +-2) and logarithmic beyond, labelled
    at 0, +-2, +-4 and the decades +-10^k in view."""
    from matplotlib import ticker
    ax.set_yscale("symlog", linthresh=4, linscale=1.5)
    decades = 10.0 ** np.arange(1, int(np.ceil(np.log10(top))) + 1)
    ticks = np.concatenate([-decades[::-1], [-4, -2, 0, 2, 4], decades])
    ax.yaxis.set_major_locator(ticker.FixedLocator(ticks))
    ax.yaxis.set_major_formatter(ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_locator(ticker.NullLocator())


def trace_figure(path, t, stem, out):
    if "reduced_trace" not in t:
        print(f"periodic.py: {path}: no /periodic/reduced_trace (an older file): periodic_trace_{stem} not drawn",
              file=sys.stderr)
        return
    fig, ax = c.plt.subplots(figsize=(5.6, 3.6))
    tr = t["reduced_trace"]
    fams = families(t)  # more than ten families: twenty colours, so that none repeats
    colours = c.plt.get_cmap("tab10" if len(fams) <= 10 else "tab20").colors
    for i, (fam, rows) in enumerate(fams):
        ls = "--" if t["parent"][rows[0]] >= 0 else "-"
        ax.plot(t["h"][rows], tr[rows], ls=ls, marker=".", ms=2.5, color=colours[i % len(colours)], lw=1.1, zorder=3,
                label=family_name(t, fam, rows))
    draw_events(ax, t["h"], tr, t)
    for v in (2, -2):
        ax.axhline(v, color="k", lw=0.8, ls=":", zorder=2)
    if np.nanmax(np.abs(tr)) > 4:
        symlog_ticks(ax, np.nanmax(np.abs(tr)))
    ax.set_xlabel("$h$")
    ax.set_ylabel("tr $P$ (reduced monodromy)")
    ax.set_title(title(path, t) + ": elliptic between the lines tr $P = \\pm 2$", fontsize=8)
    handles, labels = ax.get_legend_handles_labels()
    events, elabels = legend_handles({"stability": np.array([]), "event": t["event"], "parent": np.array([])})
    ax.legend(handles + events, [f"family {x}" for x in labels] + elabels, loc="upper left",
              bbox_to_anchor=(1.01, 1.0), fontsize=6.5, borderaxespad=0)
    c.save(fig, out, f"periodic_trace_{stem}")


def plane_segments(ax, tables, dl, names=False):
    """Every family as a vertical segment at its l (shifted by dl per family of a file),
    with its number at its top if names."""
    for t in tables:
        x = np.array(t["l"], dtype=float)
        for i, (fam, rows) in enumerate(families(t)):
            x[rows] += i * dl
            draw_coloured(ax, x, t["h"], t, rows, t["parent"][rows[0]] >= 0, lw=2.2)
            if i:  # where the family really starts: a dot at its l, tied to the shifted segment
                r = rows[0]
                ax.plot([t["l"][r], x[r]], [t["h"][r], t["h"][r]], color="0.3", lw=0.6, ls=":", zorder=4)
                ax.plot(t["l"][r], t["h"][r], "o", ms=2.2, color="0.2", zorder=4)
            if names:
                top = rows[np.argmax(t["h"][rows])]
                ax.annotate(str(fam), (x[top], t["h"][top]), fontsize=6, ha="center", xytext=(0, 3),
                            textcoords="offset points", zorder=6)
        draw_events(ax, x, t["h"], t)


def plane_window(tables, branches, args):
    """(l0, l1, h0, h1) of the whole plane: the diagram's window (bifurcation.py) widened to
    the families, or the families with a margin."""
    ls = np.concatenate([t["l"] for t in tables])
    hs = np.concatenate([t["h"] for t in tables])
    if branches is not None:
        l0, l1, h0, h1 = bif.default_window(branches[0], args)
        if not args.h_range:
            h0, h1 = min(h0, hs.min() - 0.05 * (h1 - h0)), max(h1, hs.max() + 0.05 * (h1 - h0))
        if not args.l_range:
            l0, l1 = min(l0, ls.min()), max(l1, ls.max())
        return l0, l1, h0, h1
    span_l, span_h = max(ls.max() - ls.min(), 0.4), max(hs.max() - hs.min(), 1e-3)
    l0, l1 = args.l_range or (ls.min() - 0.5 * span_l, ls.max() + 0.5 * span_l)
    h0, h1 = args.h_range or (hs.min() - 0.1 * span_h, hs.max() + 0.1 * span_h)
    return l0, l1, h0, h1


def plane_figure(tables, branches, args, stem):
    """The families in the (l, h) plane, over the bifurcation diagram of --branches if given;
    with it a second panel enlarges the families."""
    window = plane_window(tables, branches, args)
    ncols = 2 if branches is not None else 1
    fig, axes = c.plt.subplots(1, ncols, figsize=(8.4, 3.4) if ncols == 2 else (4.4, 3.4), squeeze=False)
    ax = axes[0, 0]
    extra = []
    if branches is not None:
        bt, J, w, name, labels = branches
        bif.draw_branches(ax, bt, J, w, labels, window)
        bhandles, blabels = ax.get_legend_handles_labels()
        extra = [(h, f"equilibria: {lab}") for h, lab in zip(bhandles, blabels)]
        fig.suptitle(f"{name}: families of periodic orbits over the relative equilibria", fontsize=8.5)
    else:
        ax.set_title("families of periodic orbits (vertical segments at their $\\ell$)", fontsize=8)
    nfam = max(len(np.unique(t["family"])) for t in tables)
    dl = (0.006 if branches is not None else 0.03) * (window[1] - window[0])  # apart, yet near their l
    plane_segments(ax, tables, dl, names=branches is None)
    if branches is None:  # the last family of the largest l shifted right by (nfam - 1) dl: keep it in view
        window = (window[0], max(window[1], max(t["l"].max() for t in tables) + nfam * dl)) + tuple(window[2:])
    ax.set_xlim(window[0], window[1])
    ax.set_ylim(window[2], window[3])
    last = ax
    if branches is not None:
        last = axes[0, 1]
        ls = np.concatenate([t["l"] for t in tables])
        hs = np.concatenate([t["h"] for t in tables])
        pad_h = 0.08 * max(hs.max() - hs.min(), 1e-3)
        zoom_span = max(4 * nfam * dl, 0.1 * (window[1] - window[0]), ls.max() - ls.min() + 2 * nfam * dl)
        mid = 0.5 * (ls.min() + ls.max() + (nfam - 1) * dl)
        zoom = (mid - 0.5 * zoom_span, mid + 0.5 * zoom_span, hs.min() - pad_h, hs.max() + pad_h)
        bif.draw_branches(last, bt, J, w, {}, zoom)
        plane_segments(last, tables, dl, names=True)
        last.set_xlim(zoom[0], zoom[1])
        last.set_ylim(zoom[2], zoom[3])
        last.set_title("enlarged: families numbered, shifted in $\\ell$", fontsize=7.5)
        ax.indicate_inset_zoom(last, edgecolor="0.4")
    for a in axes.ravel():
        a.set_xlabel("$\\ell = \\Pi\\cdot\\Gamma$")
    ax.set_ylabel("$h$")
    merged = {k: np.concatenate([t[k] for t in tables]) for k in ("stability", "event", "parent")}
    handles, labels = legend_handles(merged, extra, "periodic orbits: ")
    if ncols == 2:
        # fixed margins: tight_layout would count the zoom's connector lines and squeeze the panels
        fig.subplots_adjust(left=0.07, right=0.98, bottom=0.3, top=0.86, wspace=0.22)
        fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=6.5, bbox_to_anchor=(0.5, 0.0))
    else:
        ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=6.5, borderaxespad=0)
    c.save(fig, args.out, f"periodic_plane_{stem}")


def read_branches(path):
    try:
        with c.h5py.File(path, "r") as f:
            if "equilibria" not in f:
                c.die(f"--branches: {path}: no /equilibria group (not a file written by lgi bifurcation)")
            t = {k: np.asarray(f["equilibria"][k][()]) for k in f["equilibria"]}
            J, w, name = bif.body(f)
            labels = bif.branch_labels(f)
    except OSError as e:
        c.die(f"--branches: {path}: cannot read ({e})")
    return t, J, w, name, labels


def main():
    p = c.add_plane_options(c.parser(__doc__.split("\n\n")[0]))
    p.add_argument("--branches", metavar="BIFURCATION.h5",
                   help="a file of lgi bifurcation: the families are drawn over its (l, h) diagram")
    args = p.parse_args()
    if not args.files:
        c.die("give at least one file written by lgi periodic")
    branches = read_branches(args.branches) if args.branches else None
    tables = [load(path) for path in args.files]
    stems = c.unique_names([c.file_stem(p) for p in args.files], args.files)
    for path, t, stem in zip(args.files, tables, stems):
        period_figure(path, t, stem, args.out)
        trace_figure(path, t, stem, args.out)
    plane_figure(tables, branches, args, stems[0])


if __name__ == "__main__":
    main()
