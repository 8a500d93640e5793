#!/usr/bin/python3
"""A steady precession of the Lagrange top in an upright Cardan frame: a 2-torus of a system
with three degrees of freedom (paper section "Three degrees of freedom", GALI of a 2-torus).

Usage: steady_precession.py --lgi PATH --scene S.toml --theta TH --spin W [--root slow|fast] --out OUT.toml
                             [--work DIR]

With the outer axis vertical and a symmetric body on the gimbal's axis, q1 and q3 are cyclic;
what remains is the nutation (q2, p2). At q = (0, TH, 0), qdot = (Omega, 0, W), the nutation is
at rest (dp2/dt = 0) for the roots Omega of a quadratic: dp2/dt = -dH/dq2 is quadratic in the rates
when qdot2 = 0. The script measures dp2/dt with lgi itself (lgi simulate --scheme cardan-rk4, two
steps of 1e-4 from the state, the second-order one-sided difference) at Omega = -1, 0, 1, solves
for the slow or the fast root (--root, default fast: the slow precession of a fast top hardly depends
on TH, so its family of 2-tori is nearly degenerate, and GALI's laws need a twist), refines it by secant steps on the same
difference, and writes the scene with that state to OUT.toml. Along it q2 stays at TH and
q1, q3 turn uniformly: an orbit on a 2-torus. Prints Omega and the residual dp2/dt.
"""
import argparse
import os
import re
import subprocess
import sys

import h5py
import numpy as np

H = 1e-4


def scene_text(base, theta, omega, spin):
    t = re.sub(r"(?m)^cardan_angles\s*=.*$", f"cardan_angles = [0.0, {theta!r}, 0.0]", base)
    return re.sub(r"(?m)^cardan_rates\s*=.*$", f"cardan_rates = [{omega!r}, 0.0, {spin!r}]", t)


def p2_rate(args, base, omega):
    path = os.path.join(args.work, "probe.toml")
    open(path, "w").write(scene_text(base, args.theta, omega, args.spin))
    out = os.path.join(args.work, "probe.h5")
    subprocess.run([args.lgi, "simulate", "--scene", path, "--scheme", "cardan-rk4", "--t-end", repr(2 * H),
                    "--dt", repr(H), "--out", out, "--force", "--quiet"], check=True)
    with h5py.File(out, "r") as f:
        p = np.asarray(f["observables"]["cardan_momentum_2"]["value"][()]).ravel()
    return (-3 * p[0] + 4 * p[1] - p[2]) / (2 * H)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--lgi", required=True)
    ap.add_argument("--scene", required=True)
    ap.add_argument("--theta", type=float, required=True)
    ap.add_argument("--spin", type=float, required=True)
    ap.add_argument("--root", choices=("slow", "fast"), default="fast")
    ap.add_argument("--out", required=True)
    ap.add_argument("--work", default=None)
    args = ap.parse_args()
    args.work = args.work or os.path.dirname(os.path.abspath(args.out))
    base = open(args.scene).read()
    if not re.search(r"(?m)^tilt\s*=\s*0(\.0*)?\s*(#.*)?$", base):
        sys.exit(f"steady_precession.py: --scene: {args.scene} needs tilt = 0 (an upright frame)")
    f = [p2_rate(args, base, w) for w in (-1.0, 0.0, 1.0)]
    a, b, c = 0.5 * (f[2] + f[0]) - f[1], 0.5 * (f[2] - f[0]), f[1]
    roots = np.roots([a, b, c])
    roots = roots[np.isreal(roots)].real
    if roots.size == 0:
        sys.exit("steady_precession.py: no steady precession at this theta and spin (no real root)")
    w0 = float(roots[np.argmin(np.abs(roots))] if args.root == "slow" else roots[np.argmax(np.abs(roots))])
    w1 = w0 * (1 + 1e-6) + 1e-9
    r0, r1 = p2_rate(args, base, w0), p2_rate(args, base, w1)
    for _ in range(6):
        if r1 == r0:
            break
        w0, w1, r0 = w1, w1 - r1 * (w1 - w0) / (r1 - r0), r1
        r1 = p2_rate(args, base, w1)
        if abs(r1) < 1e-12:
            break
    open(args.out, "w").write(scene_text(base, args.theta, w1, args.spin))
    print(f"steady_precession.py: Omega = {w1!r} ({args.root} root of {', '.join(f'{r:.6g}' for r in roots)}), "
          f"dp2/dt = {r1:.3g}; wrote {args.out}")


if __name__ == "__main__":
    main()
