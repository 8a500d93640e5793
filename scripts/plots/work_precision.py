#!/usr/bin/python3
"""Work-precision and convergence diagrams from `lgi work-precision` files
(experiments/RESULTS.md, "work-precision").

Usage: work_precision.py --out DIR WP.h5 ...   (one file per scene)

Writes (DIR is created if missing)
  DIR/work_precision.{pdf,png}: one row per file, two panels: the attitude
      error at t_end (geodesic angle, rad) and the relative momentum error
      |Π − Π_ref|/|Π_ref| (no unit) against the median CPU seconds of a run,
      log-log, one line per scheme (fixed-step schemes over their steps,
      adaptive ones over their tolerances);
  DIR/convergence.{pdf,png}: the same two errors against the step h
      (fixed-step schemes only), with guide lines C h^p for the orders present
      and each scheme's fitted slope in the legend.
Every log axis has at least three labelled ticks (lgi_plot_common.fix_log_ticks).
Rows that failed (status not "ok") or lie below the reference's own error
(below_reference_floor = 1, error NaN) are not drawn; the reference's
estimated error is drawn as a grey band when it is not zero.
"""
import numpy as np

import lgi_plot_common as c


# The two error measures of a work-precision row (experiments/RESULTS.md): they have
# different units, so each gets its own panel.
MEASURES = [("error_attitude", "attitude error at $t_{\\rm end}$ (rad)", "attitude"),
            ("error_momentum", "momentum error at $t_{\\rm end}$, $|\\Pi-\\Pi_{\\rm ref}|/|\\Pi_{\\rm ref}|$", "momentum")]
FALLBACK = ("error", "error at $t_{\\rm end}$: max(attitude (rad), relative momentum)", "global error")


def measures(tab):
    """The error columns to draw: attitude (rad) and relative momentum error, each on its own
    panel; files without them (older lgi) fall back to the combined column, labelled as such."""
    have = [m for m in MEASURES if m[0] in tab]
    return have if have else [FALLBACK]


def scheme_rows(tab, column="error"):
    names = list(dict.fromkeys(tab["scheme"]))
    for s in names:
        sel = np.array([x == s for x in tab["scheme"]])
        ok = sel & np.array([st == "ok" for st in tab["status"]]) & np.isfinite(tab[column])
        yield s, sel, ok


def fitted_order(h, e):
    """Least-squares slope of log e against log h over the points above 1e3 ulps."""
    keep = np.isfinite(h) & np.isfinite(e) & (e > 1e-13) & (e < 1e-1)
    if keep.sum() < 2:
        return None
    return np.polyfit(np.log(h[keep]), np.log(e[keep]), 1)[0]


def load(files):
    out = []
    for p in files:
        tab = c.load_table(p, "results")
        if tab is None or "scheme" not in tab:
            c.die(f"{p}: no /results table")
        params = c.load_attrs(p, "parameters")
        ref = c.load_attrs(p, "reference")
        out.append((p, tab, params, ref))
    return out


def figure(data, kind):
    """The work-precision (kind "wp") or convergence ("conv") figure: one row per file, one
    column per error measure. Returns the matplotlib figure (not yet saved)."""
    ncols = max(len(measures(tab)) for _, tab, _, _ in data)
    rows = len(data)
    height = 2.7 * rows + 0.7 if kind == "wp" else 4.2 * rows
    fig, axes = c.plt.subplots(rows, ncols, figsize=(7.0, height), squeeze=False)
    handles = {}
    for row, (path, tab, params, ref) in enumerate(data):
        scene = c.scene_label(params.get("scene_file", path))
        est = float(ref.get("estimated_error", 0.0) or 0.0)
        t_end = params.get("t_end")
        mine = measures(tab)
        for col in range(len(mine), ncols):
            axes[row, col].set_visible(False)
        for ax, (column, ylabel, what) in zip(axes[row], mine):
            orders = set()
            for s, sel, ok in scheme_rows(tab, column):
                st = c.scheme_style(s)
                if kind == "wp":
                    x = tab["cpu_seconds_median"][ok]
                else:
                    if not np.all(np.isfinite(tab["dt"][sel])):
                        continue  # adaptive: no step
                    x = tab["dt"][ok]
                y = tab[column][ok]
                keep = (x > 0) & (y > 0)  # an exact zero has no place on a log axis
                x, y = x[keep], y[keep]
                if len(x) == 0:
                    continue
                order = np.argsort(x)
                p = fitted_order(x, y) if kind == "conv" else None
                if p is not None:
                    orders.add(p)
                label = f"{s} (p≈{p:.1f})" if p is not None else s
                h, = ax.loglog(x[order], y[order], color=st["color"], marker=st["marker"], ls=st["linestyle"],
                               ms=3.2, lw=1.0, label=label)
                handles.setdefault(s, h)
            if est > 0:
                ax.relim()
                ax.autoscale_view()
                yl = ax.get_ylim()
                lo = min(yl[0], est / 3)
                ax.axhspan(lo, est, color="0.88", zorder=0)
                ax.axhline(est, color="0.5", lw=0.6)
                ax.text(0.99, est, "reference's estimated error", transform=ax.get_yaxis_transform(),
                        ha="right", va="bottom", fontsize=5.5, color="0.35")
                ax.set_ylim(lo, yl[1])
            if kind == "conv":
                ax.legend(fontsize=5.0, ncol=2, loc="upper left", bbox_to_anchor=(0.0, -0.2), frameon=False)
                xl, yl = ax.get_xlim(), ax.get_ylim()
                x0 = np.sqrt(xl[0] * xl[1])
                for p in sorted({int(round(o)) for o in orders if o > 0.5}):
                    xs = np.array(xl)
                    y0 = np.sqrt(yl[0] * yl[1])
                    ax.loglog(xs, y0 * (xs / x0) ** p, color="0.6", ls=":", lw=0.7, zorder=0)
                    xt = xl[1] if p > 0 else xl[0]
                    yt = y0 * (xt / x0) ** p
                    if yl[0] < yt < yl[1]:
                        ax.text(xt, yt, f" $h^{{{p}}}$", fontsize=6, color="0.4", va="center")
                ax.set_xlim(xl)
                ax.set_ylim(yl)
                ax.set_xlabel("step h (s)")
            else:
                ax.set_xlabel("CPU seconds per run (median of %d repeats)" % int(np.nanmax(tab.get("repeats", np.array([1])))))
            ax.set_ylabel(ylabel, fontsize=7.5)
            ax.set_title(f"{scene}: {what}" + (f", $t_{{\\rm end}}$ = {t_end:g} s" if t_end is not None else ""),
                         loc="left", fontsize=8)
    if kind == "wp":
        c.legend_below(fig, handles, ncol=6, fontsize=6.2)
    fig.tight_layout()
    for ax in fig.axes:
        c.fix_log_ticks(ax)
    return fig


def main():
    args = c.parser(__doc__.split("\n\n")[0]).parse_args()
    if not args.files:
        c.die("no work-precision files given")
    data = load(args.files)
    c.save(figure(data, "wp"), args.out, "work_precision")
    c.save(figure(data, "conv"), args.out, "convergence")


if __name__ == "__main__":
    main()
