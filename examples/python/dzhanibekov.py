"""The Dzhanibekov flip from Python: a notebook-style walkthrough of the module lgi.

Run it as a script (headless, Matplotlib's Agg backend), or cell by cell (# %%)
in an editor that knows the cell markers:

    PYTHONPATH=build/release/python /usr/bin/python3 examples/python/dzhanibekov.py --out-dir figures

It writes three figures into --out-dir (default ./figures) and prints their paths:
  book_flip.png          the book spun about its intermediate axis flips every 3.36 s:
                         Omega_2(t) from rkmk4 and from cf4 against the exact flow
  book_error_vs_cpu.png  attitude error against the exact flow at t = 14 s versus CPU seconds,
                         for several steps, rkmk4 and cf4
  heavy_top.png          Trindade's heavy top (case 1): nutation angle and the invariants' errors
"""
# %% Setup: the module, headless plotting, where the figures go
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import lgi  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--out-dir", default="figures", help="folder for the figures (created)")
args, _ = parser.parse_known_args(sys.argv[1:])
os.makedirs(args.out_dir, exist_ok=True)
written = []


def save(fig, name):
    path = os.path.join(args.out_dir, name)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    written.append(path)


def attitude_error(R, R_ref):
    """Geodesic angle |log(R_ref^T R)| (docs/conventions.md), for stacks of matrices, from
    |R - R_ref|_F = 2 sqrt(2) sin(angle / 2) (accurate for small angles, unlike arccos of the trace)."""
    d = np.linalg.norm(R - R_ref, axis=(1, 2))
    return 2.0 * np.arcsin(np.clip(d / (2.0 * np.sqrt(2.0)), 0.0, 1.0))


# %% The book: the shipped scene and what lgi knows about it
scenes_dir = lgi.scenes_dir()
book = lgi.Scene.from_file(os.path.join(scenes_dir, "dzhanibekov_book_axis2.toml"))
print(book, "inertia", np.diag(book.inertia), "invariants", book.invariants)
schemes = {s["name"]: s for s in lgi.schemes()}
for name in ("rkmk4", "cf4"):
    s = schemes[name]
    print(f"{name}: order {s['order']}, {s['family']}, {s['reference'][:60]}...")

# %% Two schemes and the exact flow: the angular velocity about axis 2 flips sign
runs = {name: lgi.simulate(book, name, dt=2e-3, save_every=5) for name in ("rkmk4", "cf4")}
t = runs["rkmk4"].t
R_exact, Pi_exact = lgi.exact_free_flow(book, t)
omega_exact = Pi_exact / np.diag(book.inertia)
fig, ax = plt.subplots(figsize=(7, 3.5))
ax.plot(t, omega_exact[:, 1], "k-", lw=3, alpha=0.3, label="exact flow")
for name, style in (("rkmk4", "C0--"), ("cf4", "C1:")):
    ax.plot(runs[name].t, runs[name].omega[:, 1], style, label=f"{name}, dt = 2e-3")
ax.set(xlabel="t (s)", ylabel=r"$\Omega_2$ (rad/s)", title="Book spun about its intermediate axis")
ax.legend(loc="lower right")
fig.tight_layout()
save(fig, "book_flip.png")
for name, run in runs.items():
    err = attitude_error(run.R, R_exact)
    print(f"{name}: max attitude error {err.max():.2e} rad, energy error {run.errors['energy'].max():.1e}, "
          f"{run.diagnostics['steps']} steps in {run.diagnostics['cpu_seconds'] * 1e3:.1f} ms")

# %% Error against CPU time: several steps, each run timed by lgi itself (stepping only)
fig, ax = plt.subplots(figsize=(5.5, 4))
t_end = book.t_end
R_end, _ = lgi.exact_free_flow(book, [t_end])
for name, marker in (("rkmk4", "o-"), ("cf4", "s-")):
    cpu, err = [], []
    for dt in (1e-2, 5e-3, 2.5e-3, 1.25e-3):
        run = lgi.simulate(book, name, t_end, dt=dt, save_every=10**9)  # the initial and final states only
        cpu.append(run.diagnostics["cpu_seconds"])
        err.append(attitude_error(run.R[-1:], R_end)[0])
    ax.loglog(cpu, err, marker, label=name)
    print(name, "error at t_end:", " ".join(f"{e:.1e}" for e in err))
ax.set(xlabel="CPU seconds (stepping)", ylabel=f"attitude error at t = {t_end:g} s (rad)",
       title="Work-precision, the book's flip")
ax.legend()
fig.tight_layout()
save(fig, "book_error_vs_cpu.png")

# %% A heavy top: Trindade & Sampaio's case 1, nutation and the invariants
top = lgi.Scene.from_file(os.path.join(scenes_dir, "heavy_top_trindade_1.toml"))
run = lgi.simulate(top, "rkmk4", 2.0, dt=1e-3)
gamma3 = run.R[:, 2, 2]  # Gamma = R^T e3; its third component is cos(theta)
fig, (a1, a2) = plt.subplots(2, 1, figsize=(7, 5), sharex=True)
a1.plot(run.t, np.degrees(np.arccos(np.clip(gamma3, -1, 1))))
a1.set(ylabel=r"nutation $\theta$ (deg)", title=top.name)
for name, err in run.errors.items():
    if np.any(err > 0):
        a2.semilogy(run.t[1:], err[1:], label=name)
a2.set(xlabel="t (s)", ylabel="invariant error")
a2.legend(fontsize=8)
fig.tight_layout()
save(fig, "heavy_top.png")
print("heavy top invariants:", ", ".join(run.invariants))

# %% What was written
for path in written:
    print("wrote", path)
