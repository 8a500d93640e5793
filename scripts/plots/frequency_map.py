#!/usr/bin/python3
"""A frequency map of a Cardan top on one energy level (Laskar, Physica D 67 (1993) 257),
from `lgi frequencies --state-file` (experiments/FREQUENCIES.md "Cardan tops") with three
observables, one per degree of freedom, and the family file of the states
(scripts/plots/cardan_family.py: /family theta, rate_ratio).

Usage: frequency_map.py --out DIR --name NAME --family FAMILY.h5 [--order K] FREQUENCIES.h5

The frequency vector of state i is nu = (w1, w2, w3), the leading line of each observable
(/frequency_diffusion frequency, rows index == i in the order asked); its diffusion index
is Laskar's log10 |nu' - nu''| / |nu'| over the run's two halves (frequency_first_half,
frequency_second_half). Writes DIR/NAME.{pdf,png}: (a) w1/w3 against w2/w3, coloured by
the diffusion index, with the resonance lines k1 w1 + k2 w2 + k3 w3 = 0 of order
|k1| + |k2| + |k3| <= K (default 5; coprime k, k1, k2 not both 0) that cross the view;
(b) the diffusion index over the initial conditions (theta, rate ratio). Prints the count
of states and the share with a diffusion index above -3.
"""
import math

import numpy as np

import lgi_plot_common as c


def frequency_vectors(path):
    with c.h5py.File(path, "r") as f:
        d = {k: np.asarray(f["frequency_diffusion"][k][()]) for k in f["frequency_diffusion"]}
        par = c.attrs(f["parameters"])
    names = [s.decode() if isinstance(s, bytes) else str(s) for s in d["observable"]]
    per = len(dict.fromkeys(names))
    if per != 3:
        c.die(f"{path}: {per} observables per state; the map needs three, one per degree of freedom")
    shape = (-1, 3)
    nu = d["frequency"].reshape(shape)
    a, b = d["frequency_first_half"].reshape(shape), d["frequency_second_half"].reshape(shape)
    with np.errstate(divide="ignore", invalid="ignore"):
        diff = np.log10(np.linalg.norm(b - a, axis=1) / np.linalg.norm(a, axis=1))
    return nu, np.maximum(diff, -16.0), names[:3], par


def resonances(order):
    out = []
    for k1 in range(-order, order + 1):
        for k2 in range(-order, order + 1):
            for k3 in range(-order, order + 1):
                if abs(k1) + abs(k2) + abs(k3) > order or (k1 == 0 and k2 == 0):
                    continue
                if math.gcd(math.gcd(abs(k1), abs(k2)), abs(k3)) != 1:
                    continue
                first = next(k for k in (k1, k2, k3) if k != 0)
                if first < 0:  # k and -k are one line
                    continue
                out.append((k1, k2, k3))
    return out


def draw_resonances(ax, order, xlim, ylim):
    xs = np.linspace(*xlim, 200)
    for k1, k2, k3 in resonances(order):
        o = abs(k1) + abs(k2) + abs(k3)
        style = dict(color="0.35", lw=0.9 if o <= 3 else 0.5, ls="-" if o <= 3 else ":", zorder=1)
        if k2 != 0:  # k1 x + k2 y + k3 = 0
            ax.plot(xs, -(k1 * xs + k3) / k2, **style)
        else:
            ax.axvline(-k3 / k1, **style)
    ax.set_xlim(*xlim)
    ax.set_ylim(*ylim)


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--name", required=True)
    p.add_argument("--family", required=True, help="the states' family file (cardan_family.py states)")
    p.add_argument("--order", type=int, default=5)
    args = p.parse_args()
    if len(args.files) != 1:
        c.die("give one file written by lgi frequencies --state-file")
    nu, diff, names, par = frequency_vectors(args.files[0])
    with c.h5py.File(args.family, "r") as f:
        theta, ratio = np.asarray(f["family"]["theta"][()]), np.asarray(f["family"]["rate_ratio"][()])
        h = float(f["family"].attrs["h"])
    if len(theta) != len(nu):
        c.die(f"{args.family}: {len(theta)} states, but {args.files[0]} has {len(nu)}")
    x, y = nu[:, 0] / nu[:, 2], nu[:, 1] / nu[:, 2]
    ok = np.isfinite(x) & np.isfinite(y) & np.isfinite(diff)
    lo, hi = -9.0, -1.0
    fig, (a1, a2) = c.plt.subplots(1, 2, figsize=(9.6, 4.0), constrained_layout=True,
                                   gridspec_kw={"width_ratios": [1.25, 1]})
    order = np.argsort(diff[ok])[::-1]  # regular (blue) points drawn last, on top
    sc = a1.scatter(x[ok][order], y[ok][order], c=diff[ok][order], s=7, cmap="viridis_r", vmin=lo, vmax=hi,
                    linewidths=0, zorder=2)
    qx, qy = np.quantile(x[ok], [0.02, 0.98]), np.quantile(y[ok], [0.02, 0.98])
    pad = lambda q: (q[0] - 0.08 * (q[1] - q[0]), q[1] + 0.08 * (q[1] - q[0]))  # noqa: E731
    draw_resonances(a1, args.order, pad(qx), pad(qy))
    a1.set_xlabel(f"$\\omega_1/\\omega_3$ ({names[0]} / {names[2]})")
    a1.set_ylabel(f"$\\omega_2/\\omega_3$ ({names[1]} / {names[2]})")
    a1.set_title(f"(a) frequency map, $h$ = {c.num(h)}: resonances "
                 f"$k\\cdot\\omega = 0$, $|k|_1 \\leq {args.order}$ (solid: $\\leq 3$)", fontsize=8)
    nt, nr = len(np.unique(theta)), len(np.unique(ratio))
    if nt * nr == len(theta):
        grid = np.full((nt, nr), np.nan)
        it = np.searchsorted(np.unique(theta), theta)
        ir = np.searchsorted(np.unique(ratio), ratio)
        grid[it, ir] = diff
        from chaos_map import edges
        a2.grid(False)
        a2.pcolormesh(edges(np.unique(ratio)), edges(np.unique(theta)), grid, cmap="viridis_r", vmin=lo, vmax=hi)
    else:
        a2.scatter(ratio, theta, c=diff, s=10, cmap="viridis_r", vmin=lo, vmax=hi)
    a2.set_xlabel("initial rate ratio $\\dot q_1/\\dot q_3$")
    a2.set_ylabel("initial inner-ring angle $q_2$ (rad)")
    a2.set_title("(b) the same index over the initial conditions", fontsize=8)
    cb = fig.colorbar(sc, ax=[a1, a2], shrink=0.9, pad=0.02, extend="both")
    cb.set_label("diffusion index $\\log_{10}|\\Delta\\nu|/|\\nu|$")
    fig.suptitle(f"{c.scene_label(par)}: {int(ok.sum())} orbits to $t$ = {c.num(float(par.get('t_end', 0)))}",
                 fontsize=9)
    c.save(fig, args.out, args.name)
    print(f"frequency_map.py: {int(ok.sum())} states, {np.mean(diff[ok] > -3):.3f} with a diffusion index above -3")


if __name__ == "__main__":
    main()
