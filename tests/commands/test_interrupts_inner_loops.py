"""Issue 50, item 1: every loop reads the stop flag at least once a second, also the
loops inside one row, run or analysis that can take many seconds: the rows of
`lgi region --cells` (a row's triangulation, sort and sweep), each run of `lgi
singularity`, the NAFF of `lgi frequencies`, the reference of `lgi work-precision`,
one branch of `lgi bifurcation` on a heavy top, one l of `lgi bifurcation --appelrot`,
the closed-form surface of `lgi actions --h`, the GALI times of `lgi indicators`
and the --statistics of `lgi quantum`. Each test starts the command on an
input whose loop lasts far longer than the wait (tens of seconds here), signals it
and checks that it ends within about a second and a half with 130 (143 after
SIGTERM), says so in one line and publishes nothing as complete. The last four wait
and measure in CPU time, robust to a loaded machine (pacing.signal_after_cpu)."""
import os
import re
import signal
import subprocess
import time

import h5py
import pacing
from pacing import slowdown

LGI = os.environ.get("LGI_EXECUTABLE", "build/release/lgi")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def signal_and_time(args, sig=signal.SIGINT, after=1.0):
    """(exit status, stderr, seconds from the signal to the exit) of lgi with `args`, signalled `after` s in."""
    return pacing.signal_and_time(LGI, args, sig, after)


def test_region_cells_sigint_within_a_row(tmp_path):
    """At --grid 700 one row of l is a 1.5-million-vertex triangulation, its sort and sweep (seconds);
    40 rows run far longer than the wait. The row in progress is dropped; nothing is written."""
    out = str(tmp_path / "cells.h5")
    code, err, waited = signal_and_time(["region", "--scene", os.path.join(SCENES, "lagrange_top_oblate.toml"),
                                         "--cells", "--l-range", "0:3:40", "--h-range", "-1.2:3:50", "--grid", "700",
                                         "--out", out])
    assert code == 130, err
    assert waited < 1.5 * slowdown(LGI), f"the signal was read {waited:.2f} s late"
    last = err.replace("\r", "\n").strip().splitlines()[-1]
    assert last.startswith("lgi: region --cells: interrupted by signal after ") and last.endswith(
        " of 2000 cells; nothing written"), err
    assert not os.path.exists(out) and not os.path.exists(out + ".partial")


def test_singularity_sigint_inside_one_run(tmp_path):
    """--quick at --dt 1e-8: the seven quick baselines end in milliseconds (euler-zxz/rk4 at the
    singular set, the rest adaptive), then rkmk4 takes 2.5e8 steps. The signal cuts that run: it is
    dropped, the seven before it are kept in <out>.partial, no CSV."""
    out = str(tmp_path / "s.h5")
    code, err, waited = signal_and_time(["singularity", "--scenes-dir", SCENES, "--quick", "--dt", "1e-8", "--quiet",
                                         "--out", out])
    assert code == 130, err
    assert waited < 1.5 * slowdown(LGI), f"the signal was read {waited:.2f} s late"
    # Normally the seven quick baselines are done when the signal comes; on a loaded machine the
    # signal may cut one of them (or the reference) instead: K runs kept, K <= 7, never rkmk4's.
    m = re.fullmatch(r"lgi: singularity interrupted by signal after (\d+) runs?; they are kept in (.*)\.partial\n", err)
    assert m and m.group(2) == out and int(m.group(1)) <= 7, err
    kept = int(m.group(1))
    assert not os.path.exists(out) and not os.path.exists(str(tmp_path / "s.csv"))
    with h5py.File(out + ".partial", "r") as f:
        assert text(f["parameters"].attrs["status"]) == "interrupted by signal"
        methods = [text(m) for m in f["results/method"][()]] if "results/method" in f else []
        assert len(methods) == kept and "rkmk4" not in methods, methods
        assert "trindade_4" not in f["scenes"]


def test_frequencies_sigterm_inside_the_analysis(tmp_path):
    """The exact flow samples 500 001 points in a fraction of a second; NAFF's 100 terms of them (whole
    run and halves) take far longer. SIGTERM inside the analysis: exit 143, nothing written."""
    out = str(tmp_path / "f.h5")
    code, err, waited = signal_and_time(["frequencies", "--scene", os.path.join(SCENES, "free_body_hlw.toml"),
                                         "--t-end", "5000", "--scheme", "exact", "--dt", "0.01", "--observable",
                                         "angular_momentum_1", "--terms", "100", "--quiet", "--out", out],
                                        sig=signal.SIGTERM, after=1.5)
    assert code == 143, err
    assert waited < 1.5 * slowdown(LGI), f"the signal was read {waited:.2f} s late"
    assert err == ("lgi: frequencies: interrupted by signal in the frequency analysis of 500001 samples; "
                   "nothing written\n"), err
    assert not os.path.exists(out) and not os.path.exists(out + ".partial")
    assert not os.path.exists(str(tmp_path / "f.csv"))


def test_work_precision_sigint_inside_the_reference(tmp_path):
    """The converged reference (rkmk-dop853 at tol 1e-14) of the general top over t = 1e5 runs far longer
    than the wait; its runs read the flag every step: no row yet, the .partial files are kept and named."""
    out = str(tmp_path / "w.h5")
    code, err, waited = signal_and_time(["work-precision", "--scene", os.path.join(SCENES, "general_top_richter.toml"),
                                         "--schemes", "rkmk4", "--dt", "0.01", "--t-end", "1e5", "--out", out])
    assert code == 130, err
    assert waited < 1.5 * slowdown(LGI), f"the signal was read {waited:.2f} s late"
    csv = str(tmp_path / "w.csv")
    assert err == (f"lgi: work-precision interrupted by signal after 0 rows; partial results kept in {out}.partial "
                   f"and {csv}.partial\n"), err
    assert not os.path.exists(out) and not os.path.exists(csv)
    with h5py.File(out + ".partial", "r") as f:
        assert text(f["diagnostics"].attrs["status"]) == "interrupted by signal"
        assert int(f["diagnostics"].attrs["rows"]) == 0


def test_bifurcation_sigint_inside_one_branch(tmp_path):
    """A heavy top's branch at --samples 10^7 takes tens of seconds; the sampling and the classification
    read the flag every 2^16 samples: exit 130, nothing written."""
    out = str(tmp_path / "b.h5")
    code, err, waited = signal_and_time(["bifurcation", "--scene", os.path.join(SCENES, "general_top_richter.toml"),
                                         "--samples", "10000000", "--quiet", "--out", out])
    assert code == 130, err
    assert waited < 1.5 * slowdown(LGI), f"the signal was read {waited:.2f} s late"
    assert err == "lgi: bifurcation: interrupted by signal; nothing written\n", err
    assert not os.listdir(tmp_path), os.listdir(tmp_path)


def test_region_single_level_sigint(tmp_path):
    """Single-level `lgi region --l --h` at --grid 2000: the grid (8 million points), its
    triangulation, sort and sweep take far longer than the wait. The grid is polled per ring, the
    sweep every 2^20 simplices; nothing is written."""
    out = str(tmp_path / "r.h5")
    code, err, waited = signal_and_time(["region", "--scene", os.path.join(SCENES, "lagrange_top_oblate.toml"),
                                         "--l", "1", "--h", "1", "--grid", "2000", "--out", out])
    assert code == 130, err
    assert waited < 1.5 * slowdown(LGI), f"the signal was read {waited:.2f} s late"
    assert err == "lgi: region: interrupted by signal before the region was complete; nothing written\n", err
    assert not os.path.exists(out) and not os.path.exists(out + ".partial")


def signal_after_cpu(args, sig=signal.SIGINT, after=1.0):
    """(exit status, stderr, CPU seconds from the signal to the exit) of lgi with `args`, signalled once it
    has used `after` s of CPU time: robust to a loaded machine (scripts/audit_stop_polling.py)."""
    return pacing.signal_after_cpu(LGI, args, sig, after)


def test_bifurcation_appelrot_sigint_inside_one_l(tmp_path):
    """The Kovalevskaya (h, k) diagram at one l over 3000 energies (critical values, ranges of k, level
    sets' tori) takes tens of CPU seconds; it reads the flag before each energy and each level set."""
    out = str(tmp_path / "a.h5")
    code, err, cpu = signal_after_cpu(["bifurcation", "--scene", os.path.join(SCENES, "kovalevskaya.toml"),
                                       "--appelrot", "1", "--appelrot-h", "-1.1:5:3000", "--quiet", "--out", out])
    assert code == 130, err
    assert cpu < 1.0 * pacing.cpu_slowdown(LGI), f"the signal was read after {cpu:.2f} CPU seconds"
    assert err == "lgi: bifurcation: interrupted by signal; nothing written\n", err
    assert not os.listdir(tmp_path), os.listdir(tmp_path)


def test_actions_closed_form_surface_sigterm(tmp_path):
    """The Lagrange closed form on a 2001 x 2001 grid of (l, L3) takes seconds; it reads the flag every row of
    the grid: exit 143, the rows so far in <out>.partial (a whole number of rows of l), no <out>, no CSV."""
    out = str(tmp_path / "s.h5")
    code, err, cpu = signal_after_cpu(["actions", "--scene", os.path.join(SCENES, "lagrange_top_oblate.toml"),
                                       "--h", "2", "--grid", "2000", "--quiet", "--out", out], sig=signal.SIGTERM)
    assert code == 143, err
    assert cpu < 1.0 * pacing.cpu_slowdown(LGI), f"the signal was read after {cpu:.2f} CPU seconds"
    m = re.fullmatch(r"lgi: actions interrupted by signal; the (\d+) rows finished are in (.*)\.partial\n", err)
    assert m and m.group(2) == out, err
    assert not os.path.exists(out) and not os.path.exists(str(tmp_path / "s.csv"))
    with h5py.File(out + ".partial", "r") as f:
        assert text(f["parameters"].attrs["status"]) == f"interrupted by signal: {m.group(1)} rows"
        l = f["tori/actions"][:, 0]
        assert len(l) == int(m.group(1)) < 2001 * 2001
        assert (l[1:] >= l[:-1]).all()  # whole rows of the grid, in its order of l


def test_indicators_gali_sigint_inside_one_long_orbit(tmp_path):
    """--gali at t_end 1e7: after the orbit's indicators the GALI curves' sample times walk the whole step
    grid (seconds); that walk reads the flag too, so a signal in the orbit is not followed by it."""
    out = str(tmp_path / "g.h5")
    code, err, cpu = signal_after_cpu(["indicators", "--scene", os.path.join(SCENES, "general_top_richter.toml"),
                                       "--t-end", "1e7", "--gali", "--quiet", "--out", out])
    assert code == 130, err
    assert cpu < 1.0 * pacing.cpu_slowdown(LGI), f"the signal was read after {cpu:.2f} CPU seconds"
    assert "interrupted by signal" in err and out + ".partial" in err and err.strip().count("\n") == 0, err
    assert not os.path.exists(out) and not os.path.exists(str(tmp_path / "g.csv"))
    with h5py.File(out + ".partial", "r") as f:
        assert text(f["parameters"].attrs["status"]) == "interrupted by signal"


def test_quantum_statistics_sigint_in_the_unfolding(tmp_path):
    """A free body's spectrum at hbar 0.02 (j to 150) is exact and fast; the --statistics that follow
    (each of some 600 classes unfolded by Weyl's law, then /weyl per level) take seconds. They read the
    flag at every Weyl count: exit 130, nothing written."""
    out = str(tmp_path / "q.h5")
    code, err, cpu = signal_after_cpu(["quantum", "--scene", os.path.join(SCENES, "free_body_hlw.toml"), "--hbar",
                                       "0.02", "--jmax", "150", "--statistics", "--quiet", "--out", out])
    assert code == 130, err
    assert cpu < 1.0 * pacing.cpu_slowdown(LGI), f"the signal was read after {cpu:.2f} CPU seconds"
    assert err == "lgi: quantum: interrupted by signal; nothing written\n", err
    assert not os.listdir(tmp_path), os.listdir(tmp_path)
