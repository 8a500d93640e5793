#!/usr/bin/python3
"""Seed 000 (docs/sources.md), Figures 5 and 6: the energy and momentum ellipsoids of the book in
angular-velocity space and their intersection curves, computed analytically
from the inertia and the initial angular velocity of each scene, with the
numerical Ω(t) of the trajectory drawn on top as a check.

Usage: ellipsoids.py --out DIR TRAJ.h5 ...  (one trajectory per book scene; the
inertia and Ω(0) are read from the file's /parameters/scene_toml and first sample)

Energy ellipsoid Σ I_i ω_i² = 2T (semi-axes √(2T/I_i)); momentum ellipsoid
Σ I_i² ω_i² = G² (semi-axes G/I_i). On their intersection every ω_i² is an
affine function of any other, so with i the axis the curve circles (the largest
moment if G² > 2T I_mid, else the smallest) and j, k the other two,
  ω_j = A_j cos s,  ω_k = A_k sin s,  ω_i = ±√((2T − I_j ω_j² − I_k ω_k²)/I_i),
  A_j² = (G² − 2T I_i)/(I_j (I_j − I_i)),  A_k² = (G² − 2T I_i)/(I_k (I_k − I_i)),
is an exact parametrisation of its two closed branches.

Writes DIR/ellipsoids_stable.{pdf,png} (scenes whose curve circles the axis of
spin: 3-D view and a projection of the loop) and DIR/ellipsoids_intermediate.{pdf,png}
(the others: the curves wrap between +ω_2 and −ω_2).
"""
import sys

import numpy as np
from mpl_toolkits.mplot3d import Axes3D  # noqa: F401

import lgi_plot_common as c

LAB = ["$\\omega_1$", "$\\omega_2$", "$\\omega_3$"]


def invariants(I, w0):
    T2 = float(np.sum(I * w0 * w0))        # 2T
    G2 = float(np.sum((I * w0) ** 2))       # G²
    return T2, G2


def intersection(I, w0, n=4000):
    """The two branches (sign of ω_i) of the intersection curve through w0, and i."""
    T2, G2 = invariants(I, w0)
    order = np.argsort(I)
    imid = order[1]
    i = order[2] if G2 > T2 * I[imid] else order[0]
    j, k = [a for a in range(3) if a != i]
    Aj = np.sqrt(max((G2 - T2 * I[i]) / (I[j] * (I[j] - I[i])), 0.0))
    Ak = np.sqrt(max((G2 - T2 * I[i]) / (I[k] * (I[k] - I[i])), 0.0))
    s = np.linspace(0, 2 * np.pi, n)
    wj, wk = Aj * np.cos(s), Ak * np.sin(s)
    wi = np.sqrt(np.maximum((T2 - I[j] * wj**2 - I[k] * wk**2) / I[i], 0.0))
    branches = []
    for sign in (+1, -1):
        w = np.empty((n, 3))
        w[:, i], w[:, j], w[:, k] = sign * wi, wj, wk
        branches.append(w)
    return branches, i, (j, k)


def ellipsoid_surface(semi, n=40):
    u, v = np.meshgrid(np.linspace(0, 2 * np.pi, n), np.linspace(0, np.pi, n // 2))
    return semi[0] * np.cos(u) * np.sin(v), semi[1] * np.sin(u) * np.sin(v), semi[2] * np.cos(v)


def draw_3d(ax, I, w0, traj_w, title):
    T2, G2 = invariants(I, w0)
    for semi, color, name in ((np.sqrt(T2 / I), "tab:blue", "energy"), (np.sqrt(G2) / I, "tab:red", "momentum")):
        X, Y, Z = ellipsoid_surface(semi)
        ax.plot_surface(X, Y, Z, color=color, alpha=0.13, linewidth=0, shade=False)
        ax.plot_wireframe(X, Y, Z, color=color, alpha=0.25, linewidth=0.3, rstride=3, cstride=3)
        ax.plot([], [], color=color, label=f"{name} ellipsoid")
    branches, i, _ = intersection(I, w0)
    for b, w in enumerate(branches):
        ax.plot(w[:, 0], w[:, 1], w[:, 2], color="k", lw=1.6, label="intersection" if b == 0 else None, zorder=10)
    step = max(1, len(traj_w) // 250)
    ax.plot(traj_w[::step, 0], traj_w[::step, 1], traj_w[::step, 2], "o", color="gold", ms=1.6, mew=0,
            label="$\\Omega(t)$ (integrated)", zorder=11)
    lim = np.max(np.sqrt(T2 / I))
    for setlim in (ax.set_xlim, ax.set_ylim, ax.set_zlim):
        setlim(-lim, lim)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel(LAB[0], labelpad=-8)
    ax.set_ylabel(LAB[1], labelpad=-8)
    ax.set_zlabel(LAB[2], labelpad=-8)
    ax.tick_params(pad=-3, labelsize=6)
    ax.view_init(elev=22, azim=-58)
    ax.set_title(title, fontsize=8.5)
    return i


def draw_projection(ax, I, w0, traj_w, axes_pair, title, legend=True):
    branches, i, _ = intersection(I, w0)
    a, b = axes_pair
    for n, w in enumerate(branches):
        sel = w[:, i] * np.sign(w0[i] if w0[i] != 0 else 1) > 0 if i not in axes_pair else slice(None)
        ax.plot(w[sel, a] if not isinstance(sel, slice) else w[:, a],
                w[sel, b] if not isinstance(sel, slice) else w[:, b], color="k", lw=2.4,
                label="analytic intersection" if n == 0 else None)
    step = max(1, len(traj_w) // 300)
    ax.plot(traj_w[::step, a], traj_w[::step, b], "o", color="gold", ms=1.3, mew=0,
            label="$\\Omega(t)$ integrated", zorder=5)
    ax.plot([w0[a]], [w0[b]], "o", color="tab:red", ms=4, label="$\\Omega(0)$")
    ax.set_xlabel(LAB[a] + " (rad/s)")
    ax.set_ylabel(LAB[b] + " (rad/s)")
    ax.set_title(title, fontsize=8.5)
    if legend:
        ax.legend(fontsize=6, loc="center")


def legend_above_3d(fig, ax):
    """The 3-D panel's legend (and the red Ω(0) dot of the projections) in one row above
    the figure, so that it covers neither the ellipsoids nor a title."""
    h, l = ax.get_legend_handles_labels()
    h.append(c.plt.Line2D([], [], marker="o", color="tab:red", ls="", ms=4))
    l.append("$\\Omega(0)$")
    fig.legend(h, l, fontsize=6.5, ncol=len(h), loc="lower center", bbox_to_anchor=(0.5, 1.0), frameon=False)


def main():
    args = c.parser(__doc__.split("\n\n")[0]).parse_args()
    runs = {}
    for p in args.files:
        r = c.load_trajectory(p)
        scene = c.scene_label(r["parameters"])
        if scene in runs:
            print(f"ellipsoids.py: {p}: scene {scene} already drawn from {runs[scene]['path']}; "
                  "one trajectory per scene, this one is not drawn", file=sys.stderr)
            continue
        runs[scene] = r
    if not runs:
        c.die("no trajectory files given")
    stable, intermediate = [], []
    for scene, r in sorted(runs.items()):
        I = np.diag(c.inertia_of(r["scene"]))
        w0 = r["Omega"][0]
        spin_axis = int(np.argmax(np.abs(w0)))
        order = np.argsort(I)
        (intermediate if spin_axis == order[1] else stable).append((scene, r, I, w0, spin_axis))

    if stable:
        fig = c.plt.figure(figsize=(7.0, 3.2 * len(stable)))
        for n, (scene, r, I, w0, ax_i) in enumerate(stable):
            ax = fig.add_subplot(len(stable), 2, 2 * n + 1, projection="3d")
            i = draw_3d(ax, I, w0, r["Omega"], f"spin about axis {ax_i + 1}:\ntiny loops at $\\pm\\omega_{ax_i + 1}$")
            if n == 0:
                legend_above_3d(fig, ax)
            ax2 = fig.add_subplot(len(stable), 2, 2 * n + 2)
            pair = tuple(a for a in range(3) if a != i)
            draw_projection(ax2, I, w0, r["Omega"], pair,
                            f"spin about axis {ax_i + 1}: the loop around $+\\omega_{i + 1}$, projected")
            ax2.set_aspect("equal", adjustable="datalim")
            ax2.xaxis.set_major_locator(c.plt.MaxNLocator(5))  # no colliding tick labels
        fig.subplots_adjust(wspace=0.45, hspace=0.3)
        c.save(fig, args.out, "ellipsoids_stable")
    if intermediate:
        fig = c.plt.figure(figsize=(7.0, 3.0 * len(intermediate)))
        gs = fig.add_gridspec(len(intermediate), 3, width_ratios=[1.5, 1, 1], wspace=0.55)
        for n, (scene, r, I, w0, ax_i) in enumerate(intermediate):
            ax = fig.add_subplot(gs[n, 0], projection="3d")
            draw_3d(ax, I, w0, r["Omega"], f"spin about axis {ax_i + 1}")
            if n == 0:
                legend_above_3d(fig, ax)
            others = [a for a in range(3) if a != ax_i]
            for m, o in enumerate(others):
                axp = fig.add_subplot(gs[n, 1 + m])
                draw_projection(axp, I, w0, r["Omega"], (ax_i, o), f"projection on ({LAB[ax_i]}, {LAB[o]})",
                                legend=False)
        c.save(fig, args.out, "ellipsoids_intermediate")


if __name__ == "__main__":
    main()
