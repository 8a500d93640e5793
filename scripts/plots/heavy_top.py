#!/usr/bin/python3
"""Seed 001 (Trindade & Sampaio 2001; docs/sources.md), Figures 3-10: the heavy top.

Usage: heavy_top.py --out DIR TRAJ.h5 ...

Trajectories of heavy_top_trindade_{1,2,3,4}.toml (any scheme; a Lie-group
scheme in the paper) give one figure each, DIR/heavy_top_case{N}.{pdf,png}
(their Figures 3-6): nutation θ(t), the centre of mass P = R χ, total and
kinetic energy, Ω, the phase plane (θ, θ̇), the trajectory of P, the unwrapped
precession ψ(t), and the relative errors of the two invariants (H and Π·Γ).
Several files of one case give one figure each, DIR/heavy_top_case{N}_<file stem>.
DIR is created if missing.

Trajectories of heavy_top_trindade_singular.toml (and optionally singularity-study
files of `lgi singularity`, whose unguarded euler-zxz runs supply the Euler angles) give
DIR/heavy_top_singular.{pdf,png} (their Figures 7-10): files carrying
/particles/body/euler_zxz (the euler-zxz baselines, e.g. at several
tolerances) show the integrated Euler angles with their jumps by π; every other
file is a Lie-group run, whose attitude is drawn as it is (quaternion
components, centre of mass) and whose angles are extracted from R only for
comparison. The centre of mass of every run is drawn on one panel: the motion
is the same whatever the angles do.
θ, φ from Γ = Rᵀe3 = (sinθ sinφ, sinθ cosφ, cosθ); θ̇ = Ω1 cosφ − Ω2 sinφ
(docs/conventions.md §2, Trindade & Sampaio eq. 27).
"""
import os
import re
import sys

import h5py
import numpy as np

import lgi_plot_common as c


def derived(r):
    R = c.quat_to_matrix(r["q"])
    chi = np.asarray(r["scene"].get("body", {}).get("center_of_mass", [0, 0, 1]), dtype=float)
    psi, theta, phi = c.euler_zxz_from_matrix(R)
    Om = r["Omega"]
    d = {
        "R": R,
        "P": np.einsum("nij,j->ni", R, chi),
        "theta": theta,
        "phi": phi,
        "psi": psi,
        "theta_dot": Om[:, 0] * np.cos(phi) - Om[:, 1] * np.sin(phi),
        "kinetic": 0.5 * np.sum(r["Pi"] * Om, axis=1),
    }
    return d


def rel_error(x):
    x = np.asarray(x, dtype=float)
    scale = abs(x[0]) if x[0] != 0 else 1.0
    return np.maximum(np.abs(x - x[0]) / scale, 1e-17)


def case_figure(r, case, outdir, name):
    d = derived(r)
    t = r["t"]
    fig = c.plt.figure(figsize=(7.4, 3.9))
    gs = fig.add_gridspec(2, 4, wspace=0.75, hspace=0.55)
    ax = fig.add_subplot(gs[0, 0])
    ax.plot(t, d["theta"], "k")
    ax.set(xlabel="t (s)", ylabel="nutation θ (rad)")
    ax = fig.add_subplot(gs[0, 1])
    for i, n in enumerate("xyz"):
        ax.plot(t, d["P"][:, i], label=f"$P_{n}$")
    ax.set(xlabel="t (s)", ylabel="centre of mass (m)")
    ax.legend(fontsize=6, ncol=3, loc="lower left", bbox_to_anchor=(0, 1.0), frameon=False, handlelength=1.2)
    ax = fig.add_subplot(gs[0, 2])
    ax.plot(t, r["energy"], "k", label="total")
    ax.plot(t, d["kinetic"], "tab:red", label="kinetic")
    ax.set(xlabel="t (s)", ylabel="energy (J)")
    ax.legend(fontsize=6, ncol=2, loc="lower left", bbox_to_anchor=(0, 1.0), frameon=False, handlelength=1.2)
    ax = fig.add_subplot(gs[0, 3])
    for i in range(3):
        ax.plot(t, r["Omega"][:, i], label=f"$\\Omega_{i+1}$")
    ax.set(xlabel="t (s)", ylabel="Ω (rad/s)")
    ax.legend(fontsize=6, ncol=3, loc="lower left", bbox_to_anchor=(0, 1.0), frameon=False, handlelength=1.2)
    ax = fig.add_subplot(gs[1, 0])
    ax.plot(d["theta"], d["theta_dot"], "k", lw=0.6)
    ax.set(xlabel="θ (rad)", ylabel="$\\dot\\theta$ (rad/s)")
    ax = fig.add_subplot(gs[1, 1], projection="3d")
    ax.plot(d["P"][:, 0], d["P"][:, 1], d["P"][:, 2], "k", lw=0.5)
    ax.set_title("trajectory of P", fontsize=7.5, pad=0)
    # The 3-D box drawn smaller than its cell, with three ticks per axis: its z tick labels
    # must not reach the y label of the panel to its right.
    ax.set_box_aspect(None, zoom=0.8)
    for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
        axis.set_major_locator(c.plt.MaxNLocator(3))
    ax.tick_params(labelsize=5, pad=-3)
    ax.set_xlabel("x", labelpad=-10, fontsize=6)
    ax.set_ylabel("y", labelpad=-10, fontsize=6)
    ax.set_zlabel("z", labelpad=-10, fontsize=6)
    ax = fig.add_subplot(gs[1, 2])
    ax.plot(t, np.unwrap(d["psi"]), "k")
    ax.set(xlabel="t (s)", ylabel="precession ψ (rad)")
    ax.set_title("ψ extracted from R", fontsize=7, loc="left")
    ax = fig.add_subplot(gs[1, 3])
    ax.semilogy(t, rel_error(r["energy"]), label="H")
    inv = [k for k in r["observables"] if "vertical" in k]
    for k in inv:
        ax.semilogy(t, rel_error(r["observables"][k]), label="Π·Γ")
    ax.set(xlabel="t (s)", ylabel="relative error")
    ax.legend(fontsize=6, ncol=2, loc="lower left", bbox_to_anchor=(0, 1.0), frameon=False, handlelength=1.2)
    fig.suptitle(f"Heavy top, Trindade & Sampaio case {case} — {r['scheme']}, "
                 f"{_step_text(r)}", fontsize=8.5, y=1.0)
    c.save(fig, outdir, name)


def _step_text(r):
    p = r["parameters"]
    if "tol" in p and p["tol"] == p["tol"] and "dt" not in p:
        return f"tol = {p['tol']:g}"
    if "dt" in p:
        return f"h = {p['dt']:g} s"
    return f"tol = {p.get('tol', float('nan')):g}"


def euler_series(runs, studies):
    """Euler-angle runs of the singular scene: trajectory files with /particles/body/euler_zxz
    and the unguarded euler-zxz runs of singularity-study files (experiments/SINGULARITY.md)."""
    out = []
    for r in runs:
        if r["euler_zxz"] is None:
            continue
        d = derived(r)
        out.append({"label": f"{r['scheme']}, {_step_text(r)}", "t": r["t"], "psi": r["euler_zxz"][:, 0],
                    "theta": r["euler_zxz"][:, 1], "phi": r["euler_zxz"][:, 2], "status": r["diagnostics"].get("status", ""),
                    "tP": r["t"], "P": d["P"], "tol": r["parameters"].get("tol", np.nan), "energy": r["energy"], "tE": r["t"]})
    for path in studies:
        with h5py.File(path, "r") as f:
            for key in f["scenes"]:
                if "singular" not in key:
                    continue
                g = f["scenes"][key]
                grid = g["grid/time"][:]
                for label in g["runs"]:
                    rg = g["runs"][label]
                    guard = c._attr(rg.attrs.get("guard", "-"))
                    if "euler_zxz" not in rg or guard != "off":
                        continue
                    e = rg["euler_zxz"]
                    tol = float(c._attr(rg.attrs.get("tol", np.nan)))
                    dt = float(c._attr(rg.attrs.get("dt", np.nan)))
                    step = f"tol = {tol:g}" if np.isfinite(tol) else f"h = {dt:g} s"
                    P = rg["center_of_mass"][:]
                    out.append({"label": f"{c._attr(rg.attrs.get('method', label))}, {step}", "t": e["time"][:],
                                "stepper": c._attr(rg.attrs.get("stepper", "")),
                                "psi": e["psi"][:], "theta": e["theta"][:], "phi": e["phi"][:],
                                "status": c._attr(rg.attrs.get("status", "")), "tP": grid[: len(P)], "P": P, "tol": tol,
                                "energy": None, "tE": None})
    # Several tolerances of one stepper (as Trindade & Sampaio's Figures 7-10 with ODE45): dopri5 only,
    # when the study files hold it; else every unguarded run.
    if any(x.get("stepper") == "dopri5" for x in out):
        out = [x for x in out if x.get("stepper", "dopri5") == "dopri5"]
    out.sort(key=lambda x: -x["tol"] if np.isfinite(x["tol"]) else 0)
    return out


def singular_figure(runs, studies, outdir):
    euler = euler_series(runs, studies)
    lie = [r for r in runs if r["euler_zxz"] is None]
    fig, axes = c.plt.subplots(3, 2, figsize=(7.2, 6.0), sharex=True, gridspec_kw={"hspace": 0.35, "wspace": 0.3})
    colors = c.plt.get_cmap("plasma")(np.linspace(0, 0.8, max(len(euler), 1)))
    for e, col in zip(euler, colors):
        axes[0, 0].plot(e["t"], e["theta"], color=col, lw=0.9, label=e["label"])
        axes[1, 0].plot(e["t"], e["phi"], color=col, lw=0.9)
        axes[2, 0].plot(e["t"], e["psi"], color=col, lw=0.9)
        if e["status"] not in ("ok", ""):
            axes[2, 0].annotate("stopped", (e["t"][-1], e["psi"][-1]), fontsize=5.5, color=col)
    t_max = max([r["t"][-1] for r in lie] + [e["t"][-1] for e in euler] + [0])
    for r in lie:
        d = derived(r)
        axes[0, 0].plot(r["t"], d["theta"], color="0.35", lw=2.0, alpha=0.5, zorder=0,
                        label=f"{r['scheme']} ({_step_text(r)}): θ = ∠(b$_3$, e$_3$) ∈ [0, π] from R")
        axes[1, 0].plot(r["t"], d["phi"], color="0.6", lw=0.4, zorder=0, label=f"{r['scheme']}: φ extracted from R")
        axes[2, 0].plot(r["t"], d["psi"], color="0.6", lw=0.4, zorder=0, label=f"{r['scheme']}: ψ extracted from R")
        qc = c.continuous_quaternion(r["q"])
        for i, lab in enumerate(["w", "x", "y", "z"]):
            axes[1, 1].plot(r["t"], qc[:, i], lw=1.0, label=f"$q_{lab}$ ({r['scheme']})")
        axes[2, 1].semilogy(r["t"], rel_error(r["energy"]), lw=0.9, color="k", label=f"H, {r['scheme']}")
    for e, col in zip(euler, colors):
        if e["energy"] is not None:
            axes[2, 1].semilogy(e["tE"], rel_error(e["energy"]), lw=0.7, color=col, ls="--", label=f"H, {e['label']}")
    comp_colors = ["tab:blue", "tab:orange", "tab:green"]
    for r in lie:
        d = derived(r)
        for i in range(3):
            axes[0, 1].plot(r["t"], d["P"][:, i], color=comp_colors[i], lw=2.2, alpha=0.45,
                            label=f"$P_{'xyz'[i]}$, {r['scheme']}")
    for k, (e, col) in enumerate(zip(euler, colors)):
        for i in range(3):
            axes[0, 1].plot(e["tP"], e["P"][:, i], color=col, lw=0.6, ls="--",
                            label=("Euler-angle runs (dashed)" if (k == 0 and i == 0) else None))
    axes[0, 0].set_ylabel("nutation θ (rad)")
    axes[1, 0].set_ylabel("spin φ (rad)")
    axes[2, 0].set_ylabel("precession ψ (rad)")
    axes[0, 1].set_ylabel("$P = R\\chi$ (m)")
    axes[1, 1].set_ylabel("quaternion (sign-continuous)")
    axes[2, 1].set_ylabel("relative energy error")
    axes[0, 0].set_title("Euler angles as integrated (baseline, no guard)" if euler else
                         "no Euler-angle baseline run available", loc="left")
    axes[0, 1].set_title("Lie-group attitude (smooth) and the motion", loc="left")
    h0, l0 = axes[0, 0].get_legend_handles_labels()
    h1, l1 = axes[1, 0].get_legend_handles_labels()
    axes[1, 0].legend(h0 + h1, l0 + l1, fontsize=5.3, loc="lower right", framealpha=0.9)
    axes[0, 1].legend(fontsize=5.3, loc="lower left", ncol=2)
    axes[1, 1].legend(fontsize=5.3, ncol=2, loc="lower left")
    axes[2, 1].legend(fontsize=5.3, ncol=1, loc="lower right")
    for ax in axes[-1]:
        ax.set_xlabel("t (s)")
        ax.set_xlim(0, t_max)
    for ax in axes[1:, 0]:
        yl = ax.get_ylim()
        k0, k1 = int(np.floor(yl[0] / np.pi)), int(np.ceil(yl[1] / np.pi))
        stride = next(m for m in (1, 2, 5, 10, 20, 50, 100, 200, 500, 10**9) if (k1 - k0) / m <= 7)
        k0 = stride * int(np.floor(k0 / stride))
        ax.set_yticks(np.arange(k0, k1 + 1, stride) * np.pi)
        ax.set_ylim(yl)
        ax.set_yticklabels([f"{int(round(v / np.pi))}π" for v in ax.get_yticks()])
    c.save(fig, outdir, "heavy_top_singular")


def main():
    args = c.parser(__doc__.split("\n\n")[0]).parse_args()
    runs, studies = [], []
    for p in args.files:
        with h5py.File(p, "r") as f:
            is_study = "scenes" in f and "particles" not in f
        (studies if is_study else runs).append(p)
    runs = [c.load_trajectory(p) for p in runs]
    if not runs:
        c.die("no trajectory files given")
    singular, cases = [], []
    for r in runs:
        name = c.scene_label(r["parameters"])
        m = re.fullmatch(r"heavy_top_trindade_(\d)", name)
        if m:
            cases.append((r, m.group(1)))
        elif name == "heavy_top_trindade_singular":
            singular.append(r)
        else:
            print(f"heavy_top.py: {os.path.basename(r['path'])}: scene {name} is not a Trindade scene, skipped",
                  file=sys.stderr)
    # One figure per input: heavy_top_case{N}, or heavy_top_case{N}_<input stem> when
    # several inputs are of case N (never one file written over another).
    names = c.unique_names([f"heavy_top_case{case}" for _, case in cases], [r["path"] for r, _ in cases])
    for (r, case), name in zip(cases, names):
        case_figure(r, case, args.out, name)
    if singular:
        singular_figure(singular, studies, args.out)


if __name__ == "__main__":
    main()
