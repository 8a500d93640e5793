#!/usr/bin/python3
"""Long-time invariant errors from `lgi long-time` files (experiments/RESULTS.md,
"long-time": /series with log-spaced samples and per-window maxima).

Usage: long_time.py --out DIR LT.h5 ...   (one file per scene × scheme)

Writes DIR/long_time.{pdf,png}: one row per scene, one column per monitored
quantity (energy, the scene's other invariants, orthogonality), log-log
against t; per scheme the window maxima (the largest error since the previous
sample, so no spike is lost) as a step line and the sampled value as dots;
grey guide lines ∝ t and ∝ √t (linear drift and a random walk of round-off).
"""
import numpy as np

import lgi_plot_common as c


NAMES = {"energy": "energy $H$", "angular_momentum_body": "$|\\Pi|$", "angular_momentum_space": "spatial momentum $R\\Pi$",
         "casimir_vertical_momentum": "$\\Pi\\cdot\\Gamma$", "lagrange_spin_momentum": "$\\Pi_3$",
         "orthogonality": "orthogonality", "kovalevskaya_k": "Kovalevskaya $K$",
         "casimir_field_momentum": "$\\Pi\\cdot R^T B$"}


def quantities(tab):
    return [k[: -len("_error_window_max")] for k in tab if k.endswith("_error_window_max")]


def main():
    args = c.parser(__doc__.split("\n\n")[0]).parse_args()
    if not args.files:
        c.die("no long-time files given")
    runs = []
    for p in args.files:
        tab = c.load_table(p, "series")
        if tab is None:
            c.die(f"{p}: no /series table")
        params = c.load_attrs(p, "parameters")
        diag = c.load_attrs(p, "diagnostics")
        runs.append((p, tab, params, diag))
    scenes = list(dict.fromkeys(c.scene_label(r[2].get("scene_file", r[0])) for r in runs))
    qnames = {s: list(dict.fromkeys(q for r in runs if c.scene_label(r[2].get("scene_file", r[0])) == s
                                    for q in quantities(r[1]))) for s in scenes}
    ncol = max(len(v) for v in qnames.values())
    fig, axes = c.plt.subplots(len(scenes), ncol, figsize=(7.0, 2.0 * len(scenes) + 0.5), squeeze=False)
    handles = {}
    for row, s in enumerate(scenes):
        mine = [r for r in runs if c.scene_label(r[2].get("scene_file", r[0])) == s]
        for col, q in enumerate(qnames[s]):
            ax = axes[row, col]
            ymins, tmax, tmin = [], 0, np.inf
            for p, tab, params, diag in mine:
                if q + "_error_window_max" not in tab:
                    continue
                scheme = params.get("scheme", "?")
                st = c.scheme_style(scheme)
                t = tab["time"]
                wm = tab[q + "_error_window_max"]
                val = tab[q + "_error"]
                keep = (t > 0) & np.isfinite(wm)
                if not keep.any():
                    continue
                wm_pos = np.where(wm[keep] > 0, wm[keep], np.nan)  # exact zeros: not drawn on a log axis
                if not np.isfinite(wm_pos).any():
                    continue
                h, = ax.step(t[keep], wm_pos, where="pre", color=st["color"], lw=1.0,
                             label=f"{scheme}, h = {params.get('dt', float('nan')):g} ({s})")
                ax.plot(t[keep], np.where(val[keep] > 0, val[keep], np.nan), ".", color=st["color"], ms=1.6)
                handles.setdefault(h.get_label(), h)
                first = wm_pos[: max(1, len(wm_pos) // 10)]
                if np.isfinite(first).any():
                    ymins.append(np.nanmedian(first))
                tmax, tmin = max(tmax, t[keep].max()), min(tmin, t[keep].min())
                status = diag.get("status", "ok")
                if status != "ok":
                    ax.annotate(status[:40], (t[keep][-1], wm_pos[-1]), fontsize=5, color=st["color"])
            ax.set_xscale("log")
            ax.set_yscale("log")
            if ymins and tmax > tmin:
                tt = np.array([tmin, tmax])
                y0 = min(ymins)
                yl = ax.get_ylim()
                g1, = ax.plot(tt, y0 * tt / tmin, color="0.55", ls="--", lw=0.7, zorder=0, label="guide ∝ t")
                g2, = ax.plot(tt, y0 * np.sqrt(tt / tmin), color="0.55", ls=":", lw=0.8, zorder=0, label="guide ∝ √t")
                ax.set_ylim(yl[0], max(yl[1], y0 * 10))
                handles.setdefault("guide ∝ t", g1)
                handles.setdefault("guide ∝ √t", g2)
            ax.set_title(NAMES.get(q, q.replace("_", " ")), loc="left", fontsize=7.5)
            ax.set_xlabel("t (s)")
            ax.set_ylabel(f"{s}\nerror (window max)" if col == 0 else "", fontsize=7)
        for col in range(len(qnames[s]), ncol):
            axes[row, col].set_visible(False)
    c.legend_below(fig, handles, ncol=4, fontsize=6.3)
    fig.tight_layout()
    c.save(fig, args.out, "long_time")


if __name__ == "__main__":
    main()
