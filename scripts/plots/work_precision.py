#!/usr/bin/python3
"""Work-precision and convergence diagrams from `lgi work-precision` files
(experiments/RESULTS.md, "work-precision").

Usage: work_precision.py --out DIR WP.h5 ...   (one file per scene)

Writes
  DIR/work_precision.{pdf,png}: one panel per file, global error at t_end
      (the larger of attitude and momentum error) against the median CPU
      seconds of a run, log-log, one line per scheme (fixed-step schemes over
      their steps, adaptive ones over their tolerances);
  DIR/convergence.{pdf,png}: the same errors against the step h (fixed-step
      schemes only), with guide lines C h^p for the orders present and each
      scheme's fitted slope in the legend.
Rows that failed (status not "ok") or lie below the reference's own error
(below_reference_floor = 1, error NaN) are not drawn; the reference's
estimated error is drawn as a grey band when it is not zero.
"""
import numpy as np

import lgi_plot_common as c


def panels(n):
    cols = 1 if n == 1 else 2
    rows = (n + cols - 1) // cols
    return rows, cols


def scheme_rows(tab):
    names = list(dict.fromkeys(tab["scheme"]))
    for s in names:
        sel = np.array([x == s for x in tab["scheme"]])
        ok = sel & np.array([st == "ok" for st in tab["status"]]) & np.isfinite(tab["error"])
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


def draw(data, outdir, kind):
    rows, cols = panels(len(data))
    height = 2.9 * rows + 0.6 if kind == "wp" else 4.3 * rows
    fig, axes = c.plt.subplots(rows, cols, figsize=(7.0, height), squeeze=False)
    handles = {}
    for ax, (path, tab, params, ref) in zip(axes.flat, data):
        scene = c.scene_label(params.get("scene_file", path))
        est = float(ref.get("estimated_error", 0.0) or 0.0)
        orders = set()
        for s, sel, ok in scheme_rows(tab):
            st = c.scheme_style(s)
            if kind == "wp":
                x = tab["cpu_seconds_median"][ok]
                y = tab["error"][ok]
                order = np.argsort(x)
            else:
                if not np.all(np.isfinite(tab["dt"][sel])):
                    continue  # adaptive: no step
                x = tab["dt"][ok]
                y = tab["error"][ok]
                order = np.argsort(x)
                p = fitted_order(x, y)
                if p is not None:
                    orders.add(p)
            if len(x) == 0:
                continue
            label = s if kind == "wp" else (f"{s} (p≈{fitted_order(x, y):.1f})" if fitted_order(x, y) else s)
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
            ax.set_xlabel("CPU seconds (median of %d runs)" % int(np.nanmax(tab.get("repeats", np.array([1])))))
        ax.set_ylabel("global error at $t_{\\rm end}$")
        t_end = params.get("t_end")
        ax.set_title(f"{scene}" + (f", $t_{{\\rm end}}$ = {t_end:g} s" if t_end is not None else ""), loc="left")
    for ax in list(axes.flat)[len(data):]:
        ax.set_visible(False)
    if kind == "wp":
        fig.legend(list(handles.values()), list(handles.keys()), ncol=6, loc="upper center",
                   bbox_to_anchor=(0.5, 0.0), fontsize=6.2, frameon=False)
    fig.tight_layout()
    c.save(fig, outdir, "work_precision" if kind == "wp" else "convergence")


def main():
    args = c.parser(__doc__.split("\n\n")[0]).parse_args()
    if not args.files:
        c.die("no work-precision files given")
    data = load(args.files)
    draw(data, args.out, "wp")
    draw(data, args.out, "conv")


if __name__ == "__main__":
    main()
