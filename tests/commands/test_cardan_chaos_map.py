"""lgi chaos-map on a Cardan scene (experiments/CHAOS_MAP.md, "Cardan tops";
docs/cardan.md section 9.4), as a user runs it, on a 3 x 3 (tilt, h) map of
3 orbits per cell to t = 10 (a second or two):
 - the layout: /chaos_map with the varied key's values in `vary` (attribute
   vary_key), h, h_min and the 3 x 3 cell arrays; /orbits; /resume;
 - 1 and 2 threads, and 2 MPI ranks (lgi-mpi, where built), give the same
   datasets bit for bit;
 - --resume from a partial file holding half of the orbits gives the full
   run's datasets bit for bit, and refuses a partial file of another command
   line; SIGTERM in the middle of a run leaves <out>.partial (exit 143), and
   SIGKILL after the first round's checkpoint leaves that checkpoint, from
   which --resume finishes the map bit for bit;
 - the Lagrange top in thin rings: no chaotic orbit with the frame upright
   (integrable), all chaotic with the frame tilted by 0.63 rad, at h = 56;
 - bad input (an unknown key, a bad range, a value that breaks the scene, a
   vector key, --l-range on a Cardan scene, --vary on an SO(3) scene) is
   refused with exit 2 and one line naming the flag."""
import os
import signal
import subprocess
import time

import h5py
import numpy as np
import pytest

from lgi_cli import LGI, lgi, refused

LGI_MPI = os.environ.get("LGI_MPI_EXECUTABLE", "")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
GENERAL_UP = os.path.join(SCENES, "cardan_general_asymmetric_up.toml")
RICHTER = os.path.join(SCENES, "general_top_richter.toml")
MAP = ["chaos-map", "--scene", GENERAL_UP, "--vary", "suspension.tilt=0:1.5707963267948966:3",
       "--h-range", "-0.95:2:3", "--ics", "3", "--t-end", "10", "--dt", "0.01", "--quiet"]


def datasets(path):
    with h5py.File(path, "r") as f:
        return {f"{g}/{k}": f[g][k][()].tobytes() for g in ("chaos_map", "orbits", "resume") for k in f[g]}


@pytest.fixture(scope="module")
def one_thread(tmp_path_factory):
    out = str(tmp_path_factory.mktemp("cardan_map") / "t1.h5")
    lgi(*MAP, "--threads", "1", "--out", out)
    return out


def test_layout(one_thread):
    with h5py.File(one_thread, "r") as f:
        m, o = f["chaos_map"], f["orbits"]
        assert m.attrs["vary_key"] == "suspension.tilt" and m.attrs["measure"] == "microcanonical"
        assert np.allclose(m["vary"][()], [0, np.pi / 4, np.pi / 2]) and np.allclose(m["h"][()], [-0.95, 0.525, 2])
        for k in ("status", "orbits", "chaotic", "chaotic_fraction", "chaotic_fraction_low", "megno_median",
                  "lyapunov_max"):
            assert m[k].shape == (3, 3), k
        status = m["status"][()]
        # h = -0.95 lies below the least potential -|m chi| = -0.943 at every tilt: empty cells.
        assert (status[:, 0] == 1).all() and (status[:, 1:] == 0).all()
        assert np.isnan(m["chaotic_fraction"][()][:, 0]).all()
        assert (m["orbits"][()][:, 1:] == 3).all()
        low, frac, high = (m[k][()][:, 1:] for k in ("chaotic_fraction_low", "chaotic_fraction", "chaotic_fraction_high"))
        assert (low <= frac).all() and (frac <= high).all()
        assert (m["h_min"][()] > -0.9434).all() and (m["h_min"][()] < -0.93).all()
        assert o["megno"].shape == (18,) and o["initial_cardan_angles"].shape == (18, 3)
        assert np.isfinite(o["megno"][()]).all() and (o["megno"][()] > 0).all()
        assert sorted(set(o["cell"][()])) == [1, 2, 4, 5, 7, 8]
        assert f["parameters"].attrs["vary"] == "suspension.tilt=0:1.5707963267948966:3"
        assert f["parameters"].attrs["system"] == "cardan (T^3)"


def test_threads_give_the_same_map(one_thread, tmp_path):
    out = str(tmp_path / "t2.h5")
    lgi(*MAP, "--threads", "2", "--out", out)
    assert datasets(out) == datasets(one_thread)


@pytest.mark.skipif(not LGI_MPI, reason="lgi-mpi is not built (MPI not installed)")
def test_ranks_give_the_same_map(one_thread, tmp_path):
    out = str(tmp_path / "r2.h5")
    r = subprocess.run(["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", "2", LGI_MPI, *MAP,
                        "--threads", "1", "--out", out], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert datasets(out) == datasets(one_thread)
    with h5py.File(out, "r") as f:
        assert f["parameters"].attrs["ranks"] == "2"


def test_lagrange_top_is_regular_upright_and_chaotic_tilted(tmp_path):
    out = str(tmp_path / "lagrange.h5")
    lgi("chaos-map", "--scene", os.path.join(SCENES, "cardan_lagrange_upright.toml"), "--vary",
        "suspension.tilt=0:0.6283185307179586:2", "--h-range", "56:56:1", "--ics", "4", "--t-end", "100", "--dt",
        "0.002", "--threads", "2", "--quiet", "--out", out)
    with h5py.File(out, "r") as f:
        # One h: the cell arrays have one column, stored as 1-D datasets.
        chaotic, megno = f["chaos_map/chaotic"][()].ravel(), f["chaos_map/megno_median"][()].ravel()
    assert list(chaotic) == [0, 4] and megno[0] < 2.5 and megno[1] > 10


def write_partial(full, partial, keep_rows, fingerprint=None):
    """A partial file as an interrupted run leaves it: the first orbits of /orbits and /resume."""
    with h5py.File(full, "r") as f, h5py.File(partial, "w") as p:
        for k in f["orbits"]:
            p[f"orbits/{k}"] = f["orbits"][k][()][:keep_rows]
        p["resume/fingerprint"] = f["resume/fingerprint"][()] if fingerprint is None else fingerprint


def test_resume_goes_on_bit_for_bit(one_thread, tmp_path):
    out = str(tmp_path / "resumed.h5")
    write_partial(one_thread, out + ".partial", 9)
    r = lgi(*[a for a in MAP if a != "--quiet"], "--threads", "2", "--out", out, "--resume")
    assert "(9 orbits resumed)" in r.stdout
    assert datasets(out) == datasets(one_thread)
    assert not os.path.exists(out + ".partial")
    other = str(tmp_path / "other.h5")
    write_partial(one_thread, other + ".partial", 9, fingerprint=np.array([12345], dtype=np.int64))
    line = refused(*MAP, "--out", other, "--resume")
    assert "--resume" in line and "another command line" in line


def test_signal_then_resume(tmp_path):
    """Two orbits of about 0.75 s each (release build, one core; the scalar step of
    integrators/ensemble/cardan_tangent_kernel.hpp) on one thread, stopped after 1 s, inside the second one (or
    the first in a slower build: the wait is not scaled, so the run is cut earlier, never missed)."""
    args = ["chaos-map", "--scene", GENERAL_UP, "--vary", "suspension.tilt=0:0.5:2", "--h-range", "1:1:1",
            "--ics", "1", "--t-end", "12000", "--dt", "0.01", "--threads", "1", "--quiet"]
    out = str(tmp_path / "s.h5")
    p = subprocess.Popen([LGI, *args, "--out", out], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(1.0)
    assert p.poll() is None, "the map ended before it could be interrupted"
    p.send_signal(signal.SIGTERM)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 143, err
    assert os.path.exists(out + ".partial") and not os.path.exists(out)
    with h5py.File(out + ".partial", "r") as f:
        assert (f["chaos_map/status"][()] == 3).any()
    lgi(*args, "--out", out, "--resume")
    full = str(tmp_path / "full.h5")
    lgi(*args, "--out", full)
    assert datasets(out) == datasets(full)


def test_kill_after_a_checkpoint_then_resume(tmp_path):
    """16 orbits on one thread: two rounds, a checkpoint after the first; SIGKILL once it is there."""
    args = ["chaos-map", "--scene", GENERAL_UP, "--vary", "suspension.tilt=0:1:4", "--h-range", "1:1:1",
            "--ics", "4", "--t-end", "3000", "--dt", "0.01", "--threads", "1", "--quiet"]
    out = str(tmp_path / "k.h5")
    p = subprocess.Popen([LGI, *args, "--out", out], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 120
    while not os.path.exists(out + ".partial") and p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.02)
    assert p.poll() is None, "the map ended before its checkpoint was seen"
    time.sleep(0.05)  # the checkpoint is renamed into place whole (hdf5::publish)
    p.kill()
    p.communicate(timeout=60)
    with h5py.File(out + ".partial", "r") as f:
        assert f["parameters"].attrs["status"] == "checkpoint after round 1 of 2"
        assert list(f["chaos_map/status"][()].ravel()) == [0, 0, 3, 3]
    lgi(*args, "--out", out, "--resume")
    full = str(tmp_path / "full.h5")
    lgi(*args, "--out", full)
    assert datasets(out) == datasets(full) and not os.path.exists(out + ".partial")


@pytest.mark.parametrize("flags, words", [
    (["--vary", "suspension.colour=0:1:3"], ["--vary", "suspension.colour", "cannot be varied"]),
    (["--vary", "suspension.tilt=1:0:3"], ["--vary"]),
    (["--vary", "suspension.tilt=0:1"], ["--vary"]),
    (["--vary", "0:1:3"], ["--vary", "KEY=a:b:n"]),
    (["--vary", "suspension.tilt=0:4:3"], ["--vary", "suspension.tilt", "invalid"]),
    (["--vary", "suspension.inner_inertia=0:1:3"], ["--vary", "inner_inertia_1"]),
    (["--vary", "initial.angular_momentum_1=0:1:3"], ["--vary", "initial state"]),
    (["--vary", "suspension.tilt=0:1:3", "--l-range", "0:1:2"], ["--vary", "--l-range"]),
])
def test_bad_input_is_refused(flags, words, tmp_path):
    args = [a for a in MAP if a not in ("--vary", "suspension.tilt=0:1.5707963267948966:3")]
    line = refused(*args, *flags, "--out", str(tmp_path / "x.h5"))
    for w in words:
        assert w in line, line
    assert not os.path.exists(tmp_path / "x.h5")


def test_flags_that_name_the_other_plane(tmp_path):
    line = refused("chaos-map", "--scene", GENERAL_UP, "--l-range", "0:1:2", "--h-range", "0:1:2", "--ics", "2",
                   "--t-end", "1", "--out", str(tmp_path / "x.h5"))
    assert "--l-range" in line and "--vary" in line
    line = refused("chaos-map", "--scene", RICHTER, "--vary", "body.mass=1:2:2", "--h-range", "0:1:2", "--ics", "2",
                   "--t-end", "1", "--out", str(tmp_path / "x.h5"))
    assert "--vary" in line and "SO(3)" in line
