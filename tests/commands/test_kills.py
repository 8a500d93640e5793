"""Killed runs lose nothing (issue 15): simulate, long-time, work-precision and
stress are started for real and sent SIGKILL at moments drawn from a
fixed-seed generator. The file left behind is <out>.partial (OUTPUT.md, "Life
of a file"; RESULTS.md): h5py opens it, every dataset of a table or a time
series has the same length, steps and times are monotone, the records present
are bit for bit the first records of an uninterrupted run, and its
/diagnostics status is "running" (no file claims to be complete). Each run is
sized to last far longer than the kill moment, so a loaded machine only
changes how many records were flushed, never the verdict.
(A killed long-time run goes on with --resume: test_long_time_resume.py.)"""
import os
import random
import signal
import subprocess
import time

import h5py
import numpy as np
import pytest

LGI = os.environ.get("LGI_EXECUTABLE", "build/release/lgi")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
FREE = os.path.join(SCENES, "free_body_hlw.toml")
RNG = random.Random(15)  # fixed seed: the same kill moments on every run

# Each command: the arguments of a run far longer than any kill moment, those of a short uninterrupted
# run whose records are a prefix of it, and the range of kill moments (s after the .partial appears).
SIMULATE = (["simulate", "--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-4", "--save-every", "100", "--t-end", "1e4"],
            ["simulate", "--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-4", "--save-every", "100", "--t-end", "200"],
            (0.2, 1.2))
LONG_TIME = (["long-time", "--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-4", "--samples", "40", "--t-end", "1e5"],
             ["long-time", "--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-4", "--samples", "40", "--t-end", "300"],
             (1.0, 3.2))  # rows are flushed every 2 s: later moments catch some
WP_ROWS = ["--dt", "4e-3,2e-3,1e-3,5e-4", "--tol", "1e-6,1e-8,1e-10", "--t-end", "300", "--repeat", "2"]
WORK_PRECISION = (["work-precision", "--scene", FREE, "--schemes", "rkmk4,cf4,lgvi,dmv,rkmk-dp54,rkmk-gauss4", *WP_ROWS],
                  ["work-precision", "--scene", FREE, "--schemes", "rkmk4,cf4,lgvi,dmv,rkmk-dp54", *WP_ROWS],
                  (2.1, 3.5))  # rows are flushed 2 s after the file's creation at the earliest
STRESS = (["stress", "--quick", "--scenes-dir", SCENES], None, (0.3, 1.2))  # about 2 s of CPU in all
CASES = {"simulate": SIMULATE, "long-time": LONG_TIME, "work-precision": WORK_PRECISION, "stress": STRESS}
MOMENTS = {name: [RNG.uniform(*c[2]) for _ in range(3)] for name, c in CASES.items()}


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def wait_for(path, p, timeout=60.0):
    end = time.monotonic() + timeout
    while not os.path.exists(path):
        assert p.poll() is None, f"the run ended before {path} appeared"
        assert time.monotonic() < end, f"{path} did not appear"
        time.sleep(0.01)


def run_and_kill(args, out, moment, may_finish=False):
    """Starts lgi, sends SIGKILL `moment` s after its .partial file appeared. Returns False if the
    run finished first (allowed only with may_finish)."""
    p = subprocess.Popen([LGI, *args, "--out", out, "--quiet"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_for(out + ".partial", p)
        time.sleep(moment)
        if p.poll() is not None and may_finish:
            assert p.returncode == 0
            return False
        assert p.poll() is None, f"the run ended before the kill at {moment:.2f} s; make it longer"
        p.send_signal(signal.SIGKILL)
    finally:
        if p.poll() is None:
            p.kill()
        p.wait(timeout=60)
    assert p.returncode == -signal.SIGKILL
    return True


def complete_run(args, out):
    r = subprocess.run([LGI, *args, "--out", out, "--quiet"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    return out


def table(f, group):
    """Every dataset of a table group, as arrays; all of one length."""
    cols = {k: f[group][k][()] for k in f[group]}
    lengths = {k: len(v) for k, v in cols.items()}
    assert len(set(lengths.values())) == 1, f"/{group} columns differ in length: {lengths}"
    return cols, next(iter(lengths.values()))


def series(f):
    """Every value of a trajectory file with its step and time; all of one length."""
    out = {}
    for group in ("particles/body", "observables"):
        for name in f[group]:
            if isinstance(f[group][name], h5py.Group) and "value" in f[group][name]:
                out[group + "/" + name] = f[group][name]["value"][()]
    out["step"] = f["particles/body/orientation/step"][()]
    out["time"] = f["particles/body/orientation/time"][()]
    lengths = {k: len(v) for k, v in out.items()}
    assert len(set(lengths.values())) == 1, f"series differ in length: {lengths}"
    return out, len(out["step"])


def assert_incomplete(f, out):
    assert text(f["diagnostics"].attrs["status"]) == "running"
    assert not os.path.exists(out), "a killed run must not leave a file under the final name"


def assert_prefix(cols, ref, n, keys):
    """The first n records of a killed run are those of the uninterrupted one, bit for bit."""
    for k in keys:
        a, b = cols[k][:n], ref[k][:n]
        if a.dtype.kind == "O":
            assert [text(x) for x in a] == [text(x) for x in b], k
        else:
            assert a.tobytes() == b.tobytes(), k


@pytest.fixture(scope="module")
def references(tmp_path_factory):
    """Uninterrupted runs, made once: short ones for simulate and long-time (their records are a
    prefix of the long runs'), the same runs for work-precision and stress."""
    d = tmp_path_factory.mktemp("uninterrupted")
    out = {}
    for name, (args, short, _) in CASES.items():
        out[name] = complete_run(short or args, str(d / f"{name}.h5"))
    return out


def killed(tmp_path, references, name, k, read):
    """Kills a run of command `name` at its k-th moment; returns read() of its .partial file and of
    the uninterrupted run."""
    out = str(tmp_path / "kill.h5")
    run_and_kill(CASES[name][0], out, MOMENTS[name][k])
    with h5py.File(out + ".partial", "r") as f, h5py.File(references[name], "r") as g:
        assert_incomplete(f, out)
        return read(f), read(g)


@pytest.mark.parametrize("k", range(3))
def test_killed_simulate(tmp_path, references, k):
    (cols, n), (ref, m) = killed(tmp_path, references, "simulate", k, series)
    assert (np.diff(cols["step"]) > 0).all() and (np.diff(cols["time"]) >= 0).all()
    assert_prefix(cols, ref, min(n, m - 1), ref.keys())


@pytest.mark.parametrize("k", range(3))
def test_killed_long_time(tmp_path, references, k):
    (cols, n), (ref, m) = killed(tmp_path, references, "long-time", k, lambda f: table(f, "series"))
    assert (np.diff(cols["step"]) > 0).all() and (np.diff(cols["time"]) > 0).all()
    assert_prefix(cols, ref, min(n, m - 1), ref.keys())
    assert os.path.exists(str(tmp_path / "kill.csv.partial"))


@pytest.mark.parametrize("k", range(3))
def test_killed_work_precision(tmp_path, references, k):
    # the same rows but the last scheme's
    (cols, n), (ref, m) = killed(tmp_path, references, "work-precision", k, lambda f: table(f, "results"))
    # CPU times and the batch sizes judged from them vary from run to run.
    deterministic = [c for c in ref if not c.startswith("cpu_seconds") and c != "runs_per_repeat"]
    assert_prefix(cols, ref, min(n, m), deterministic)


@pytest.mark.parametrize("k", range(3))
def test_killed_stress(tmp_path, references, k):
    out = str(tmp_path / "kill.h5")
    if not run_and_kill(STRESS[0], out, MOMENTS["stress"][k], may_finish=True):
        # A fast machine: the quick suite (~2 s of CPU) ended before the kill; then it is complete.
        with h5py.File(out, "r") as f:
            assert text(f["diagnostics"].attrs["status"]) == "ok" and not os.path.exists(out + ".partial")
        return
    with h5py.File(out + ".partial", "r") as f, h5py.File(references["stress"], "r") as g:
        assert_incomplete(f, out)
        cols, n = table(f, "results")
        ref, m = table(g, "results")
        assert n < m
        assert_prefix(cols, ref, n, ["case", "variant", "scheme"])
        # Outcomes and errors too, except for runs stopped by the CPU budget (timing-dependent).
        for i in range(n):
            if "budget" not in text(cols["reason"][i]) + text(ref["reason"][i]):
                assert text(cols["outcome"][i]) == text(ref["outcome"][i]), i
                assert cols["error"][i:i + 1].tobytes() == ref["error"][i:i + 1].tobytes(), i
