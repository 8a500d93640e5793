#!/usr/bin/python3
"""The cost at equal error on heavy tops nobody has tuned for: random general tops.

Draws --count heavy tops, each from its own seed (numpy's default_rng([--seed, k])),
writes each as a scene file, runs `lgi work-precision` on it with the Lie-group
candidates and the baselines of scripts/benchmark_ratios.py, and prints, per top and
target error, the cheapest Lie-group scheme, the cheapest baseline and the ratio of
their CPU times (minimum over the timed repeats, log-log interpolated along each
curve as in the paper's "cost at equal error" table, scripts/plots/cost_table.py).
The last lines give, per target, the median and the largest ratio over the tops and
how many are at or below --bar. If lgi fails on a top, the script stops with exit 1 (2 when lgi
refused its input, e.g. an unknown scheme in --lie), after printing and writing (--json, with
"complete": false) the tops done before it.

A top (m = g = 1, t_end = 10):
- moments about the fixed point (s2 + s3, s1 + s3, s1 + s2), s_i uniform in [0.1, 1],
  so the triangle inequalities hold; drawn again until every two differ by 5% or
  more (no near-symmetric top);
- the centre of mass chi: a uniform direction, |chi| uniform in [0.2, 1], so in
  general off every principal axis;
- the initial attitude: a rotation vector of uniform direction and angle in
  [0.2, 2.5] rad; the body angular velocity: uniform direction, |Omega| in [1, 4].

usage: scripts/unseen_tops.py [--count N] [--seed S] [--lgi PATH] [--repeat N]
                              [--targets E,...] [--bar R] [--tolerances T,...] [--dts H,...]
                              [--lie NAMES] [--baselines NAMES] [--keep DIR] [--json FILE]
"""
import argparse
import csv
import json
import os
import statistics
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "plots"))
from benchmark_ratios import BASELINES, LIE_GROUP, TOLERANCES, cheapest  # noqa: E402


def draw_top(seed, k):
    """The k-th top of `seed`: a dict of its parameters (module docstring)."""
    rng = np.random.default_rng([seed, k])
    while True:
        s = rng.uniform(0.1, 1.0, 3)
        inertia = np.array([s[1] + s[2], s[0] + s[2], s[0] + s[1]])
        if all(abs(inertia[i] - inertia[j]) >= 0.05 * max(inertia[i], inertia[j]) for i, j in ((0, 1), (0, 2), (1, 2))):
            break

    def direction():
        v = rng.normal(size=3)
        return v / np.linalg.norm(v)

    chi = direction() * rng.uniform(0.2, 1.0)
    rotation = direction() * rng.uniform(0.2, 2.5)
    omega = direction() * rng.uniform(1.0, 4.0)
    return {"inertia": inertia.tolist(), "center_of_mass": chi.tolist(), "rotation_vector": rotation.tolist(),
            "angular_velocity": omega.tolist()}


def scene_toml(top, seed, k):
    vec = lambda v: "[" + ", ".join(repr(float(x)) for x in v) + "]"  # noqa: E731
    return (f'name = "Random heavy top {k} of seed {seed}"\n'
            f'description = "scripts/unseen_tops.py: a general heavy top drawn at random, m = g = 1, t_end = 10"\n\n'
            f"[body]\nmass = 1.0\ninertia = {vec(top['inertia'])}\ncenter_of_mass = {vec(top['center_of_mass'])}\n\n"
            f"[gravity]\ng = 1.0\n\n"
            f"[initial]\nrotation_vector = {vec(top['rotation_vector'])}\n"
            f"angular_velocity = {vec(top['angular_velocity'])}\n\n"
            f"[run]\nt_end = 10.0\ndt = 1.0e-3\ntol = 1.0e-8\n")


def ratios_of(rows, lie, baselines, targets, cpu_at_error):
    """Per target: (Lie-group scheme, its seconds, baseline, its seconds) or None."""
    out = []
    for target in targets:
        a, b = cheapest(rows, lie, target, cpu_at_error), cheapest(rows, baselines, target, cpu_at_error)
        out.append(None if a is None or b is None else (a[0], a[1], b[0], b[1]))
    return out


def summary(per_top, targets, bar):
    """The last lines: per target, median and largest ratio and the count at or below bar."""
    lines = []
    for i, target in enumerate(targets):
        r = [p[i][1] / p[i][3] for p in per_top if p[i] is not None]
        if not r:
            lines.append(f"# at error {target:g}: no top had both a Lie-group scheme and a baseline reach it")
            continue
        lines.append(f"# at error {target:g}: median {statistics.median(r):.3f}, largest {max(r):.3f}, "
                     f"{sum(x <= bar for x in r)} of {len(r)} tops at or below {bar:g}")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--count", type=int, default=6)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--lgi", default=os.path.join(HERE, "..", "build", "release", "lgi"))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--targets", default="1e-6,1e-8,1e-10")
    ap.add_argument("--bar", type=float, default=0.5)
    ap.add_argument("--tolerances", default=TOLERANCES)
    # From 0.8: on a slow top a composition of order 8 reaches 1e-10 at dt = 0.2 already.
    ap.add_argument("--dts", default="0.8,0.4,0.2,0.1,0.05,0.025,0.012,0.006", help="fixed steps of the splittings")
    ap.add_argument("--lie", default=",".join(LIE_GROUP))
    ap.add_argument("--baselines", default=",".join(BASELINES))
    ap.add_argument("--keep", help="directory for the scene and work-precision files (default: removed)")
    ap.add_argument("--json")
    a = ap.parse_args()
    if a.count < 1 or a.repeat < 1:
        ap.error("--count and --repeat must be at least 1")
    try:
        targets = [float(x) for x in a.targets.split(",")]
    except ValueError:
        ap.error(f"--targets: not a list of numbers: {a.targets}")
    if not os.access(a.lgi, os.X_OK):
        ap.error(f"--lgi: no executable at {a.lgi}")
    from cost_table import cpu_at_error  # matplotlib and h5py come with it: imported after the arguments

    lie, baselines = a.lie.split(","), a.baselines.split(",")
    per_top, records, failed, status = [], [], None, 0
    with tempfile.TemporaryDirectory() as tmp:
        where = a.keep or tmp
        os.makedirs(where, exist_ok=True)
        for k in range(a.count):
            top = draw_top(a.seed, k)
            print(f"unseen_tops: lgi work-precision on top {k}", file=sys.stderr, flush=True)
            try:
                found = run_top(a, top, k, where, lie, baselines, targets, cpu_at_error)
            except subprocess.CalledProcessError as e:
                # lgi's exit 2 is input it refused (its line above names it, e.g. a scheme of --lie).
                failed, status = f"unseen_tops: lgi work-precision failed on top {k} (exit {e.returncode})", e.returncode
                break
            per_top.append(found)
            cells = [f"{t:g} " + ("not reached" if r is None else f"{r[1] / r[3]:.3f} {r[0]} / {r[2]}")
                     for t, r in zip(targets, found)]
            print(f"# top {k}: J = {np.round(top['inertia'], 3).tolist()}, chi = "
                  f"{np.round(top['center_of_mass'], 3).tolist()}: " + "; ".join(cells), flush=True)
            records.append({"top": k, **top, "ratios": [None if r is None else
                                                        {"lie_group": r[0], "lie_group_s": r[1], "baseline": r[2],
                                                         "baseline_s": r[3], "ratio": r[1] / r[3]} for r in found]})
    # The tops done so far are reported and kept, also after a failed run.
    for line in summary(per_top, targets, a.bar) if per_top else []:
        print(line)
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"seed": a.seed, "targets": targets, "bar": a.bar, "complete": failed is None, "tops": records},
                      f, indent=1)
    if failed:
        print(failed + (f"; its files are in {a.keep}" if a.keep else "; --keep DIR keeps its files"), file=sys.stderr)
        sys.exit(2 if status == 2 else 1)


def run_top(a, top, k, where, lie, baselines, targets, cpu_at_error):
    """Writes top k's scene, runs lgi work-precision on it, returns ratios_of() its rows."""
    scene = os.path.join(where, f"top_{a.seed}_{k}.toml")
    with open(scene, "w") as f:
        f.write(scene_toml(top, a.seed, k))
    out = os.path.join(where, f"top_{a.seed}_{k}.h5")
    subprocess.run([a.lgi, "work-precision", "--scene", scene, "--schemes", ",".join(lie + baselines),
                    "--tol", a.tolerances, "--dt", a.dts, "--repeat", str(a.repeat), "--out", out, "--force",
                    "--quiet"], check=True)
    with open(out[:-3] + ".csv") as f:
        return ratios_of(list(csv.DictReader(f)), lie, baselines, targets, cpu_at_error)

if __name__ == "__main__":
    main()
