#!/usr/bin/python3
"""GALI_k of a 3-torus, a 2-torus and a chaotic orbit side by side, from three
`lgi indicators --gali` files (experiments/INDICATORS.md: /gali t, log10_gali, k = 2..6).

Usage: gali_tori.py --out DIR --name NAME --torus3 A.h5 --torus2 B.h5 --chaos C.h5 [--json OUT.json]

Writes DIR/NAME.{pdf,png}: (a), (b) log10 GALI_k against log10 t with, dashed, the power
laws of Skokos, Bountis & Antonopoulos (Physica D 231 (2007) 30) for an s-torus of a system
with N = 3 degrees of freedom (gali.law: GALI_k constant for k <= s, t^-(k-s) up to
k = 6 - s, t^-2(k-3) above), started where the fitted window starts; (c) log10 GALI_k
against t (linear samples) with, dashed, the exponential decay
exp(-[(l1 - l2) + ... + (l1 - lk)] t) from the file's Lyapunov spectrum. The slopes are
fitted over the last decade of t (tori, as gali.py does), the rates (chaos) from a tenth of the
run on while GALI_k / GALI_(k-1), about the k-th singular value, is above 1e-14;
--json writes them, the laws, the rates and the spectrum for the paper's text.
"""
import json

import numpy as np

import lgi_plot_common as c
from gali import FLOOR, law

ROUNDOFF = -14.0  # log10 of the k-th singular value below which GALI_k is round-off


def load(path, want_spectrum=False):
    with c.h5py.File(path, "r") as f:
        if "gali" not in f:
            c.die(f"{path}: no /gali (not a file written by lgi indicators --gali)")
        t = np.asarray(f["gali"]["t"][()])
        v = np.asarray(f["gali"]["log10_gali"][()])
        spacing = f["gali"].attrs.get("spacing", "log")
        spacing = spacing.decode() if isinstance(spacing, bytes) else str(spacing)
        ind = {k: np.asarray(f["indicators"][k][()]) for k in f["indicators"]}
        par = c.attrs(f["parameters"])
    if want_spectrum and "spectrum" not in ind:
        c.die(f"{path}: no spectrum (run lgi indicators with --spectrum)")
    ok = np.cumsum(~(v[:, 0] > FLOOR)) == 0
    return t[ok], v[ok], spacing, ind, par


def torus_panel(ax, path, s, label):
    t, v, spacing, ind, par = load(path)
    if spacing != "log":
        c.die(f"{path}: a torus needs log-spaced samples (--gali-spacing log)")
    x = np.log10(t)
    fit = x >= x.max() - 1.0
    slopes = []
    for k in range(5):
        sl = float(np.polyfit(x[fit], v[fit, k], 1)[0])
        slopes.append(sl)
        line, = ax.plot(x, v[:, k], lw=1.0, label=f"GALI$_{k + 2}$: {sl:.2f} (law {law(k + 2, s):g})")
        x0 = x[fit][0]
        ax.plot(x[fit], v[fit, k][0] + law(k + 2, s) * (x[fit] - x0), ls="--", lw=1.1, color=line.get_color())
    ax.set_xlabel("$\\log_{10} t$")
    ax.set_title(f"{label}\n{c.scene_label(par)}, MEGNO {float(ind['megno'][0]):.2f}", fontsize=8)
    ax.legend(fontsize=6.5, title="slope over the last decade", title_fontsize=6.5, loc="lower left")
    return {"slopes": slopes, "laws": [law(k, s) for k in range(2, 7)], "window": [float(t[fit][0]), float(t[-1])],
            "megno": float(ind["megno"][0]), "t_end": float(t[-1])}


def chaos_panel(ax, path, label):
    t, v, spacing, ind, par = load(path, want_spectrum=True)
    if spacing != "linear":
        c.die(f"{path}: a chaotic orbit needs linear samples (--gali-spacing linear)")
    lam = np.sort(np.asarray(ind["spectrum"][0]))[::-1]
    rates, expected = [], []
    windows = []
    for k in range(5):
        # GALI_k / GALI_(k-1) is about the k-th singular value: fit while it is above round-off
        ratio = v[:, k] - (v[:, k - 1] if k > 0 else 0.0)
        fit = (t >= 0.1 * t.max()) & (np.cumsum(~(ratio > ROUNDOFF)) == 0)
        windows.append([float(t[fit][0]), float(t[fit][-1])])
        r = float(-np.polyfit(t[fit], v[fit, k], 1)[0] * np.log(10))
        e = float(sum(lam[0] - lam[j] for j in range(1, k + 2)))
        rates.append(r)
        expected.append(e)
        line, = ax.plot(t, v[:, k], lw=1.0, label=f"GALI$_{k + 2}$: rate {r:.2f} (spectrum {e:.2f})")
        t0 = t[fit][0]
        ax.plot(t[fit], v[fit, k][0] - e * (t[fit] - t0) / np.log(10), ls="--", lw=1.1, color=line.get_color())
    ax.set_xlabel("$t$")
    ax.set_title(f"{label}\n{c.scene_label(par)}, MEGNO {float(ind['megno'][0]):.1f}", fontsize=8)
    ax.legend(fontsize=6.5, title="$-d\\ln$ GALI$_k/dt$", title_fontsize=6.5, loc="lower left")
    return {"rates": rates, "expected": expected, "spectrum": lam.tolist(), "windows": windows,
            "megno": float(ind["megno"][0]), "t_end": float(par.get("t_end", t[-1]))}


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--name", required=True)
    p.add_argument("--torus3", required=True)
    p.add_argument("--torus2", required=True)
    p.add_argument("--chaos", required=True)
    p.add_argument("--json")
    args = p.parse_args()
    fig, axes = c.plt.subplots(1, 3, figsize=(11.5, 4.0), constrained_layout=True)
    out = {"torus3": torus_panel(axes[0], args.torus3, 3, "(a) a 3-torus"),
           "torus2": torus_panel(axes[1], args.torus2, 2, "(b) a 2-torus"),
           "chaos": chaos_panel(axes[2], args.chaos, "(c) a chaotic orbit")}
    axes[0].set_ylabel("$\\log_{10}$ GALI$_k$")
    c.save(fig, args.out, args.name)
    if args.json:
        with open(args.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
