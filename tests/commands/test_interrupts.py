"""Ctrl-C (SIGINT) and SIGTERM in the long commands: every loop reads the flag
as RunConfig::stop and ends after its current step with its statistics (no
observer throws); the command closes its file with status "interrupted by
signal", keeps what it computed in <out>.partial, says so in one line on
stderr and exits with 128 + the signal: 130 after SIGINT, 143 after SIGTERM
(README "Using lgi"). lgi sweep's case is in test_sweep.py."""
import os
import signal
import subprocess
import time

import h5py
import numpy as np
import pytest
import pacing
from pacing import slowdown

LGI = os.environ.get("LGI_EXECUTABLE", "build/release/lgi")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
SCENE = os.path.join(SCENES, "free_body_hlw.toml")
EXIT = {signal.SIGINT: 130, signal.SIGTERM: 143}

# Runs far longer than the moment of the signal.
COMMANDS = {
    "simulate": ["simulate", "--scene", SCENE, "--scheme", "rkmk4", "--dt", "1e-4", "--t-end", "1e4",
                 "--save-every", "1000"],
    "long-time": ["long-time", "--scene", SCENE, "--scheme", "rkmk4", "--dt", "1e-4", "--t-end", "1e5"],
    "work-precision": ["work-precision", "--scene", SCENE, "--schemes", "rkmk4,cf4,lgvi", "--dt", "1e-3,1e-5",
                       "--t-end", "1000", "--repeat", "3"],
    "stress": ["stress", "--scenes-dir", SCENES],
}


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def interrupt(args, after=1.0, sig=signal.SIGINT):
    p = subprocess.Popen([LGI, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(after * slowdown(LGI))  # the same moment of the run in a slower (sanitizer) build
    assert p.poll() is None, "the command ended before it could be interrupted"
    p.send_signal(sig)
    _, err = p.communicate(timeout=120)
    return p.returncode, err


def assert_interrupted(partial):
    with h5py.File(partial, "r") as f:
        assert text(f["diagnostics"].attrs["status"]).startswith("interrupted")


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
@pytest.mark.parametrize("command", list(COMMANDS))
def test_signal_ends_the_run_cleanly(tmp_path, command, sig):
    out = str(tmp_path / "o.h5")
    # Late enough for a first row (work-precision, stress) even on a loaded machine.
    after = {"stress": 2.0, "work-precision": 3.0}.get(command, 1.5)
    code, err = interrupt([*COMMANDS[command], "--out", out], after=after, sig=sig)
    assert code == EXIT[sig], err
    assert "interrupted by signal" in err and err.strip().count("\n") == 0, err
    assert not os.path.exists(out), "an interrupted run must not publish its file"
    assert_interrupted(out + ".partial")
    with h5py.File(out + ".partial", "r") as f:
        if command == "simulate":
            steps = f["particles/body/orientation/step"][()]
            assert int(f["diagnostics"].attrs["steps"]) > 0 and steps[-1] == f["diagnostics"].attrs["steps"]
            assert np.isfinite(f["particles/body/angular_momentum_body/value"][()]).all()
        elif command == "long-time":
            assert len(f["series/step"]) > 1  # the rows so far and one for the step it stopped at
            assert f["series/step"][-1] == f["diagnostics"].attrs["steps"]
        elif command == "work-precision":
            assert len(f["results/scheme"]) == f["diagnostics"].attrs["rows"] >= 1
        else:
            assert len(f["results/scheme"]) == f["diagnostics"].attrs["rows"] > 0
    if command != "simulate":
        assert os.path.exists(str(tmp_path / "o.csv.partial"))


def test_simulate_with_a_baseline_ends_cleanly(tmp_path):
    # The baselines' loop honours RunConfig::stop as the Lie-group loop does.
    out = str(tmp_path / "b.h5")
    code, err = interrupt(["simulate", "--scene", SCENE, "--scheme", "quat/rk4", "--dt", "1e-4", "--t-end", "1e6",
                           "--save-every", "100000", "--out", out])
    assert code == 130, err
    assert "interrupted by signal" in err
    assert_interrupted(out + ".partial")
    with h5py.File(out + ".partial", "r") as f:
        assert int(f["diagnostics"].attrs["steps"]) > 0


def test_singularity_stops_after_the_run_in_progress(tmp_path):
    out = str(tmp_path / "s.h5")
    code, err = interrupt(["singularity", "--scenes-dir", SCENES, "--dt", "1e-4", "--quiet", "--out", out], after=2.5,
                          sig=signal.SIGTERM)
    assert code == 143, err
    assert "interrupted by signal" in err and err.strip().count("\n") == 0, err
    assert not os.path.exists(out) and not os.path.exists(str(tmp_path / "s.csv"))
    with h5py.File(out + ".partial", "r") as f:
        assert text(f["parameters"].attrs["status"]) == "interrupted by signal"
        assert len(f["results/method"]) > 0


@pytest.mark.parametrize("command", ["chaos-map", "indicators"])
def test_signal_inside_one_long_orbit(tmp_path, command):
    # One orbit far longer than the wait: the tangent-flow loop itself must read the flag
    # (integrators/core/tangent_flow.hpp, every 256 steps), not only the loop over orbits.
    richter = os.path.join(SCENES, "general_top_richter.toml")
    out = str(tmp_path / "o.h5")
    args = {"chaos-map": ["chaos-map", "--scene", richter, "--l-range", "2.2:2.2:1", "--h-range", "2:2:1", "--ics",
                          "2", "--t-end", "1e7", "--threads", "1", "--out", out],
            "indicators": ["indicators", "--scene", richter, "--t-end", "1e7", "--out", out]}[command]
    start = time.monotonic()
    p = subprocess.Popen([LGI, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(1.5 * slowdown(LGI))
    assert p.poll() is None, "the command ended before it could be interrupted"
    p.send_signal(signal.SIGINT)
    sent = time.monotonic()
    _, err = p.communicate(timeout=60)
    assert time.monotonic() - sent < 5.0 * slowdown(LGI), "the signal was not read within the orbit"
    assert time.monotonic() - start < 60
    if command == "chaos-map":
        assert p.returncode == 130, err
        assert os.path.exists(out + ".partial") and not os.path.exists(out)
    else:  # lgi indicators: the same guard as the other commands (issue 50)
        assert p.returncode == 130, err
        assert "interrupted by signal" in err and out + ".partial" in err and err.strip().count("\n") == 0, err
        assert not os.path.exists(out)
        with h5py.File(out + ".partial", "r") as f:
            assert text(f["parameters"].attrs["status"]) == "interrupted by signal"
            assert f["indicators/t_end"][0] == 0 and np.isnan(f["indicators/lyapunov"][0])  # cut short


def test_indicators_sigterm_keeps_the_partial(tmp_path):
    out = str(tmp_path / "i.h5")
    richter = os.path.join(SCENES, "general_top_richter.toml")
    code, err = interrupt(["indicators", "--scene", richter, "--t-end", "1e7", "--out", out], sig=signal.SIGTERM)
    assert code == 143, err
    assert "interrupted by signal" in err and out + ".partial" in err, err
    assert os.path.exists(out + ".partial") and not os.path.exists(out)


CARDAN = os.path.join(SCENES, "cardan_general_asymmetric_up.toml")
CARDAN_MAP = ["chaos-map", "--scene", CARDAN, "--vary", "suspension.tilt=0:0.5:2", "--h-range", "1:1:1", "--ics", "4",
              "--dt", "0.01", "--threads", "1"]


def test_cardan_chaos_map_sigint_inside_the_lanes(tmp_path):
    """A Cardan map (issue 50): its orbits run 4 at a time in SIMD lanes far longer than the wait; SIGINT is
    read by the lanes' loop within a second (every 256 steps), exit 130, <out>.partial kept, one line."""
    out = str(tmp_path / "c.h5")
    p = subprocess.Popen([LGI, *CARDAN_MAP, "--t-end", "1e7", "--out", out], stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, text=True)
    time.sleep(1.5 * slowdown(LGI))
    assert p.poll() is None, "the command ended before it could be interrupted"
    p.send_signal(signal.SIGINT)
    sent = time.monotonic()
    _, err = p.communicate(timeout=60)
    assert time.monotonic() - sent < 5.0 * slowdown(LGI), "the signal was not read within the orbits"
    assert p.returncode == 130, err
    assert "interrupted by signal" in err and out + ".partial" in err and err.strip().count("\n") == 0, err
    assert os.path.exists(out + ".partial") and not os.path.exists(out)
    with h5py.File(out + ".partial", "r") as f:
        assert text(f["parameters"].attrs["status"]) == "interrupted by signal"
        assert (f["chaos_map/status"][()] == 3).all()  # no orbit finished: every cell not run


def test_cardan_chaos_map_progress(tmp_path):
    """The progress line on stderr as the heavy-top form prints it: a line at the end (and every 10 s) into a
    pipe; in place (carriage return, erase line) on a terminal; none with --quiet."""
    import pty
    r = subprocess.run([LGI, *CARDAN_MAP, "--t-end", "20", "--out", str(tmp_path / "p.h5")], capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "chaos-map: 8/8 orbits" in r.stderr and "\r" not in r.stderr, r.stderr
    leader, follower = pty.openpty()
    p = subprocess.Popen([LGI, *CARDAN_MAP, "--t-end", "20", "--out", str(tmp_path / "t.h5")],
                         stdout=subprocess.DEVNULL, stderr=follower)
    os.close(follower)
    seen = b""
    while True:
        try:
            chunk = os.read(leader, 4096)
        except OSError:  # the terminal closed with the process
            break
        if not chunk:
            break
        seen += chunk
    p.wait(timeout=120)
    os.close(leader)
    assert p.returncode == 0
    assert b"\r\033[Kchaos-map: 8/8 orbits" in seen, seen
    q = subprocess.run([LGI, *CARDAN_MAP, "--t-end", "20", "--quiet", "--out", str(tmp_path / "q.h5")],
                       capture_output=True, text=True, timeout=120)
    assert q.returncode == 0 and q.stderr == "", q.stderr


def signal_within_a_second(args, sig=signal.SIGINT, after=1.5):
    """Sends `sig` `after` s into a run far longer than that and returns (exit status, stderr); fails unless
    the run ends within a few seconds of the signal (every loop reads the flag at least once a second)."""
    code, err, waited = pacing.signal_and_time(LGI, args, sig, after)
    assert waited < 3.0 * slowdown(LGI), "the signal was not read within the work"
    return code, err


def test_periodic_sigint_inside_a_long_start_keeps_the_finished_ones(tmp_path):
    """lgi periodic (issue 50): the shooting reads the flag every step, so SIGINT inside one long start (a
    Newton solve whose shots cover 300 periods) ends the run at once; the start it cut short is dropped and
    the families of the starts before it go to <out>.partial, exit 130."""
    richter = os.path.join(SCENES, "general_top_richter.toml")
    first = str(tmp_path / "first.h5")
    r = subprocess.run([LGI, "periodic", "--scene", richter, "--l", "3", "--from-equilibria", "--steps", "0",
                        "--out", first, "--quiet"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    with h5py.File(first, "r") as f:
        x = np.concatenate([f["periodic/angular_momentum"][0], f["periodic/gamma"][0]])
        period = float(f["periodic/period"][0])
    seeds = str(tmp_path / "seeds.txt")
    with open(seeds, "w") as s:  # a quick start, then the same orbit taken 300 times round: a long one
        s.write(" ".join(repr(float(v)) for v in x) + f" {period!r}\n")
        s.write(" ".join(repr(float(v)) for v in x) + f" {300 * period!r}\n")
    out = str(tmp_path / "p.h5")
    code, err = signal_within_a_second(["periodic", "--scene", richter, "--l", "3", "--seed-file", seeds, "--steps",
                                        "0", "--out", out])
    assert code == 130, err
    assert "interrupted by signal" in err and out + ".partial" in err and err.strip().count("\n") == 0, err
    assert not os.path.exists(out)
    with h5py.File(out + ".partial", "r") as f:
        assert text(f["parameters"].attrs["status"]).startswith("interrupted by signal: the families of 1 of 2 starts")
        assert len(f["periodic/family"]) >= 1 and (f["periodic/family"][()] == 0).all()
        assert np.all(f["periodic/residual"][()] <= 1e-10)


def test_actions_sigterm_inside_a_long_torus(tmp_path):
    """lgi actions (issue 50): a numerical torus at --dt 1e-5 runs far longer than the wait; its recorders
    read the flag every step, the cut torus is not kept and the closed-form row goes to <out>.partial."""
    out = str(tmp_path / "a.h5")
    code, err = signal_within_a_second(["actions", "--scene", os.path.join(SCENES, "lagrange_top_cigar.toml"),
                                        "--dt", "1e-5", "--out", out], sig=signal.SIGTERM)
    assert code == 143, err
    assert "interrupted by signal" in err and out + ".partial" in err and err.strip().count("\n") == 0, err
    assert not os.path.exists(out)
    with h5py.File(out + ".partial", "r") as f:
        assert text(f["parameters"].attrs["status"]).startswith("interrupted by signal")
        assert list(f["tori/method"][()]) == [0]  # the Lagrange closed form; no numerical row


def test_cardan_poincare_sigint_inside_one_long_orbit(tmp_path):
    """lgi poincare on a Cardan top (issue 50): the orbit's loop reads the flag every step, so one orbit far
    longer than the wait ends at once; it is not kept (0 of 1 orbits in <out>.partial), exit 130."""
    out = str(tmp_path / "c.h5")
    code, err = signal_within_a_second(["poincare", "--scene", CARDAN, "--l", "1.68", "--h", "2.2", "--ics", "1",
                                        "--t-end", "1e7", "--dt", "0.01", "--megno", "--threads", "1", "--out", out])
    assert code == 130, err
    assert "interrupted by signal" in err and out + ".partial" in err, err
    assert not os.path.exists(out)
    with h5py.File(out + ".partial", "r") as f:
        assert text(f["parameters"].attrs["status"]) == "interrupted by signal: 0 of 1 orbits"
        assert len(f["sweep/index"]) == 0
