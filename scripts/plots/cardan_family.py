#!/usr/bin/python3
"""A two-parameter family of Cardan-top states on one energy level, for a frequency map
(experiments/FREQUENCIES.md "Cardan tops"; paper section "Three degrees of freedom").

Usage: cardan_family.py probes --scene S.toml --theta A:B:N --dir DIR
       cardan_family.py states --probes DIR --h H --rate-ratio A:B:M --out STATES.h5

The family (Laskar's frequency maps fix the angles and vary the actions): the angles
q = (0, theta, 0), the rates along (a, 0, 1), scaled so that H = h. The kinetic energy is
(1/2) qdot^T M(q) qdot with p = M(q) qdot, so the three lgi runs with unit rates e_k at each
theta give M(q) column by column (p = M e_k) and the potential U(q) = E - M_kk / 2 (the same
for k = 1, 2, 3: the script checks it). `probes` writes those scenes (DIR/probe_I_K.toml;
run `lgi simulate --scheme cardan-rk4 --t-end DT --dt DT` on each, writing DIR/probe_I_K.h5);
`states` reads them and writes /family (cardan_angles, cardan_momenta, theta, rate_ratio,
energy) for `lgi frequencies --state-file`; states with h <= U(q) are left out.
"""
import argparse
import glob
import os
import re
import sys

import h5py
import numpy as np


def span(text, flag):
    try:
        a, b, n = text.split(":")
        a, b, n = float(a), float(b), int(n)
    except ValueError:
        sys.exit(f"cardan_family.py: {flag}: expected A:B:N, got '{text}'")
    return np.linspace(a, b, n) if n > 1 else np.array([a])


def probes(args):
    text = open(args.scene).read()
    if "[initial]" not in text or "cardan_angles" not in text:
        sys.exit(f"cardan_family.py: --scene: {args.scene} has no [initial] cardan_angles (not a Cardan scene)")
    os.makedirs(args.dir, exist_ok=True)
    for i, th in enumerate(span(args.theta, "--theta")):
        for k in range(3):
            rates = [0.0, 0.0, 0.0]
            rates[k] = 1.0
            t = re.sub(r"(?m)^cardan_angles\s*=.*$", f"cardan_angles = [0.0, {th!r}, 0.0]", text)
            t = re.sub(r"(?m)^cardan_rates\s*=.*$", f"cardan_rates = {rates!r}", t)
            open(os.path.join(args.dir, f"probe_{i:03d}_{k}.toml"), "w").write(t)


def first(f, name):
    return float(np.asarray(f["observables"][name]["value"][()]).ravel()[0])


def states(args):
    files = sorted(glob.glob(os.path.join(args.probes, "probe_*_0.h5")))
    if not files:
        sys.exit(f"cardan_family.py: --probes: no probe_*_0.h5 in {args.probes}")
    ratios = span(args.rate_ratio, "--rate-ratio")
    q_rows, p_rows, th_rows, a_rows = [], [], [], []
    worst = 0.0
    for f0 in files:
        stem = f0[:-len("_0.h5")]
        m = np.zeros((3, 3))
        u = []
        for k in range(3):
            with h5py.File(f"{stem}_{k}.h5", "r") as f:
                q = np.array([first(f, f"cardan_angle_{j}") for j in (1, 2, 3)])
                m[:, k] = [first(f, f"cardan_momentum_{j}") for j in (1, 2, 3)]
                u.append(first(f, "energy") - 0.5 * m[k, k])
        worst = max(worst, max(u) - min(u))
        pot = float(np.mean(u))
        for a in ratios:
            v = np.array([a, 0.0, 1.0])
            kin = 0.5 * v @ m @ v
            if not args.h > pot:
                continue
            s = np.sqrt((args.h - pot) / kin)
            q_rows.append(q)
            p_rows.append(s * (m @ v))
            th_rows.append(q[1])
            a_rows.append(a)
    if worst > 1e-9 * max(1.0, abs(args.h)):
        sys.exit(f"cardan_family.py: the potential from the three probes differs by {worst:.3g}: not one state")
    with h5py.File(args.out, "w") as f:
        g = f.create_group("family")
        g["cardan_angles"] = np.array(q_rows)
        g["cardan_momenta"] = np.array(p_rows)
        g["theta"] = np.array(th_rows)
        g["rate_ratio"] = np.array(a_rows)
        g.attrs["h"] = args.h
        g.attrs["potential_spread"] = worst
    print(f"cardan_family.py: {len(q_rows)} states on h = {args.h:g} (potential from the probes agrees to {worst:.1e})")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="what", required=True)
    a = sub.add_parser("probes")
    a.add_argument("--scene", required=True)
    a.add_argument("--theta", required=True)
    a.add_argument("--dir", required=True)
    b = sub.add_parser("states")
    b.add_argument("--probes", required=True)
    b.add_argument("--h", type=float, required=True)
    b.add_argument("--rate-ratio", required=True)
    b.add_argument("--out", required=True)
    args = p.parse_args()
    probes(args) if args.what == "probes" else states(args)


if __name__ == "__main__":
    main()
