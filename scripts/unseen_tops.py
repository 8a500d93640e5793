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

--rounds N runs every top's work-precision N times, in turn (top 0, 1, ..., then top 0 again), and
takes for each row the least of its rounds' CPU minima: a slow spell of a virtual machine then moves
a row only if it falls on that row in every round, where with one round it can fall on one scheme's
repeats and not on another's (docs/performance.md §7). The counts and errors of a row are the same
in every round (lgi's runs are deterministic); the script checks that. A top's line is printed after
its last round; after a failure, the tops with at least one round are printed and written with the
rounds they have ("rounds" in the JSON).

A top (m = g = 1, t_end = 10):
- moments about the fixed point (s2 + s3, s1 + s3, s1 + s2), s_i uniform in [0.1, 1],
  so the triangle inequalities hold; drawn again until every two differ by 5% or
  more (no near-symmetric top);
- the centre of mass chi: a uniform direction, |chi| uniform in [0.2, 1], so in
  general off every principal axis;
- the initial attitude: a rotation vector of uniform direction and angle in
  [0.2, 2.5] rad; the body angular velocity: uniform direction, |Omega| in [1, 4].

usage: scripts/unseen_tops.py [--count N] [--seed S] [--lgi PATH] [--repeat N] [--rounds N]
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


DETERMINISTIC = ("scheme", "dt", "tol", "steps", "rejected_steps", "rhs_evaluations", "error", "status")


def merge_rounds(rounds):
    """The rows of one top's rounds (lists of CSV rows, in lgi's order) as one list: each row the first
    round's with cpu_seconds_min the least over the rounds. Raises ValueError if a row's counts or
    errors differ between rounds (they cannot, for a deterministic lgi) or the rounds' rows differ."""
    merged = [dict(row) for row in rounds[0]]
    for later in rounds[1:]:
        if len(later) != len(merged):
            raise ValueError(f"a round has {len(later)} rows where the first has {len(merged)}")
        for row, other in zip(merged, later):
            for c in DETERMINISTIC:
                if row.get(c) != other.get(c):
                    raise ValueError(f"{row.get('scheme')} tol={row.get('tol')} dt={row.get('dt')}: "
                                     f"{c} is {row.get(c)} in one round and {other.get(c)} in another")
            if row.get("status") == "ok":
                row["cpu_seconds_min"] = repr(min(float(row["cpu_seconds_min"]), float(other["cpu_seconds_min"])))
    return merged


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
    ap.add_argument("--rounds", type=int, default=1,
                    help="work-precision runs of each top, in turn over the tops; each row's time the least")
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
    if a.count < 1 or a.repeat < 1 or a.rounds < 1:
        ap.error("--count, --repeat and --rounds must be at least 1")
    try:
        targets = [float(x) for x in a.targets.split(",")]
    except ValueError:
        ap.error(f"--targets: not a list of numbers: {a.targets}")
    if not os.access(a.lgi, os.X_OK):
        ap.error(f"--lgi: no executable at {a.lgi}")
    from cost_table import cpu_at_error  # matplotlib and h5py come with it: imported after the arguments

    lie, baselines = a.lie.split(","), a.baselines.split(",")
    per_top, records, failed, status = survey(a, lie, baselines, targets, cpu_at_error)
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


def survey(a, lie, baselines, targets, cpu_at_error):
    """Runs every top's rounds and prints a line per top. Returns (ratios per top, JSON records,
    the failure's message or None, lgi's exit status)."""
    per_top, records, failed, status = [], [], None, 0
    rounds_of = {}  # top -> the CSV rows of each of its rounds so far

    def report(k):
        """Prints top k's line from the rounds it has, and keeps it for the summary and the JSON."""
        top = draw_top(a.seed, k)
        try:
            found = ratios_of(merge_rounds(rounds_of[k]), lie, baselines, targets, cpu_at_error)
        except ValueError as e:
            sys.exit(f"unseen_tops: top {k}: {e}")
        per_top.append(found)
        cells = [f"{t:g} " + ("not reached" if r is None else f"{r[1] / r[3]:.3f} {r[0]} / {r[2]}")
                 for t, r in zip(targets, found)]
        print(f"# top {k}: J = {np.round(top['inertia'], 3).tolist()}, chi = "
              f"{np.round(top['center_of_mass'], 3).tolist()}: " + "; ".join(cells), flush=True)
        records.append({"top": k, **top, "rounds": len(rounds_of[k]),
                        "ratios": [None if r is None else
                                   {"lie_group": r[0], "lie_group_s": r[1], "baseline": r[2], "baseline_s": r[3],
                                    "ratio": r[1] / r[3]} for r in found]})

    with tempfile.TemporaryDirectory() as tmp:
        where = a.keep or tmp
        os.makedirs(where, exist_ok=True)
        for rnd in range(a.rounds):
            for k in range(a.count):
                which = f" (round {rnd + 1} of {a.rounds})" if a.rounds > 1 else ""
                print(f"unseen_tops: lgi work-precision on top {k}{which}", file=sys.stderr, flush=True)
                try:
                    rows = run_top(a, draw_top(a.seed, k), k, where, rnd)
                except subprocess.CalledProcessError as e:
                    # lgi's exit 2 is input it refused (its line above names it, e.g. a scheme of --lie).
                    failed, status = f"unseen_tops: lgi work-precision failed on top {k} (exit {e.returncode})", \
                        e.returncode
                    break
                rounds_of.setdefault(k, []).append(rows)
                if rnd == a.rounds - 1:
                    report(k)
            if failed:
                break
    if failed:  # the tops not reported yet, with the rounds they have
        for k in sorted(set(rounds_of) - {r["top"] for r in records}):
            report(k)
    return per_top, records, failed, status


def run_top(a, top, k, where, rnd):
    """Writes top k's scene, runs lgi work-precision on it (round rnd of --rounds), returns its CSV rows."""
    scene = os.path.join(where, f"top_{a.seed}_{k}.toml")
    with open(scene, "w") as f:
        f.write(scene_toml(top, a.seed, k))
    out = os.path.join(where, f"top_{a.seed}_{k}" + (f"_round{rnd + 1}" if a.rounds > 1 else "") + ".h5")
    subprocess.run([a.lgi, "work-precision", "--scene", scene, "--schemes", f"{a.lie},{a.baselines}",
                    "--tol", a.tolerances, "--dt", a.dts, "--repeat", str(a.repeat), "--out", out, "--force",
                    "--quiet"], check=True)
    with open(out[:-3] + ".csv") as f:
        return list(csv.DictReader(f))


if __name__ == "__main__":
    main()
