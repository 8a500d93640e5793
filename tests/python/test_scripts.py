"""The scripts under scripts/ as a user runs them: plot scripts (scripts/plots),
demo.sh, table1.sh, benchmark_ratios.py.

Run with Debian's python3: /usr/bin/python3 -m pytest -q -p no:cacheprovider tests/python
(CTest: scripts_pytest). Input HDF5 files are made by the built lgi, the path in
$LGI_EXECUTABLE (default build/release/lgi); every output goes under pytest's
tmp_path ($LGI_TEST_TMPDIR/scripts_pytest under CTest, see conftest.py).
"""
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

sys.dont_write_bytecode = True
ROOT = Path(__file__).resolve().parents[2]
SCRIPTS = ROOT / "scripts"
PLOTS = SCRIPTS / "plots"
SCENES = ROOT / "experiments" / "scenes"
PY = "/usr/bin/python3"
LGI = Path(os.environ.get("LGI_EXECUTABLE", ROOT / "build" / "release" / "lgi"))
ENV = dict(os.environ, PYTHONDONTWRITEBYTECODE="1", MPLBACKEND="Agg")

sys.path.insert(0, str(PLOTS))
import lgi_plot_common as c  # noqa: E402
import work_precision  # noqa: E402


def run(cmd, **kw):
    p = subprocess.run([str(x) for x in cmd], capture_output=True, text=True, env=ENV, timeout=120, **kw)
    assert p.returncode == 0, f"{cmd} exited {p.returncode}\nstdout:\n{p.stdout}\nstderr:\n{p.stderr}"
    return p


def lgi(*args):
    if not LGI.exists():
        pytest.skip(f"no lgi at {LGI} (build it, or set LGI_EXECUTABLE)")
    return run([LGI, *args])


@pytest.fixture(scope="session")
def data(tmp_path_factory):
    """Small trajectories and a work-precision file, written once per session."""
    d = tmp_path_factory.mktemp("data")
    top = SCENES / "heavy_top_trindade_1.toml"
    book = SCENES / "dzhanibekov_book_axis2.toml"
    lgi("simulate", "--scene", top, "--scheme", "rkmk4", "--dt", "1e-2", "--t-end", "1", "--out", d / "top_a.h5")
    lgi("simulate", "--scene", top, "--scheme", "rkmk4", "--dt", "2e-2", "--t-end", "1", "--out", d / "top_b.h5")
    lgi("simulate", "--scene", book, "--scheme", "rkmk4", "--dt", "1e-2", "--t-end", "2", "--out", d / "book.h5")
    lgi("work-precision", "--scene", SCENES / "free_body_hlw.toml", "--schemes", "rkmk4,cf4",
        "--dt", "0.1,0.05,0.025", "--t-end", "1", "--out", d / "wp.h5")
    return {"top_a": d / "top_a.h5", "top_b": d / "top_b.h5", "book": d / "book.h5", "wp": d / "wp.h5"}


def plot(script, out, *files, extra=()):
    return run([PY, PLOTS / script, "--out", out, *extra, *files])


# ── (a) every plot script creates its --out folder ───────────────────────────
def test_parser_creates_nested_out_folder(tmp_path):
    out = tmp_path / "a" / "b" / "c"
    args = c.parser("test").parse_args(["--out", str(out)])
    assert out.is_dir() and args.out == str(out)


def test_every_plot_script_takes_out_through_the_common_helper():
    for script in sorted(PLOTS.glob("*.py")):
        text = script.read_text()
        if script.name == "lgi_plot_common.py" or '__name__ == "__main__"' not in text:
            continue  # the helper itself, and modules imported by scripts (cost_table.py)
        if "matplotlib" not in text and "lgi_plot_common" not in text:
            continue  # a data helper that writes one file, not figures (cardan_family.py, steady_precession.py)
        assert "c.parser(" in text or "type=c.out_dir" in text, \
            f"{script.name}: --out must go through lgi_plot_common (parser or out_dir), which creates the folder"


@pytest.mark.parametrize("script,key,names", [
    ("animate.py", "book", ["dzhanibekov_book_axis2.gif", "tumbling_frames.png"]),
    ("heavy_top.py", "top_a", ["heavy_top_case1.png", "heavy_top_case1.pdf"]),
    ("work_precision.py", "wp", ["work_precision.png", "convergence.png"]),
    ("dzhanibekov.py", "book", ["dzhanibekov_omega.png"]),
    ("ellipsoids.py", "book", ["ellipsoids_intermediate.png"]),
])
def test_plot_script_out_to_missing_nested_folder(data, tmp_path, script, key, names):
    out = tmp_path / "new" / "nested" / "dir"
    extra = ("--frames", "3") if script == "animate.py" else ()
    plot(script, out, data[key], extra=extra)
    for n in names:
        assert (out / n).is_file() and (out / n).stat().st_size > 0, n


# ── (b) no silent overwrite ──────────────────────────────────────────────────
def test_heavy_top_two_files_give_two_figures(data, tmp_path):
    out = tmp_path / "figs"
    plot("heavy_top.py", out, data["top_a"], data["top_b"])
    a, b = out / "heavy_top_case1_top_a.png", out / "heavy_top_case1_top_b.png"
    assert a.is_file() and b.is_file()
    assert a.read_bytes() != b.read_bytes()
    assert not (out / "heavy_top_case1.png").exists()


def test_animate_two_files_of_one_scene_give_two_gifs(data, tmp_path):
    copy = tmp_path / "book_copy.h5"
    copy.write_bytes(data["book"].read_bytes())
    out = tmp_path / "anim"
    plot("animate.py", out, data["book"], copy, extra=("--frames", "2"))
    assert (out / "dzhanibekov_book_axis2_book.gif").is_file()
    assert (out / "dzhanibekov_book_axis2_book_copy.gif").is_file()


def test_unique_names_and_claim(tmp_path):
    assert c.unique_names(["x", "y"], ["d/a.h5", "d/b.h5"]) == ["x", "y"]
    assert c.unique_names(["x", "x"], ["d/a.h5", "d/b.h5"]) == ["x_a", "x_b"]
    assert c.unique_names(["x", "x"], ["d/a.h5", "e/a.h5"]) == ["x_a_1", "x_a_2"]
    p = tmp_path / "once.png"
    c.claim(p)
    with pytest.raises(SystemExit):
        c.claim(p)


# ── (c) log axes have enough labelled ticks; (d) one unit per panel ──────────
def log_axes(fig):
    for ax in fig.axes:
        if not ax.get_visible() or ax.name == "3d":
            continue
        for which in ("x", "y"):
            if (ax.get_xscale() if which == "x" else ax.get_yscale()) == "log":
                yield ax, which


@pytest.mark.parametrize("kind", ["conv", "wp"])
def test_work_precision_log_axes_have_labelled_ticks(data, kind):
    fig = work_precision.figure(work_precision.load([str(data["wp"])]), kind)
    found = list(log_axes(fig))
    assert len(found) == 4  # two panels, both axes log
    for ax, which in found:
        labels = c.labelled_ticks(ax, which)
        assert len(labels) >= 2, f"{kind} {ax.get_title()} {which}: labelled ticks {labels}"
    c.plt.close(fig)


@pytest.mark.parametrize("lim", [(2.2e-9, 8e-9), (5e-9, 5e-8), (3.1e-4, 1.9e-3), (1.01, 1.2), (1e-16, 1e-2)])
def test_fix_log_ticks_on_narrow_and_wide_ranges(lim):
    fig, ax = c.plt.subplots()
    ax.loglog([1e-3, 1e-1], [lim[0], lim[1]])
    ax.set_ylim(*lim)
    c.fix_log_ticks(ax)
    labels = c.labelled_ticks(ax, "y")
    assert len(labels) >= 2, labels
    assert ax.get_ylim() == pytest.approx(lim)
    c.plt.close(fig)


def test_work_precision_panels_separate_attitude_and_momentum(data):
    fig = work_precision.figure(work_precision.load([str(data["wp"])]), "wp")
    labels = [ax.get_ylabel() for ax in fig.axes if ax.get_visible() and ax.get_ylabel()]
    assert len(labels) == 2
    assert "attitude" in labels[0] and "(rad)" in labels[0]
    assert "momentum" in labels[1] and "rad" not in labels[1]
    c.plt.close(fig)


# ── (g) table1.sh: the unit in its header and docs is the unit of its values ─
def test_table1_header_says_milliseconds_like_its_values():
    text = (SCRIPTS / "table1.sh").read_text()
    header = text.split("set -euo pipefail")[0]
    assert "CPU seconds" not in header and "CPU milliseconds" in header
    assert re.search(r'def cell\(v\):\s*\n\s*return "fail" if v is None else "%.3g" % \(1e3 \* v\)', text), \
        "cells are cpu_seconds x 1e3: milliseconds"
    assert '"%s, case %d (ms)"' in text and '"case %d (ms)"' in text
    assert "Ex.%d" not in text
    readme = (ROOT / "README.md").read_text()
    line = next(l for l in readme.splitlines() if l.startswith("scripts/table1.sh"))
    assert "milliseconds" in line and "CPU seconds" not in line


def test_table1_progress_on_stderr(tmp_path):
    if not LGI.exists():
        pytest.skip(f"no lgi at {LGI}")
    out = tmp_path / "t1"
    p = run(["bash", SCRIPTS / "table1.sh", "--lgi", LGI, "--repeat", "1", "--cases", "2", "--tol", "1e-3",
             "--dt", "1e-2", "--out", out])
    progress = [l for l in p.stderr.splitlines() if re.fullmatch(r"table1: case 2 \(1/1\) \S+, run \d+/17", l)]
    assert len(progress) == 17 and "quat/rk4" in "".join(progress)
    md = (out / "table1.md").read_text()
    assert "Quaternion, case 2 (ms)" in md and "| Lie-group scheme (SO(3) x R^3) | case 2 (ms) |" in md
    assert "CPU milliseconds" in md


def fake_bench(tmp_path):
    """A stand-in lgi_bench: lists three benchmarks, prints progress lines, writes its JSON report."""
    fake = tmp_path / "fake_bench"
    names = ["free_body_hlw/quat/rk4", "free_body_hlw/rkmk4", "so3_exp"]
    fake.write_text(f"""#!{PY}
import json, sys
names = {names!r}
per_step = {{"free_body_hlw/quat/rk4": 150.0, "free_body_hlw/rkmk4": 300.0}}  # the scheme benchmarks' names
args = dict(a.split("=", 1) for a in sys.argv[1:] if "=" in a)
if args.get("--benchmark_list_tests") == "true":
    print("\\n".join(names)); sys.exit(0)
bench = []
for n in names:
    print(f"{{n:<40}} 100 ns 100 ns 1000", flush=True)
    b = {{"name": n, "cpu_time": 30.0, "time_unit": "ns"}}
    if n in per_step:
        b["ns_per_step"] = per_step[n]
    bench.append(b)
open(args["--benchmark_out"], "w").write(json.dumps({{"context": {{"num_cpus": 2}}, "benchmarks": bench}}))
""")
    fake.chmod(0o755)
    return fake, names


def test_benchmark_ratios_progress_on_stderr(tmp_path):
    fake, names = fake_bench(tmp_path)
    p = run([PY, SCRIPTS / "benchmark_ratios.py", "--bench", fake, "--min-time", "0.001", "--skip-equal-error",
             "--skip-long-run"])
    assert [l for l in p.stderr.splitlines() if re.match(r"benchmark_ratios: \d/3 ", l)] == \
        [f"benchmark_ratios: {i + 1}/3 {n}" for i, n in enumerate(names)]
    assert "2.00" in p.stdout
    assert "equal error" not in p.stdout


def test_benchmark_ratios_vector_peaks_over_the_scalar_peak():
    """The ensemble's ceiling line: each packed peak over the scalar peak, and nothing
    when either is missing."""
    sys.path.insert(0, str(SCRIPTS))
    from benchmark_ratios import vector_peak_line
    limits = {"limits/scalar_peak": {"scalar_flops_per_ns": 10.0},
              "limits/vector_peak/sse2": {"lane_flops_per_ns": 20.0},
              "limits/vector_peak/avx2": {"lane_flops_per_ns": 23.0}}
    line = vector_peak_line(limits)
    assert "sse2 20.0 lane operations per ns = 2.00 x" in line and "avx2 23.0 lane operations per ns = 2.30 x" in line
    assert vector_peak_line({"limits/scalar_peak": {"scalar_flops_per_ns": 10.0}}) is None
    assert vector_peak_line({"limits/vector_peak/avx2": {"lane_flops_per_ns": 23.0}}) is None


def test_benchmark_ratios_cost_at_equal_error(tmp_path):
    """The heavy tops' bars: cheapest Lie-group scheme over cheapest baseline at the
    target error, interpolated along each curve, from the CSV lgi work-precision writes
    (a stand-in lgi here, whose rows fix the answer: rkmk-dop853 reaches 1e-10 at
    tol 1e-10, in 20 us; quat/rkf78 between its two rows, at 40 us)."""
    bench, _ = fake_bench(tmp_path)
    fake_lgi = tmp_path / "fake_lgi"
    fake_lgi.write_text(f"""#!{PY}
import sys
a = sys.argv[1:]
assert a[0] == "work-precision" and "--quiet" in a and "--repeat" in a
out = a[a.index("--out") + 1]
head = "scheme,dt,tol,error,cpu_seconds_min,status"
rows = ["rkmk-dop853,nan,1e-09,1e-09,1.5e-05,ok", "rkmk-dop853,nan,1e-10,1e-10,2e-05,ok",
        "rkmk-dp54,nan,1e-10,1e-10,9e-05,ok", "split-axes@kahan-li8,0.1,nan,nan,1e-06,ok",
        "quat/rkf78,nan,1e-10,1e-09,2e-05,ok", "quat/rkf78,nan,1e-12,1e-11,8e-05,ok",
        "matrix/rkf78,nan,1e-10,1e-08,1e-06,failed: blow-up"]
open(out[:-3] + ".csv", "w").write("\\n".join([head] + rows) + "\\n")
""")
    fake_lgi.chmod(0o755)
    p = run([PY, SCRIPTS / "benchmark_ratios.py", "--bench", bench, "--min-time", "0.001",
             "--processes", "0", "--lgi", fake_lgi, "--skip-long-run"])
    lines = [l for l in p.stdout.splitlines() if "at error" in l]
    assert lines == [
        "# heavy_top_hlw at error 1e-10: rkmk-dop853 20.0 us / quat/rkf78 40.0 us = 0.500 (bar: <= 0.5)",
        "# heavy_top_trindade_1 over 2 s at error 1e-08: rkmk-dop853 15.0 us / quat/rkf78 20.0 us "
        "= 0.750 (bar: <= 0.5)"], p.stdout
    assert "lgi work-precision on heavy_top_hlw" in p.stderr


def test_benchmark_ratios_long_run(tmp_path):
    """The DMV bar over one long run: 10^7 steps of each scheme with lgi simulate, the
    minimum of its cpu_seconds over 3 runs each, per step (a stand-in lgi whose files
    hold 0.7 s for dmv-pre10, 1.0 s for quat/rk4, and 0.1 s less on each later run)."""
    bench, _ = fake_bench(tmp_path)
    calls = tmp_path / "calls"
    fake_lgi = tmp_path / "fake_lgi"
    fake_lgi.write_text(f"""#!{PY}
import sys, h5py
a = sys.argv[1:]
assert a[0] == "simulate" and "--quiet" in a and a[a.index("--dt") + 1] == "0.01" and a[a.index("--t-end") + 1] == "100000.0"
assert a[a.index("--scene") + 1].endswith("tests/benchmarks/scenes/free_body_hairer_vilmart.toml")
scheme = a[a.index("--scheme") + 1]
n = open({str(calls)!r}, "a+").write(scheme + "\\n")
k = sum(1 for l in open({str(calls)!r}) if l.strip() == scheme)
with h5py.File(a[a.index("--out") + 1], "w") as f:
    f.create_group("diagnostics").attrs["cpu_seconds"] = (0.7 if scheme == "dmv-pre10" else 1.0) - 0.1 * (k - 1)
""")
    fake_lgi.chmod(0o755)
    p = run([PY, SCRIPTS / "benchmark_ratios.py", "--bench", bench, "--min-time", "0.001",
             "--processes", "0", "--lgi", fake_lgi, "--skip-equal-error"])
    lines = [l for l in p.stdout.splitlines() if "steps (lgi simulate)" in l]
    assert lines == ["# free_body_hairer_vilmart over 1e+07 steps (lgi simulate): dmv-pre10 50.0 ns / "
                     "quat/rk4 80.0 ns per step = 0.625 (bar: <= 0.45)"], p.stdout
    assert calls.read_text().split() == ["dmv-pre10", "quat/rk4"] * 3


# ── (h) demo.sh --out DIR writes into DIR only ───────────────────────────────
def files_written_since(t0, skip):
    """Files under the repository modified after t0, outside .git, CMake build trees
    (folders with a CMakeCache.txt) and the folders in skip."""
    found = []
    for d, dirs, files in os.walk(ROOT):
        dp = Path(d)
        if dp.name == ".git" or (dp / "CMakeCache.txt").exists() or any(dp == s for s in skip):
            dirs[:] = []
            continue
        found += [dp / f for f in files if (dp / f).lstat().st_mtime > t0]
    return found


def test_demo_out_writes_into_out_only(tmp_path):
    if not LGI.exists():
        pytest.skip(f"no lgi at {LGI}")
    out = tmp_path / "nested" / "demo"
    t0 = time.time() - 0.01
    p = run(["bash", SCRIPTS / "demo.sh", "--out", out, "--build-dir", LGI.parent])
    assert sorted(f.name for f in out.iterdir()) == sorted(
        f"book_axis{a}_{s}.h5" for a in (1, 2, 3) for s in ("rkmk4", "exact"))
    assert "dzhanibekov_book_axis2" in p.stdout
    assert files_written_since(t0, [tmp_path.resolve()]) == []


def test_demo_and_build_paper_document_out():
    for script in ("demo.sh", "build_paper.sh"):
        p = run(["bash", SCRIPTS / script, "--help"])
        assert "--out DIR" in p.stdout, script
    readme = (ROOT / "README.md").read_text()
    assert "scripts/demo.sh --out" in readme and "scripts/build_paper.sh --quick --out" in readme


# ── (f, i) README lists every script; its GIF names are the written ones ─────
def test_readme_lists_every_script():
    readme = (ROOT / "README.md").read_text()
    for f in sorted(list(SCRIPTS.glob("*.sh")) + list(SCRIPTS.glob("*.py")) + list(PLOTS.glob("*.py"))):
        rel = f.relative_to(ROOT).as_posix()
        assert f"`{rel}`" in readme, f"README.md does not list {rel}"


def test_readme_gif_names_are_the_written_ones():
    readme = (ROOT / "README.md").read_text()
    animate = (PLOTS / "animate.py").read_text()
    build = (SCRIPTS / "build_paper.sh").read_text()
    assert "c.scene_label(r[\"parameters\"])" in animate  # GIF named after the scene file
    assert 'plot animate.py' in build  # build_paper.sh writes the GIFs with animate.py into figures/
    for scene in ("dzhanibekov_book_axis2", "prism_edurev"):  # the scenes build_paper.sh animates
        assert (SCENES / f"{scene}.toml").is_file()
        assert f"paper/build/figures/{scene}.gif" in readme
    for media in re.findall(r"docs/media/[\w.]+\.gif", readme):
        assert (ROOT / media).is_file(), media


# ── (g) what a scheme is comes from its facts, never its name ────────────────
FACTS = [
    {"name": "lgvi", "kind": "lie-group", "base": None, "family": "Moser-Veselov", "order": 2},
    {"name": "lgvi@yoshida4", "kind": "composition", "base": "lgvi", "family": "composition of lgvi", "order": 4},
    {"name": "quat/rk4", "kind": "baseline", "base": None, "family": "baseline quat", "order": 4, "baseline": True},
    # names without '@' or '/': only the facts say composition and baseline
    {"name": "plain-comp", "kind": "composition", "base": "lgvi", "family": "composition of lgvi", "order": 4},
    {"name": "odd-baseline", "kind": "baseline", "base": None, "family": "baseline odd", "order": 4},
]


def test_styles_and_families_read_the_facts_not_the_names(tmp_path):
    import cost_table
    import make_tables
    c.use_scheme_facts(FACTS)
    try:
        assert c.scheme_style("plain-comp")["linestyle"] == "-."
        assert c.scheme_style("odd-baseline")["linestyle"] == "--"
        assert c.scheme_style("lgvi")["linestyle"] == "-"
        assert c.scheme_style("unknown@x")["linestyle"] == "-"  # no facts: solid, whatever the name
        assert make_tables.is_baseline("odd-baseline") and not make_tables.is_baseline("a/b")
    finally:
        c.use_scheme_facts([])
    assert cost_table.family_of("plain-comp", FACTS) == "Moser-Veselov"
    assert cost_table.family_of("odd-baseline", FACTS) == "baseline odd"
    assert cost_table.family_of("not-registered", FACTS) == "other"
    path = tmp_path / "schemes.json"
    path.write_text(json.dumps(FACTS))
    body, data = make_tables.schemes_table(str(path))
    row = next(line for line in body.splitlines() if "& composition &" in line)
    assert "@yoshida4" in row and "plain-comp" in row  # both compositions in their base's row
    assert "baseline odd &" in body and "baseline quat &" in body  # one row per baseline family


def test_plot_script_refuses_an_unreadable_schemes_json(tmp_path, data):
    p = subprocess.run([PY, PLOTS / "work_precision.py", "--out", tmp_path, "--schemes-json", tmp_path / "none.json",
                        data["wp"]], capture_output=True, text=True, env=ENV, timeout=120)
    assert p.returncode == 2
    assert "--schemes-json" in p.stderr and "none.json" in p.stderr
