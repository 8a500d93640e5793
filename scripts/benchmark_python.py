#!/usr/bin/python3
"""The Python call overhead of lgi.simulate (issue 14's bar: at most 5 % over the
stepping time for a 10^4-step run).

A 10^4-step rkmk4 run of the book (dt = 1e-3, t_end = 10 s) through lgi.simulate,
with small output (save_every = 10^4: 2 samples) and full output (every step:
10^4 + 1 samples, which the module keeps in memory). For each, the median over
--repeat calls of
  call        the wall time of the Python call, and its thread CPU time
  stepping    the module's own diagnostics cpu_seconds (the stepping alone, as /diagnostics)
  output      diagnostics output_seconds (invariants and the in-memory samples)
  overhead    call wall - stepping - output, per call: what the Python call adds (argument
              handling, scheme lookup, the model, the arrays), relative to the stepping
and the stepping time `lgi simulate` itself reports for the same run (/diagnostics
cpu_seconds of its file). Prints the figures; asserts nothing.

Usage: PYTHONPATH=build/release/python /usr/bin/python3 scripts/benchmark_python.py \
           [--lgi build/release/lgi] [--repeat 15]
"""
import argparse
import os
import statistics
import subprocess
import tempfile
import time

import lgi

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
BOOK = os.path.join(ROOT, "experiments", "scenes", "dzhanibekov_book_axis2.toml")
DT, T_END = 1e-3, 10.0  # 10^4 steps


def time_calls(scene, save_every, repeat):
    rows = []
    for _ in range(repeat):
        w0, c0 = time.perf_counter(), time.thread_time()
        run = lgi.simulate(scene, "rkmk4", T_END, dt=DT, save_every=save_every)
        c1, w1 = time.thread_time(), time.perf_counter()
        d = run.diagnostics
        assert d["steps"] == 10_000
        overhead = (w1 - w0) - d["cpu_seconds"] - d["output_seconds"]  # per call: robust to load changes
        rows.append((w1 - w0, c1 - c0, d["cpu_seconds"], d["output_seconds"], len(run), overhead))
        del run  # freed outside the timed call
    return [statistics.median(col) for col in zip(*rows)]


def cli_stepping(exe, repeat):
    import h5py
    times = []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "cli.h5")
        for _ in range(repeat):
            subprocess.run([exe, "simulate", "--scene", BOOK, "--scheme", "rkmk4", "--dt", str(DT), "--t-end",
                            str(T_END), "--save-every", "10000", "--out", out, "--force", "--quiet"], check=True)
            with h5py.File(out, "r") as f:
                times.append(float(f["/diagnostics"].attrs["cpu_seconds"]))
    return statistics.median(times)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--lgi", default=os.path.join(ROOT, "build", "release", "lgi"), help="the lgi executable")
    p.add_argument("--repeat", type=int, default=15)
    a = p.parse_args()
    scene = lgi.Scene.from_file(BOOK)
    lgi.simulate(scene, "rkmk4", T_END, dt=DT, save_every=10_000)  # warm-up
    print(f"lgi.simulate, rkmk4, 10^4 steps (dt = {DT}, t_end = {T_END}), median of {a.repeat} calls")
    print(f"{'output':<24}{'samples':>8}{'call wall':>11}{'call CPU':>10}{'stepping':>10}{'output':>9}"
          f"{'overhead':>10}{'overhead/stepping':>19}")
    for label, save_every in (("small (save_every=1e4)", 10_000), ("full (save_every=1)", 1)):
        wall, cpu, stepping, output, n, overhead = time_calls(scene, save_every, a.repeat)
        print(f"{label:<24}{n:>8}{wall * 1e3:>9.3f}ms{cpu * 1e3:>8.3f}ms{stepping * 1e3:>8.3f}ms"
              f"{output * 1e3:>7.3f}ms{overhead * 1e3:>8.3f}ms{100 * overhead / stepping:>18.2f}%")
    if os.access(a.lgi, os.X_OK):
        cli = cli_stepping(a.lgi, min(a.repeat, 7))
        wall, _, stepping, _, _, _ = time_calls(scene, 10_000, a.repeat)
        print(f"stepping time: lgi simulate reports {cli * 1e3:.3f} ms (/diagnostics cpu_seconds), the module "
              f"{stepping * 1e3:.3f} ms; module call wall / CLI stepping - 1 = "
              f"{100 * (wall / cli - 1):.2f}%")
    else:
        print(f"(no lgi executable at {a.lgi}: the CLI comparison is left out; give --lgi)")


if __name__ == "__main__":
    main()
