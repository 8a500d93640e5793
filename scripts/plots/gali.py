#!/usr/bin/python3
"""GALI_k curves from `lgi indicators --gali` files (experiments/INDICATORS.md: /gali
index, t, log10_gali with the columns k = 2..6).

Usage: gali.py --out DIR [--torus-dim S] FILE.h5 ...

Writes DIR/gali_<file stem>.{pdf,png}: one panel per state (at most four). Log-spaced
samples (--gali-spacing log, for tori): log10 GALI_k against log10 t for k = 2..6, the
slopes fitted over the last decade of t in the legend and, dashed, the laws of Skokos,
Bountis & Antonopoulos (2008) for an s-torus (--torus-dim, default 3) in the
6-dimensional tangent space: GALI_k constant for k <= s, t^-(k-s) for s < k <= 6 - s,
t^-2(k-3) above. Linear samples (--gali-spacing linear, for
chaos): log10 GALI_k against t, the rates -d ln GALI_k / dt fitted over the decay in the
legend (fitted while GALI_2 > 1e-7, before the smallest singular values meet round-off).
Prints the fitted slopes or rates. The curves stop where GALI_2 reaches the
round-off floor (log10 GALI_2 below -15: the vectors agree to the last bit).
"""
import numpy as np

import lgi_plot_common as c

FLOOR = -15.0
WINDOW = -7.0  # linear files: the rates are fitted while log10 GALI_2 > WINDOW


def law(k, s):
    """The exponent of t in GALI_k on an s-torus, N = 3 (Skokos et al. 2008)."""
    return 0.0 if k <= s else (-(k - s) if k <= 6 - s else -2.0 * (k - 3))


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--torus-dim", type=int, default=3, choices=(1, 2, 3),
                   help="the torus dimension s of the dashed laws (log-spaced files)")
    args = p.parse_args()
    if not args.files:
        c.die("give at least one file written by lgi indicators --gali")
    for path in args.files:
        with c.h5py.File(path, "r") as f:
            if "gali" not in f:
                c.die(f"{path}: no /gali (not a file written by lgi indicators --gali)")
            g = {k: np.asarray(f["gali"][k][()]) for k in f["gali"]}
            log_t = f["gali"].attrs.get("spacing", "log") == "log"
            par = c.attrs(f["parameters"])
        states = np.unique(g["index"])[:4]
        fig, axes = c.plt.subplots(1, len(states), figsize=(3.6 * len(states), 3.2), squeeze=False)
        for ax, i in zip(axes[0], states):
            sel = g["index"] == i
            t, v = g["t"][sel], g["log10_gali"][sel]
            ok = np.cumsum(~(v[:, 0] > FLOOR)) == 0  # up to the first sample at the floor
            x = np.log10(t) if log_t else t
            if log_t:  # the last decade: the asymptotic power law
                fit = ok & (x >= x[ok].max() - 1.0)
            else:  # the decay past its first tenth, while GALI_2 > 1e-7: GALI_6's smallest
                # singular value falls twice as fast as GALI_2 and meets round-off (1e-16) there
                fit = ok & (x >= 0.1 * x[ok].max()) & (np.cumsum(~(v[:, 0] > WINDOW)) == 0)
            for k in range(5):
                s = np.polyfit(x[fit], v[fit, k], 1)[0] if fit.sum() > 2 else float("nan")
                if log_t:
                    label = f"GALI$_{k + 2}$ (slope {s:.2f})"
                    print(f"{path}: state {i}: GALI_{k + 2}: d log10 GALI / d log10 t = {s:.3f} "
                          f"over t in [{t[fit].min():.4g}, {t[fit].max():.4g}]")
                else:
                    label = f"GALI$_{k + 2}$ (rate {-s * np.log(10):.3f})"
                    print(f"{path}: state {i}: GALI_{k + 2}: -d ln GALI / dt = {-s * np.log(10):.4f} "
                          f"over t in [{t[fit].min():.4g}, {t[fit].max():.4g}]")
                line, = ax.plot(x[ok], v[ok, k], lw=1.0, label=label)
                if log_t and fit.any():
                    x0 = x[fit][0]
                    ax.plot(x[fit], v[fit, k][0] + law(k + 2, args.torus_dim) * (x[fit] - x0), ls="--", lw=0.7,
                            color=line.get_color())
            ax.set_xlabel("$\\log_{10} t$" if log_t else "$t$")
            ax.set_title(f"state {i}", fontsize=8)
            ax.legend(fontsize=6)
        axes[0][0].set_ylabel("$\\log_{10}$ GALI$_k$")
        fig.suptitle(f"{c.scene_label(par)}: GALI to t = {par.get('t_end')}, dt = {par.get('dt')} "
                     + (f"(dashed: the laws of a {args.torus_dim}-torus)" if log_t else "(chaos: exponential decay)"), fontsize=8)
        c.save(fig, args.out, f"gali_{c.file_stem(path)}")


if __name__ == "__main__":
    main()
