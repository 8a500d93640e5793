#!/usr/bin/python3
"""The sweep engine's speed figures (README "Performance", experiments/SWEEPS.md).

1. Per-trajectory overhead: `lgi sweep` on experiments/sweeps/short_trajectories.toml
   (1e5 trajectories of 100 rkmk4 steps) and on the same spec with 2e5, CPU
   seconds of the whole process on one thread, against the bare stepping of
   the same trajectories measured by lgi_bench (sweep/bare: initial state +
   run function, null observer). The sweeps run with --simd off, one
   trajectory at a time as sweep/bare steps them; the default path (SIMD
   lanes of the ensemble kernels, docs/ensemble.md) is timed beside them end
   to end. The per-trajectory cost is the difference of
   the two sweeps over 1e5 (what one more trajectory costs); the end-to-end
   figure also carries the per-sweep costs (process start, files). Each is the
   minimum over --repeat runs, interleaved.
2. Parallel efficiency 1 -> 2 threads, and MPI np 1 -> 2 (lgi-mpi or an
   -DLGI_MPI=ON lgi, one thread per rank): wall-clock seconds, minimum over
   --repeat runs, on the short sweep and on a longer one (--long SPEC).
Prints a table; --json FILE keeps the numbers (for the paper and the scaling model).

usage: scripts/benchmark_sweep.py [--build build/release] [--repeat 3] [--long SPEC] [--json FILE]
"""
import argparse
import json
import os
import resource
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def run_timed(cmd):
    """(wall, CPU of the child processes) of one command."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.monotonic()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    wall = time.monotonic() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def bare_microseconds(bench):
    out = subprocess.run([bench, "--benchmark_filter=sweep/bare$", "--benchmark_min_time=2",
                          "--benchmark_format=json"], check=True, capture_output=True, text=True).stdout
    b = json.loads(out)["benchmarks"][0]
    return b["cpu_time"] * {"ns": 1e-3, "us": 1.0, "ms": 1e3}[b["time_unit"]]


def sweep_cmd(lgi, spec, out, threads, mpi=None, ranks=1, simd="auto"):
    cmd = [lgi, "sweep", "--spec", spec, "--out", out, "--threads", str(threads), "--simd", simd, "--quiet", "--force"]
    if mpi:
        cmd = [shutil.which("mpirun"), "--allow-run-as-root", "--oversubscribe", "-np", str(ranks), mpi] + cmd[1:]
    return cmd


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build", "release"))
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--long", default=os.path.join(ROOT, "experiments", "sweeps", "kovalevskaya_sections.toml"))
    ap.add_argument("--json")
    ap.add_argument("--overhead-only", action="store_true", help="skip the parallel-efficiency runs")
    a = ap.parse_args()
    lgi, bench = os.path.join(a.build, "lgi"), os.path.join(a.build, "lgi_bench")
    mpi = os.path.join(a.build, "lgi-mpi")
    mpi = mpi if os.path.exists(mpi) and shutil.which("mpirun") else None
    short = os.path.join(ROOT, "experiments", "sweeps", "short_trajectories.toml")
    tmp = tempfile.mkdtemp(prefix="lgi-sweep-bench-")
    out = os.path.join(tmp, "s.h5")
    n = 100000
    res = {}

    double = os.path.join(tmp, "short_2e5.toml")
    with open(short) as f, open(double, "w") as g:
        g.write(f.read().replace("samples = 100000", "samples = 200000").replace(
            '"../scenes/', '"' + os.path.join(ROOT, "experiments", "scenes") + "/"))
    bare, e2e, e2e2, lanes = [], [], [], []
    for k in range(a.repeat):
        print(f"overhead: run {k + 1}/{a.repeat}", file=sys.stderr)
        bare.append(bare_microseconds(bench))
        e2e.append(run_timed(sweep_cmd(lgi, short, out, 1, simd="off"))[1])
        e2e2.append(run_timed(sweep_cmd(lgi, double, out, 1, simd="off"))[1])
        lanes.append(run_timed(sweep_cmd(lgi, short, out, 1))[1])
    res["bare_us_per_trajectory"] = min(bare)
    res["sweep_us_per_trajectory"] = 1e6 * min(e2e) / n
    res["sweep_us_per_extra_trajectory"] = 1e6 * (min(e2e2) - min(e2e)) / n
    res["overhead"] = res["sweep_us_per_extra_trajectory"] / res["bare_us_per_trajectory"] - 1.0
    res["overhead_end_to_end"] = res["sweep_us_per_trajectory"] / res["bare_us_per_trajectory"] - 1.0
    res["ensemble_us_per_trajectory"] = 1e6 * min(lanes) / n

    for name, spec in (() if a.overhead_only else (("short", short), ("long", a.long))):
        for label, make in (("threads", lambda p: sweep_cmd(lgi, spec, out, p)),
                            ("ranks", (lambda p: sweep_cmd(lgi, spec, out, 1, mpi, p)) if mpi else None)):
            if make is None:
                continue
            walls = {}
            for p in (1, 2):
                print(f"efficiency: {name} sweep, {p} {label}", file=sys.stderr)
                walls[p] = min(run_timed(make(p))[0] for _ in range(a.repeat))
            res[f"{name}_{label}_wall_1"] = walls[1]
            res[f"{name}_{label}_wall_2"] = walls[2]
            res[f"{name}_{label}_efficiency"] = walls[1] / (2 * walls[2])
    shutil.rmtree(tmp, ignore_errors=True)

    print(f"per-trajectory overhead (100 rkmk4 steps each, 1 thread): bare {res['bare_us_per_trajectory']:.2f} us, "
          f"lgi sweep {res['sweep_us_per_extra_trajectory']:.2f} us per trajectory (2e5 - 1e5): "
          f"{100 * res['overhead']:+.1f} %; end to end at 1e5 (with process start and files): "
          f"{res['sweep_us_per_trajectory']:.2f} us, {100 * res['overhead_end_to_end']:+.1f} % (--simd off); "
          f"the default SIMD lanes end to end: {res['ensemble_us_per_trajectory']:.2f} us")
    for name in ("short", "long"):
        for label in ("threads", "ranks"):
            key = f"{name}_{label}_efficiency"
            if key in res:
                print(f"parallel efficiency, {name} sweep, 1 -> 2 {label}: {res[f'{name}_{label}_wall_1']:.2f} s -> "
                      f"{res[f'{name}_{label}_wall_2']:.2f} s, {100 * res[key]:.1f} %")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(res, f, indent=1)


if __name__ == "__main__":
    main()
