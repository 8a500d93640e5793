"""Ctrl-C (SIGINT) in the long commands: every loop reads the flag as
RunConfig::stop and ends after its current step with its statistics (no
observer throws), the command keeps what it computed and exits with status 1
(README "Using lgi"). lgi sweep's case is in test_sweep.py."""
import os
import signal
import subprocess
import time

import h5py

LGI = os.environ.get("LGI_EXECUTABLE", "build/release/lgi")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENE = os.path.join(ROOT, "experiments", "scenes", "free_body_hlw.toml")


def interrupt(args, after=1.0):
    p = subprocess.Popen([LGI, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(after)
    assert p.poll() is None, "the command ended before it could be interrupted"
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=60)
    return p.returncode, err


def test_simulate_with_a_baseline_ends_cleanly(tmp_path):
    # The baselines' loop honours RunConfig::stop as the Lie-group loop does.
    out = str(tmp_path / "b.h5")
    code, err = interrupt(["simulate", "--scene", SCENE, "--scheme", "quat/rk4", "--dt", "1e-4", "--t-end", "1e6",
                           "--save-every", "100000", "--out", out])
    assert code == 1, err
    assert "interrupted by signal" in err
    with h5py.File(out + ".partial", "r") as f:
        status = f["diagnostics"].attrs["status"]
        assert (status.decode() if isinstance(status, bytes) else status).startswith("interrupted")
        assert int(f["diagnostics"].attrs["steps"]) > 0


def test_stress_stops_between_runs(tmp_path):
    out = str(tmp_path / "s.h5")
    code, err = interrupt(["stress", "--out", out], after=2.0)
    assert code == 1, err
    assert "interrupted by signal" in err and err.strip().count("\n") == 0
    with h5py.File(out + ".partial", "r") as f:
        assert len(f["results/scheme"]) > 0
