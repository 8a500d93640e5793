"""Injected faults (issue 15): a full disk (a file-size limit, RLIMIT_FSIZE,
with SIGXFSZ ignored so that the write fails with EFBIG), an output directory
that cannot be written, an output path that exists, a run that blows up
to non-finite values, and a sweep's resume file removed while it runs. Each ends with one line on stderr naming the file or
the time, the exit status of the README (1: the run failed; 2: the output was
refused before anything was written), a previous output left as it was, and
no file that claims to be complete."""
import os
import resource
import signal
import subprocess
import time

import h5py
import numpy as np
import pytest
from pacing import LONG_SWEEP, slowdown, wait_part_way

LGI = os.environ.get("LGI_EXECUTABLE", "build/release/lgi")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
FREE = os.path.join(SCENES, "free_body_hlw.toml")
LIMIT = 256 * 1024  # bytes: above a new file's metadata, far below a finished run's file
MIDRUN_LIMIT = 16 * 1024  # bytes: a new HDF5 file's first blocks, below each MIDRUN output


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def lgi(*args, limit=None):
    def preexec():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # EFBIG instead of death by SIGXFSZ
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    return subprocess.run([LGI, *args], capture_output=True, text=True, timeout=300,
                          preexec_fn=preexec if limit else None)


def one_line(err):
    assert err.endswith("\n") and err.count("\n") == 1, repr(err)
    return err


def not_complete(path):
    """A file left by a failed run: absent, or not openable, or with a status other than "ok"."""
    if not os.path.exists(path):
        return True
    try:
        with h5py.File(path, "r") as f:
            return text(f["diagnostics"].attrs.get("status", "")) != "ok"
    except OSError:
        return True


# Runs that would write tens of MB: (arguments, the HDF5 file, the CSV twin if any).
BIG = {
    "simulate": ["simulate", "--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-3", "--t-end", "200", "--save-every", "1"],
    "long-time": ["long-time", "--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-3", "--t-end", "100", "--samples",
                  "50000"],
}
SMALL = {
    "simulate": ["simulate", "--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-2", "--t-end", "1"],
    "long-time": ["long-time", "--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-2", "--t-end", "1"],
}


@pytest.mark.parametrize("command", list(BIG))
def test_disk_full_fails_cleanly_and_keeps_the_previous_output(tmp_path, command):
    out = str(tmp_path / "o.h5")
    r = lgi(*SMALL[command], "--out", out, "--quiet")
    assert r.returncode == 0, r.stderr
    before = open(out, "rb").read()
    r = lgi(*BIG[command], "--out", out, "--force", "--quiet", limit=LIMIT)
    assert r.returncode == 1, r.stderr
    line = one_line(r.stderr)
    assert ("o.h5" in line or "o.csv" in line) and "cannot write" in line, line
    assert open(out, "rb").read() == before, "the previous output was changed"
    assert not_complete(out + ".partial")
    if command == "long-time":
        assert open(str(tmp_path / "o.csv"), "rb").read().count(b"\n") > 1  # the previous CSV too


def test_disk_full_at_the_start_refuses_without_a_trace(tmp_path):
    # So small that not even the metadata fits: the file cannot be created.
    out = str(tmp_path / "o.h5")
    r = lgi(*SMALL["simulate"], "--out", out, limit=1024)
    assert r.returncode in (1, 2), r.stderr
    assert "o.h5" in one_line(r.stderr)
    assert not os.path.exists(out) and not_complete(out + ".partial")


@pytest.mark.parametrize("where", ["missing", "file", "read-only"])
def test_unwritable_output_directory_is_refused(tmp_path, where):
    if where == "missing":
        d = str(tmp_path / "no" / "such")
    elif where == "file":
        d = str(tmp_path / "plain")
        open(d, "w").close()
    else:
        d = str(tmp_path / "ro")
        os.mkdir(d, 0o555)
        if os.access(d, os.W_OK):  # root ignores the mode: sysfs refuses even root
            d = "/sys"
            try:
                open(os.path.join(d, "lgi_probe.h5"), "w").close()
                os.unlink(os.path.join(d, "lgi_probe.h5"))
                pytest.skip("no directory this user cannot write")
            except OSError:
                pass
    out = os.path.join(d, "o.h5")
    for args in (SMALL["simulate"], SMALL["long-time"]):
        r = lgi(*args, "--out", out)
        assert r.returncode == 2, r.stderr
        assert "o.h5" in one_line(r.stderr)
        assert not os.path.exists(out) and not os.path.exists(out + ".partial")


@pytest.mark.parametrize("command", list(SMALL))
def test_existing_output_is_refused_unless_force(tmp_path, command):
    out = str(tmp_path / "o.h5")
    r = lgi(*SMALL[command], "--out", out)
    assert r.returncode == 0, r.stderr
    before = open(out, "rb").read()
    r = lgi(*SMALL[command], "--out", out)
    assert r.returncode == 2 and "--force" in one_line(r.stderr) and "o.h5" in r.stderr
    assert open(out, "rb").read() == before and not os.path.exists(out + ".partial")
    r = lgi(*SMALL[command], "--out", out, "--force")
    assert r.returncode == 0, r.stderr
    with h5py.File(out, "r") as f:
        assert text(f["diagnostics"].attrs["status"]) == "ok"


def test_blow_up_stops_with_the_time_and_keeps_the_good_steps(tmp_path):
    # Explicit rkmk4 at dt = 0.01 is unstable for the damping c/J = 1000 s^-1 of this scene.
    out = str(tmp_path / "b.h5")
    r = lgi("simulate", "--scene", os.path.join(SCENES, "stiff_damped_spring.toml"), "--scheme", "rkmk4",
            "--dt", "0.01", "--t-end", "5", "--out", out)
    assert r.returncode == 1, r.stderr
    line = one_line(r.stderr)
    assert "non-finite" in line and "state" in line and "t = " in line and "b.h5.partial" in line, line
    assert not os.path.exists(out)
    with h5py.File(out + ".partial", "r") as f:
        status = text(f["diagnostics"].attrs["status"])
        assert status.startswith("state became non-finite")
        t = f["particles/body/orientation/time"][()]
        steps = int(f["diagnostics"].attrs["steps"])
        assert len(t) == steps and t[0] == 0.0  # every good step, not the one that blew up
        for name in ("orientation", "angular_momentum_body", "angular_velocity_body"):
            assert np.isfinite(f["particles/body"][name]["value"][()]).all(), name
        # The failing step is the next one, at the time the message names.
        assert f"t = {float(status.split('t = ')[1]):.6g}" == f"t = {t[-1] + 0.01:.6g}"


def test_resume_file_removed_mid_run(tmp_path):
    # lgi long-time has no --resume; lgi sweep has. Its resumed run keeps the .partial open: a
    # file removed under it lives on until it is closed (POSIX), so the sweep completes as it would have.
    spec = tmp_path / "spec.toml"
    spec.write_text(LONG_SWEEP.replace("SCENES", SCENES))
    out = str(tmp_path / "s.h5")
    args = [LGI, "sweep", "--spec", str(spec), "--out", out, "--threads", "1", "--quiet"]
    p = subprocess.Popen(args)
    try:
        wait_part_way(p, out + ".partial")
    finally:
        p.kill()
        p.wait()
    with h5py.File(out + ".partial", "r") as f:
        assert (f["sweep/status"][()] < 0).any()
    # Removed only once the resumed run has written to it: removed before its open has returned,
    # the run would find no file (HDF5 looks the name up again after opening it).
    killed_write = os.stat(out + ".partial").st_mtime_ns
    p = subprocess.Popen([*args, "--resume"], stderr=subprocess.PIPE, text=True)
    end = time.monotonic() + 300
    while os.stat(out + ".partial").st_mtime_ns == killed_write and p.poll() is None and time.monotonic() < end:
        time.sleep(0.005)
    if p.poll() is not None:
        pytest.skip("the resumed sweep ended before its file could be removed")
    os.unlink(out + ".partial")
    _, err = p.communicate(timeout=300 * slowdown(LGI))
    assert p.returncode == 0, err
    with h5py.File(out, "r") as f:
        assert (f["sweep/status"][()] >= 0).all() and len(f["sweep/status"]) == 2000
    assert not os.path.exists(out + ".partial")


STATE_SPACE_MISMATCH = [
    ("simulate", "cardan_euler_tilted.toml", "--scheme", "rkmk4", "runs on SO(3) x R^3 scenes only"),
    ("simulate", "free_body_hlw.toml", "--scheme", "cardan-dp54", "runs on Cardan scenes only"),
    ("work-precision", "heavy_top_hlw.toml", "--schemes", "cardan-dp54", "runs on Cardan scenes only"),
]


@pytest.mark.parametrize("command,scene,flag,scheme,words", STATE_SPACE_MISMATCH)
def test_scheme_of_the_other_state_space_is_refused_naming_both(tmp_path, command, scene, flag, scheme, words):
    """A scheme that exists but integrates the other state space (issue 48): exit 2, one line
    naming the flag, the scheme, both state spaces, and no output file."""
    out = tmp_path / "x.h5"
    extra = ["--dt", "0.01"] if command == "work-precision" else []
    r = lgi(command, "--scene", os.path.join(SCENES, scene), flag, scheme, *extra, "--out", str(out))
    assert r.returncode == 2, r.stderr
    one_line(r.stderr)
    assert words in r.stderr and flag in r.stderr and scheme in r.stderr
    assert "SO(3) x R^3" in r.stderr and "T^3 x R^3" in r.stderr
    assert not out.exists() and not (tmp_path / "x.h5.partial").exists()


KOVALEVSKAYA = os.path.join(SCENES, "kovalevskaya.toml")
NO_WORK = [
    ("simulate", "--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-300", "--t-end", "1"),
    ("simulate", "--scene", FREE, "--scheme", "rkmk4", "--dt", "5e-324", "--t-end", "1"),
    ("simulate", "--scene", FREE, "--scheme", "lgvi", "--dt", "1e-17", "--t-end", "1e3"),
    ("long-time", "--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-300", "--t-end", "1"),
    ("chaos-map", "--scene", KOVALEVSKAYA, "--l-range", "1:1:1", "--h-range", "2:2:1", "--ics", "2",
     "--t-end", "1", "--dt", "1e-300"),
]


@pytest.mark.parametrize("args", NO_WORK, ids=[f"{a[0]}-{a[-3] if a[0] != 'chaos-map' else 'dt'}" for a in NO_WORK])
def test_a_step_that_cannot_advance_time_is_refused(tmp_path, args):
    """Issue 50: a step count past 2^53, or a step below the resolution of t (t + dt == t), is
    refused up front with exit 2 naming --dt: never a success with 0 steps, never a loop that
    cannot end."""
    out = tmp_path / "x.h5"
    started = time.monotonic()
    r = lgi(*args, "--out", str(out))
    assert time.monotonic() - started < 10
    assert r.returncode == 2, (r.returncode, r.stderr)
    one_line(r.stderr)
    assert "--dt" in r.stderr and ("2^53" in r.stderr or "resolution of t" in r.stderr), r.stderr
    assert not out.exists() and not (tmp_path / "x.h5.partial").exists()


# A full disk part-way through the commands that write their table at the end or as they go
# (issue 50, item 9): one exit-status rule, 1 for a failed write once the output exists, with
# the .partial kept and named; never 2, and never the HDF5 library's error stack.
MIDRUN = {
    "poincare": ["poincare", "--scene", KOVALEVSKAYA, "--l", "1", "--h", "2", "--ics", "2", "--t-end", "50",
                 "--threads", "1"],
    "region": ["region", "--scene", os.path.join(SCENES, "lagrange_top_oblate.toml"), "--cells", "--l-range",
               "0:3:9", "--h-range", "-1.2:3:9", "--grid", "40"],
    "bifurcation": ["bifurcation", "--scene", os.path.join(SCENES, "heavy_top_hlw.toml")],
    # (lgi actions writes through the same write_table_file as bifurcation; its run takes too long here.)
    "singularity": ["singularity", "--scenes-dir", SCENES, "--quick"],
}


@pytest.mark.parametrize("command", list(MIDRUN))
def test_disk_full_mid_run_exits_1_and_keeps_the_partial(tmp_path, command):
    out = str(tmp_path / "o.h5")
    r = lgi(*MIDRUN[command], "--out", out, "--quiet", limit=MIDRUN_LIMIT)
    assert r.returncode == 1, r.stderr
    line = one_line(r.stderr)
    assert "o.h5" in line and ".partial" in line and "kept" in line, line
    assert not os.path.exists(out)
    assert any(n.endswith(".partial") for n in os.listdir(tmp_path)), os.listdir(tmp_path)
