#!/usr/bin/python3
"""Per-step cost of every scheme as a ratio to quat/rk4 on the same scene.

Runs build/release/lgi_bench (Google Benchmark) once, so every figure and its
baseline come from the same run, and prints a table (and, with --tex FILE, a
LaTeX table for the paper). The baseline is quat/rk4 where registered, else
rkmk4 (the table says which). Progress goes to stderr, one line per benchmark.

The preprocessed-DMV bar (dmv-pre10 / quat/rk4 on Hairer & Vilmart's body) is
also measured in --processes fresh processes (default 5) and printed as the
median and range of their ratios: a process's stack placement (address-space
randomisation) moves the DMV step's cost by up to ~20% (false store-to-load
dependencies between addresses 4 KiB apart), so one process is one sample.

What bounds that step (docs/performance.md §3, "The arithmetic limit") is printed on one line from the
limits/ benchmarks: the core's scalar peak, and dmv-pre10's step alone and with two
trajectories stepped in alternation. A second line gives the packed peaks of the
instruction sets this CPU has over the scalar peak: the ceiling of the ensemble's
speed-up over the scalar loop for a throughput-bound step (docs/performance.md §5).

The same bar over one long run, as the Fortran comparison was timed (10^7 steps, so t
reaches 10^5, where a fixed-step run's h jitters by ulp(t)), is measured with
`lgi simulate` (its cpu_seconds, minimum of 3 alternating runs of each scheme;
--skip-long-run to leave it out).

The cost at equal error on heavy tops (the performance bars there) is measured with
`lgi work-precision` (--lgi, default build/release/lgi; --skip-equal-error to
leave it out): on each study's scene, the CPU time (minimum of 5 repeats) at which
the cheapest Lie-group scheme and the cheapest baseline reach the target error,
log-log interpolated along each curve as in the paper's "cost at equal error"
table (scripts/plots/cost_table.py), and their ratio.

The tangent flow in SIMD lanes (bench_tangent_lanes.cpp; the Cardan top's in
bench_cardan_tangent_lanes.cpp, tangent/cardan_*; docs/ensemble.md): the chaos
indicators' loop per trajectory, in the lanes of each instruction set over the scalar loop
(trajectories per second per core), and that speed-up as a fraction of the instruction set's
vector ceiling (its packed peak over the scalar peak, from limits/).

--filter REGEX runs only the benchmarks it matches (Google Benchmark's --benchmark_filter),
e.g. 'tangent/|limits/(scalar|vector)_peak' for the tangent lanes and their ceilings alone.

usage: scripts/benchmark_ratios.py [--bench PATH] [--min-time S] [--processes N] [--tex FILE] [--json FILE]
                                   [--lgi PATH] [--skip-equal-error] [--skip-long-run] [--filter REGEX]
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile


def vector_peak_line(limits):
    """The packed peaks (limits/vector_peak/<isa>, bench_issue_limit.cpp) over the scalar
    peak: the most an ensemble kernel can gain over the scalar loop where the scalar step
    is bound by throughput. None without the scalar peak or any vector peak."""
    scalar = limits.get("limits/scalar_peak", {}).get("scalar_flops_per_ns")
    peaks = [(name.rsplit("/", 1)[1], b["lane_flops_per_ns"]) for name, b in limits.items()
             if name.startswith("limits/vector_peak/") and "lane_flops_per_ns" in b]
    if not scalar or not peaks:
        return None
    return ("# vector peaks: " + ", ".join(f"{isa} {v:.1f} lane operations per ns = {v / scalar:.2f} x the scalar peak"
                                          for isa, v in peaks)
            + " (the most an ensemble kernel can gain over a throughput-bound scalar loop)")


def tangent_lines(tangents, limits):
    """One line per tangent/<scene>/<loop>/<isa> benchmark (bench_tangent_lanes.cpp,
    bench_cardan_tangent_lanes.cpp): trajectories per second, the speed-up over .../scalar (the
    scalar loop, scalar_tangent_step or scalar_cardan_tangent_step; .../eigen and .../torus are the
    Eigen forms, no ceiling) and, where
    limits/ measured it, the fraction of that instruction set's vector ceiling (its packed peak over
    the scalar peak, vector_peak_line). Bars (issue 52): >= 3x on AVX-512, >= 0.7 of the ceiling on AVX2."""
    scalar = limits.get("limits/scalar_peak", {}).get("scalar_flops_per_ns")
    lines = []
    for name, rate in tangents.items():
        base, isa = name.rsplit("/", 1)
        if isa == "scalar" or base + "/scalar" not in tangents:
            continue
        ratio = rate / tangents[base + "/scalar"]
        line = f"# {name}: {rate:.0f} trajectories/s, {ratio:.2f} x the scalar loop"
        peak = limits.get("limits/vector_peak/" + isa, {}).get("lane_flops_per_ns")
        if scalar and peak and isa not in ("eigen", "torus"):
            ceiling = peak / scalar
            line += f", {ratio / ceiling:.2f} of the {isa} ceiling ({ceiling:.2f} x)"
        if isa == "avx512":
            line += " (bar: >= 3 x)"
        elif isa == "avx2":
            line += " (bar: >= 0.7 of the ceiling)"
        lines.append(line)
    return lines


def tex_escape(s):
    return s.replace("_", "\\_")


def write_tex(path, per_scene, maps, ctx):
    """A longtable for the paper: one row per scheme, ns/step and the ratio to
    the baseline for each scene; then the Lie-group maps' ns per call."""
    scenes = list(per_scene)
    base = {sc: ("quat/rk4" if "quat/rk4" in per_scene[sc] else "rkmk4") for sc in scenes}
    schemes = list(dict.fromkeys(s for sc in scenes for s in per_scene[sc]))
    cols = "@{}l" + " rr" * len(scenes) + "@{}"
    head = "scheme & " + " & ".join(f"\\multicolumn{{2}}{{c}}{{\\texttt{{{tex_escape(sc)}}}}}" for sc in scenes)
    sub = " & " + " & ".join("ns/step & ratio" for _ in scenes)
    caption = ("Cost per step from Google Benchmark (\\texttt{lgi\\_bench}, one run, "
               + ", ".join(f"ratio to \\texttt{{{base[sc]}}} on \\texttt{{{tex_escape(sc)}}}" for sc in scenes)
               + f", measured in the same run; {ctx.get('num_cpus', '?')} CPUs at {ctx.get('mhz_per_cpu', '?')} MHz). "
               "Produced by \\texttt{scripts/benchmark\\_ratios.py}. A dash: the scheme does not run on that scene.")
    lines = ["% generated by scripts/benchmark_ratios.py — do not edit",
             "\\begingroup\\footnotesize",  # the long scheme names stay within the text width
             f"\\begin{{longtable}}{{{cols}}}", f"\\caption{{{caption}}}\\label{{tab:bench}}\\\\",
             "\\toprule", head + " \\\\", sub + " \\\\", "\\midrule", "\\endfirsthead",
             "\\toprule", head + " \\\\", sub + " \\\\", "\\midrule", "\\endhead"]
    for s in schemes:
        cells = []
        for sc in scenes:
            ns = per_scene[sc].get(s)
            cells += ["--", "--"] if ns is None else [f"{ns:.0f}", f"{ns / per_scene[sc][base[sc]]:.2f}"]
        lines.append(f"\\texttt{{{tex_escape(s)}}} & " + " & ".join(cells) + " \\\\")
    if maps:
        lines.append("\\midrule")
        for name, t, unit in maps:
            lines.append(f"\\texttt{{{tex_escape(name)}}} & \\multicolumn{{{2 * len(scenes)}}}{{l}}"
                         f"{{{t:.1f} {unit} per call}} \\\\")
    lines += ["\\bottomrule", "\\end{longtable}", "\\endgroup"]
    with open(path, "w") as f:
        f.write("\n".join(lines) + "\n")


def run_bench(bench, min_time, only=None):
    """Run every benchmark of `bench` once and return its JSON report; on stderr, one
    progress line per benchmark ("benchmark_ratios: 3/52 free_body_hlw/rkmk4") as it finishes."""
    selection = [f"--benchmark_filter={only}"] if only else []
    names = subprocess.run([bench, "--benchmark_list_tests=true"] + selection, check=True, capture_output=True,
                           text=True).stdout.split()
    print(f"benchmark_ratios: {len(names)} benchmarks, min time {min_time} s each", file=sys.stderr, flush=True)
    with tempfile.TemporaryDirectory(prefix="lgi_bench_") as tmp:
        report = os.path.join(tmp, "report.json")
        proc = subprocess.Popen([bench, "--benchmark_format=console", "--benchmark_color=false",
                                 f"--benchmark_out={report}", "--benchmark_out_format=json",
                                 f"--benchmark_min_time={min_time}"] + selection,
                                stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        done = 0
        for line in proc.stdout:
            first = line.split(maxsplit=1)[0] if line.strip() else ""
            if first in names:
                done += 1
                print(f"benchmark_ratios: {done}/{len(names)} {first}", file=sys.stderr, flush=True)
        if proc.wait() != 0:
            raise subprocess.CalledProcessError(proc.returncode, bench)
        with open(report) as f:
            return f.read()


def dmv_bar_over_processes(bench, processes):
    """dmv-pre10 / quat/rk4 on Hairer & Vilmart's body, one ratio per fresh process
    (each the median of 3 repetitions within the process)."""
    ratios = []
    for _ in range(processes):
        out = subprocess.run([bench, "--benchmark_filter=free_body_hairer_vilmart/(quat/rk4|dmv-pre10)$",
                              "--benchmark_repetitions=3", "--benchmark_min_time=0.1",
                              "--benchmark_report_aggregates_only=true", "--benchmark_format=json"],
                             check=True, capture_output=True, text=True).stdout
        med = {b["run_name"]: b["ns_per_step"] for b in json.loads(out)["benchmarks"]
               if b.get("aggregate_name") == "median"}
        ratios.append(med["free_body_hairer_vilmart/dmv-pre10"] / med["free_body_hairer_vilmart/quat/rk4"])
    return sorted(ratios)


SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "experiments", "scenes")
LIE_GROUP = ("rkmk-dop853", "rkmk-verner87", "rkmk-verner98", "rkmk-verner65", "rkmk-dp54", "rkmk-cayley-dop853",
             "rkmk-cayley-verner87", "rkmk-cayley-verner98", "split-exact@kahan-li8",
             "split-symmetric@kahan-li8", "split-axes@kahan-li8", "split-symmetric@bcm-processed6",
             "split-symmetric@bcm-processed8")
BASELINES = ("quat/rkf78", "quat/dopri5", "quat/bs", "rotvec/rkf78", "matrix/rkf78")
# (scene, t_end or None for the scene's, target error, bar, fixed steps of the splittings)
EQUAL_ERROR_STUDIES = (
    ("heavy_top_hlw", None, 1e-10, 0.5, (0.1, 0.05, 0.025, 0.012, 0.006)),
    ("heavy_top_trindade_1", 2.0, 1e-8, 0.5, (0.1, 0.05, 0.025, 0.012, 0.006)),
)
TOLERANCES = "1e-6,1e-7,1e-8,1e-9,1e-10,1e-11,1e-12,1e-13"


def cheapest(rows, names, target, cpu_at_error):
    """(scheme, CPU seconds) of the cheapest of `names` to reach `target`, or None."""
    best = None
    for name in names:
        mine = [r for r in rows if r["scheme"] == name and r["status"] == "ok"]
        cpu = cpu_at_error([float(r["error"]) for r in mine], [float(r["cpu_seconds_min"]) for r in mine], target)
        if cpu is not None and (best is None or cpu < best[1]):
            best = (name, cpu)
    return best


def equal_error_ratios(lgi, tmp):
    """One line per study: cheapest Lie-group scheme / cheapest baseline at the target error."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "plots"))
    from cost_table import cpu_at_error  # matplotlib and h5py come with it: imported only here
    lines = []
    for scene, t_end, target, bar, dts in EQUAL_ERROR_STUDIES:
        out = os.path.join(tmp, scene + ".h5")
        cmd = [lgi, "work-precision", "--scene", os.path.join(SCENES, scene + ".toml"),
               "--schemes", ",".join(LIE_GROUP + BASELINES), "--tol", TOLERANCES,
               "--dt", ",".join(map(repr, dts)), "--repeat", "5", "--out", out, "--quiet"]
        if t_end is not None:
            cmd += ["--t-end", repr(t_end)]
        print(f"benchmark_ratios: lgi work-precision on {scene}", file=sys.stderr, flush=True)
        subprocess.run(cmd, check=True)
        with open(out[:-3] + ".csv") as f:
            rows = list(csv.DictReader(f))
        lie = cheapest(rows, LIE_GROUP, target, cpu_at_error)
        base = cheapest(rows, BASELINES, target, cpu_at_error)
        span = f" over {t_end:g} s" if t_end is not None else ""
        if lie is None or base is None:
            lines.append(f"# {scene}{span} at error {target:g}: no "
                         f"{'Lie-group scheme' if lie is None else 'baseline'} reached it (bar: <= {bar})")
            continue
        lines.append(f"# {scene}{span} at error {target:g}: {lie[0]} {lie[1] * 1e6:.1f} us / {base[0]} "
                     f"{base[1] * 1e6:.1f} us = {lie[1] / base[1]:.3f} (bar: <= {bar})")
    return lines


BENCH_SCENES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "benchmarks", "scenes")
LONG_RUN = ("free_body_hairer_vilmart", 0.01, 1e5)  # scene, h, t_end: 10^7 steps


def long_run_ratio(lgi, tmp, repeats=3):
    """dmv-pre10 / quat/rk4 per step over one long run each, from lgi simulate's cpu_seconds."""
    import h5py  # only here: the per-step table needs no h5py
    scene, dt, t_end = LONG_RUN
    steps = round(t_end / dt)
    print(f"benchmark_ratios: lgi simulate, {steps:.0e} steps, dmv-pre10 and quat/rk4", file=sys.stderr, flush=True)
    best = {}
    out = os.path.join(tmp, "long_run.h5")
    for _ in range(repeats):
        for scheme in ("dmv-pre10", "quat/rk4"):
            subprocess.run([lgi, "simulate", "--scene", os.path.join(BENCH_SCENES, scene + ".toml"), "--scheme", scheme,
                            "--dt", repr(dt), "--t-end", repr(t_end), "--save-every", str(10 * steps), "--out", out,
                            "--force", "--quiet"], check=True)
            with h5py.File(out, "r") as f:
                cpu = float(f["diagnostics"].attrs["cpu_seconds"])
            best[scheme] = min(best.get(scheme, cpu), cpu)
    dmv, rk4 = (best[k] / steps * 1e9 for k in ("dmv-pre10", "quat/rk4"))
    return (f"# {scene} over {steps:.0e} steps (lgi simulate): dmv-pre10 {dmv:.1f} ns / quat/rk4 {rk4:.1f} ns "
            f"per step = {dmv / rk4:.3f} (bar: <= 0.45)")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bench", default="build/release/lgi_bench")
    ap.add_argument("--min-time", default="0.05")
    ap.add_argument("--tex")
    ap.add_argument("--json")
    ap.add_argument("--processes", type=int, default=5)
    ap.add_argument("--lgi", default="build/release/lgi")
    ap.add_argument("--skip-equal-error", action="store_true")
    ap.add_argument("--skip-long-run", action="store_true")
    ap.add_argument("--filter", help="only the benchmarks this regular expression matches")
    a = ap.parse_args()
    out = run_bench(a.bench, a.min_time, a.filter)
    data = json.loads(out)
    if a.json:
        with open(a.json, "w") as f:
            f.write(out)
    per_scene = {}
    maps = []
    ensembles = {}
    tangents = {}
    limits = {}
    for b in data["benchmarks"]:
        if b.get("error_occurred"):
            continue  # e.g. an Euler-angle baseline on a scene that starts at its singularity
        if b["name"].startswith("ensemble/"):  # bench_ensemble.cpp: trajectories/s, scalar loop vs ensemble
            ensembles[b["name"]] = b["trajectories_per_second"]
            continue
        if b["name"].startswith("tangent/"):  # bench_tangent_lanes.cpp: the tangent flow, scalar loop vs lanes
            tangents[b["name"]] = b["trajectories_per_second"]
            continue
        if b["name"].startswith("limits/"):  # bench_issue_limit.cpp: what bounds a dmv-pre10 step
            limits[b["name"]] = b
            continue
        if b["name"].startswith("newton/"):
            continue  # the implicit schemes' Newton variants (bench_implicit_newton.cpp): not a per-scheme row
        if "ns_per_step" in b:
            scene, scheme = b["name"].split("/", 1)
            per_scene.setdefault(scene, {})[scheme] = b["ns_per_step"]
        else:
            maps.append((b["name"], b["cpu_time"], b["time_unit"]))
    rows = []
    for scene, schemes in per_scene.items():
        base = "quat/rk4" if "quat/rk4" in schemes else "rkmk4"
        for scheme, ns in schemes.items():
            rows.append((scene, scheme, ns, ns / schemes[base], base))
    print(f"{'scene':<22}{'scheme':<30}{'ns/step':>12}{'ratio':>9}  baseline")
    for r in rows:
        print(f"{r[0]:<22}{r[1]:<30}{r[2]:>12.1f}{r[3]:>9.2f}  {r[4]}")
    for name, t, unit in maps:
        print(f"{name:<22}{t:>10.2f} {unit} per call")
    # The preprocessed DMV bar (issue 13): dmv-pre10 <= 0.45 x quat/rk4 per step on
    # Hairer & Vilmart's body at h = 0.01 (tests/benchmarks/scenes/), same run.
    hv = per_scene.get("free_body_hairer_vilmart", {})
    if "quat/rk4" in hv:
        for scheme in ("dmv", "dmv-pre4", "dmv-pre6", "dmv-pre8", "dmv-pre10"):
            if scheme in hv:
                print(f"# free_body_hairer_vilmart: {scheme} / quat/rk4 = {hv[scheme] / hv['quat/rk4']:.3f}"
                      + (" (bar: <= 0.45)" if scheme == "dmv-pre10" else ""))
    if a.processes > 0 and "quat/rk4" in hv and "dmv-pre10" in hv:
        r = dmv_bar_over_processes(a.bench, a.processes)
        print(f"# free_body_hairer_vilmart: dmv-pre10 / quat/rk4 over {len(r)} processes: median "
              f"{r[len(r) // 2]:.3f}, range {r[0]:.3f}-{r[-1]:.3f} (bar: <= 0.45)")
    if {"limits/scalar_peak", "limits/dmv-pre10/one", "limits/dmv-pre10/two_interleaved"} <= limits.keys():
        print(f"# limits: {limits['limits/scalar_peak']['scalar_flops_per_ns']:.1f} scalar additions and "
              f"multiplications per ns at the core's peak; dmv-pre10 "
              f"{limits['limits/dmv-pre10/one']['ns_per_step']:.1f} ns per step alone, "
              f"{limits['limits/dmv-pre10/two_interleaved']['ns_per_step']:.1f} with two trajectories in alternation")
    if not a.skip_long_run:
        if os.path.exists(a.lgi):
            with tempfile.TemporaryDirectory(prefix="lgi_long_run_") as tmp:
                print(long_run_ratio(a.lgi, tmp))
        else:
            print(f"# long run: not measured (no lgi at {a.lgi}; --lgi PATH)")
    vector_line = vector_peak_line(limits)
    if vector_line:
        print(vector_line)
    # The ensemble stepper (docs/ensemble.md): trajectories per second per core over the scalar loop, same run.
    for name, rate in ensembles.items():
        base = name.rsplit("/", 1)[0] + "/scalar"
        if name != base and base in ensembles:
            print(f"# {name}: {rate:.0f} trajectories/s, {rate / ensembles[base]:.2f} x the scalar loop")
    # The tangent flow in lanes (docs/ensemble.md): over the scalar loop, and as a fraction of the ceiling.
    for line in tangent_lines(tangents, limits):
        print(line)
    # The heavy tops' cost at equal error (the work-precision bars), from lgi work-precision.
    if not a.skip_equal_error:
        if os.path.exists(a.lgi):
            with tempfile.TemporaryDirectory(prefix="lgi_equal_error_") as tmp:
                print("\n".join(equal_error_ratios(a.lgi, tmp)))
        else:
            print(f"# cost at equal error: not measured (no lgi at {a.lgi}; --lgi PATH)")
    ctx = data["context"]
    print(f"# {ctx.get('host_name', '')} {ctx.get('num_cpus', '')} cpus @ {ctx.get('mhz_per_cpu', '')} MHz, "
          f"library build {ctx.get('library_build_type', '')}")
    if a.tex:
        write_tex(a.tex, per_scene, maps, ctx)
    return 0


if __name__ == "__main__":
    sys.exit(main())
