#!/usr/bin/python3
"""Round-off over long runs: the energy error of `lgi long-time` files against
the number of steps (experiments/RESULTS.md, "long-time"), for Brouwer's law.

Usage: round_off.py --out DIR LT.h5 ...

Writes DIR/round_off.{pdf,png}: per file the window maxima of the relative
energy error (the largest since the previous sample) against the step count,
log-log, with guide lines through the last point ∝ n (a drift) and ∝ √n (a
random walk of round-off: Brouwer's law; E. Hairer, R. I. McLachlan,
A. Razakarivony, BIT 48 (2008) 231), and the exponent fitted over the last two
decades.
"""
import numpy as np

import lgi_plot_common as c


def main():
    args = c.parser(__doc__.split("\n\n")[0]).parse_args()
    if not args.files:
        c.die("no long-time files given")
    fig, ax = c.plt.subplots(figsize=(5.2, 3.8))
    for path in args.files:
        tab = c.load_table(path, "series")
        if tab is None or "energy_error_window_max" not in tab:
            c.die(f"{path}: no /series/energy_error_window_max (not a file of lgi long-time)")
        params = c.load_attrs(path, "parameters")
        n = np.asarray(tab["step"], dtype=float)
        e = np.asarray(tab["energy_error_window_max"], dtype=float)
        keep = (n > 0) & (e > 0)
        n, e = n[keep], np.maximum.accumulate(e[keep])
        tail = n >= n[-1] / 100.0
        p = np.polyfit(np.log(n[tail]), np.log(e[tail]), 1)[0] if tail.sum() > 2 else float("nan")
        label = f"{params.get('scheme', '?')} on {c.scene_label(params)}: $n^{{{p:.2f}}}$"
        ax.loglog(n, e, drawstyle="steps-post", lw=1.0, label=label)
        ref = np.array([n[-1] / 1e3, n[-1]])
        ax.loglog(ref, e[-1] * (ref / n[-1]), color="0.5", ls="--", lw=0.7)
        ax.loglog(ref, e[-1] * np.sqrt(ref / n[-1]), color="0.5", ls=":", lw=0.9)
    ax.set_xlabel("steps $n$")
    ax.set_ylabel("max $|H - H_0| / |H_0|$ so far")
    ax.set_title("guides through the last point: $\\propto n$ (dashed), $\\propto\\sqrt{n}$ (dotted)", fontsize=8)
    ax.legend(fontsize=7, loc="upper left")
    c.save(fig, args.out, "round_off")


if __name__ == "__main__":
    main()
