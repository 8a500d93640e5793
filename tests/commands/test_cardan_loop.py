"""Cardan scenes (state on T^3 x R^3) through the one time loop (docs/cardan.md
section 7):
 - `lgi simulate --output-dt D` samples at t0, t0 + D, ... and t_end, for a
   fixed-step scheme and for the adaptive cardan-dp54 (steps landed on the
   output times); the samples at those times are the states of the run
   without --output-dt at the same steps (fixed step), bit for bit;
 - `lgi long-time` on a Cardan scene writes the energy and p1 errors
   (--resume after SIGKILL: tests/commands/test_long_time_resume.py);
 - a scheme of the other state space is refused with exit 2 and one line
   naming both state spaces, in every command that takes a scheme."""
import os
import subprocess

import h5py
import numpy as np

LGI = os.environ.get("LGI_EXECUTABLE", "build/release/lgi")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
TILTED = os.path.join(SCENES, "cardan_euler_tilted.toml")
HLW = os.path.join(SCENES, "heavy_top_hlw.toml")


def lgi(*args):
    return subprocess.run([LGI, *args], capture_output=True, text=True, timeout=300)


def sample_times(path):
    with h5py.File(path, "r") as f:
        return f["observables/cardan_angle_1/time"][()], f["observables/cardan_angle_1/value"][()]


def test_output_dt_on_a_cardan_scene(tmp_path):
    expected = np.round(np.arange(0, 101) * 0.01, 12)
    for scheme, extra in [("cardan-rk4", ["--dt", "1e-3"]), ("cardan-dp54", ["--tol", "1e-9"])]:
        out = str(tmp_path / f"{scheme}.h5")
        r = lgi("simulate", "--scene", TILTED, "--scheme", scheme, *extra, "--t-end", "1", "--output-dt", "0.01",
                "--out", out)
        assert r.returncode == 0, r.stderr
        t, _ = sample_times(out)
        assert len(t) == len(expected)
        assert np.max(np.abs(t - expected)) <= 1e-12
        with h5py.File(out, "r") as f:
            assert f["parameters"].attrs["output_dt"] == 0.01
    # A fixed step: the samples are the run's own states at the multiples of 10 steps.
    every = str(tmp_path / "every.h5")
    r = lgi("simulate", "--scene", TILTED, "--scheme", "cardan-rk4", "--dt", "1e-3", "--t-end", "1",
            "--save-every", "10", "--out", every)
    assert r.returncode == 0, r.stderr
    _, q_every = sample_times(every)
    _, q_output = sample_times(str(tmp_path / "cardan-rk4.h5"))
    assert np.array_equal(q_every, q_output)


def test_output_dt_not_a_multiple_of_the_fixed_step(tmp_path):
    r = lgi("simulate", "--scene", TILTED, "--scheme", "cardan-rk4", "--dt", "1e-2", "--t-end", "1",
            "--output-dt", "0.015", "--out", str(tmp_path / "x.h5"))
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1 and "--output-dt" in r.stderr


def test_long_time_on_a_cardan_scene(tmp_path):
    out = str(tmp_path / "lt.h5")
    r = lgi("long-time", "--scene", TILTED, "--scheme", "cardan-midpoint", "--dt", "1e-2", "--t-end", "20",
            "--out", out)
    assert r.returncode == 0, r.stderr
    assert "energy_error_max=" in r.stdout and "cardan_momentum_1_error_max=" in r.stdout
    with h5py.File(out, "r") as f:
        series = f["series"]
        assert series["step"][-1] == 2000
        assert np.max(series["energy_error_window_max"][()]) < 1e-3
        # cardan_euler_tilted: vertical outer axis, so p1 is an integral; the midpoint rule keeps it.
        assert np.max(series["cardan_momentum_1_error_window_max"][()]) < 1e-12


def test_a_scheme_of_the_other_state_space_is_refused(tmp_path):
    out = str(tmp_path / "x.h5")
    for args in (["simulate", "--scene", TILTED, "--scheme", "rkmk4"],
                 ["simulate", "--scene", HLW, "--scheme", "cardan-rk4"],
                 ["long-time", "--scene", TILTED, "--scheme", "rkmk4"],
                 ["long-time", "--scene", HLW, "--scheme", "cardan-dp54"],
                 ["work-precision", "--scene", HLW, "--schemes", "cardan-dp54"]):
        r = lgi(*args, "--out", out)
        assert r.returncode == 2, (args, r.stderr)
        assert len(r.stderr.strip().splitlines()) == 1, r.stderr
        assert "SO(3) x R^3" in r.stderr and "T^3 x R^3" in r.stderr, r.stderr


def write_cardan_spec(tmp_path, extra=""):
    spec = tmp_path / "cardan_tilt.toml"
    spec.write_text(f'''name = "Cardan tilt sweep"
scene = "{os.path.join(SCENES, 'cardan_lagrange_horizontal.toml')}"
scheme = "cardan-rk4"
dt = 2.0e-3
t_end = 0.5
monitor_every = 5

[[vary]]
key = "suspension.tilt"
values = [0.0, 0.4, 1.5707963267948966]

[[event]]
quantity = "gamma"
component = 3
value = 0.5
name = "gamma3"
{extra}''')
    return str(spec)


def test_sweep_on_a_cardan_scene(tmp_path):
    spec = write_cardan_spec(tmp_path)
    outs = []
    for threads in ("1", "2"):
        out = str(tmp_path / f"sweep{threads}.h5")
        r = lgi("sweep", "--spec", spec, "--threads", threads, "--quiet", "--out", out)
        assert r.returncode == 0, r.stderr
        outs.append(out)
    with h5py.File(outs[0], "r") as f, h5py.File(outs[1], "r") as g:
        s = f["sweep"]
        assert list(s["status"][()]) == [0, 0, 0]
        assert list(s["steps"][()]) == [250, 250, 250]
        # H is kept to the scheme's accuracy; p1 is an integral only with the outer axis vertical (tilt 0).
        assert np.all(s["max_energy_error"][()] < 1e-6)
        p1 = s["max_cardan_momentum_1_error"][()]
        assert p1[0] < 1e-12 and np.isnan(p1[1]) and np.isnan(p1[2])
        for column in ("angular_momentum", "orientation", "gamma", "max_energy_error"):
            assert np.array_equal(s[column][()], g["sweep"][column][()], equal_nan=True)
        assert np.array_equal(f["events/t"][()], g["events/t"][()])
        assert np.all(np.abs(f["events/gamma"][()][:, 2] - 0.5) < 1e-9)
        final_pi = s["angular_momentum"][()][2]
    # Row 2 has the scene's own tilt: its final state is that of lgi simulate on the scene.
    sim = str(tmp_path / "sim.h5")
    r = lgi("simulate", "--scene", os.path.join(SCENES, "cardan_lagrange_horizontal.toml"), "--scheme", "cardan-rk4",
            "--dt", "2e-3", "--t-end", "0.5", "--out", sim)
    assert r.returncode == 0, r.stderr
    with h5py.File(sim, "r") as f:
        assert np.array_equal(f["particles/body/angular_momentum_body/value"][()][-1].reshape(3), final_pi)


def test_sweep_on_a_cardan_scene_refuses_so3_state_keys(tmp_path):
    for extra, word in (('[[vary]]\nkey = "initial.angular_momentum"\nvalues = [[0.0, 0.0, 1.0]]\n', "initial.angular_momentum"),
                        ('[level_set]\nh = 1.0\nl = 0.5\n', "level_set")):
        r = lgi("sweep", "--spec", write_cardan_spec(tmp_path, extra), "--out", str(tmp_path / "x.h5"))
        assert r.returncode == 2, r.stderr
        assert len(r.stderr.strip().splitlines()) == 1 and word in r.stderr and "T^3 x R^3" in r.stderr, r.stderr
        assert not os.path.exists(tmp_path / "x.h5") and not os.path.exists(tmp_path / "x.h5.partial")
