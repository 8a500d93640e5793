"""lgi.indicators, lgi.tangent_flow and the Stepper.state setter
(python/README.md): the records of `lgi indicators` bit for bit, from a
state file and from a dict; the tangent vector against central differences
of the flow; (6, k) columns equal to one vector at a time; a set state
continues as a fresh stepper started there; bad states are refused."""
import os
import subprocess

import h5py
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

import lgi

from conftest import SCENES

GENERAL = os.path.join(SCENES, "general_top_richter.toml")
BOOK = os.path.join(SCENES, "dzhanibekov_book_axis2.toml")


def run_cli(exe, *args):
    return subprocess.run([exe, *args], capture_output=True, text=True)


def test_indicators_match_lgi_indicators(lgi_exe, tmp_path):
    eq, out = str(tmp_path / "eq.h5"), str(tmp_path / "ind.h5")
    assert run_cli(lgi_exe, "equilibria", "--scene", GENERAL, "--l", "2", "--out", eq, "--quiet").returncode == 0
    r = run_cli(lgi_exe, "indicators", "--scene", GENERAL, "--state-file", eq, "--t-end", "15", "--dt", "0.01",
                "--spectrum", "--seed", "4", "--out", out, "--quiet")
    assert r.returncode == 0, r.stderr
    with h5py.File(out, "r") as f:
        cli = {k: f["indicators"][k][()] for k in f["indicators"]}
    mine = lgi.indicators(GENERAL, t_end=15, dt=0.01, states=eq, spectrum=True, seed=4)
    assert sorted(mine) == sorted(cli)
    for k in cli:
        assert np.array_equal(mine[k], cli[k], equal_nan=True), k
    with h5py.File(eq, "r") as f:
        states = {"angular_momentum": f["equilibria/angular_momentum"][()], "gamma": f["equilibria/gamma"][()]}
    again = lgi.indicators(lgi.Scene.from_file(GENERAL), t_end=15, dt=0.01, states=states, spectrum=True, seed=4)
    assert np.array_equal(again["lyapunov"], cli["lyapunov"])
    one = lgi.indicators(GENERAL, t_end=5)  # the scene's initial state and [run] dt
    assert one["index"].tolist() == [0] and "spectrum" not in one
    with pytest.raises(ValueError, match="t_end"):
        lgi.indicators(GENERAL, t_end=-1)
    with pytest.raises(ValueError, match="angular_momentum"):
        lgi.indicators(GENERAL, t_end=1, states={"gamma": [[0, 0, 1]]})


def test_tangent_flow_against_central_differences():
    scene = lgi.Scene.from_file(GENERAL)
    x0 = {"R": Rotation.from_rotvec([0.3, -0.2, 0.5]).as_matrix(), "Pi": np.array([1.0, 0.7, 1.1])}
    v = np.array([0.2, -0.1, 0.3, 0.5, 0.1, -0.4])
    dt, steps, eps = 0.01, 100, 1e-6
    end = lgi.tangent_flow(scene, x0, v, dt, steps)
    assert end["t"] == pytest.approx(1.0) and end["v"].shape == (6,)

    def moved(s):
        x = {"R": x0["R"] @ Rotation.from_rotvec(s * v[:3]).as_matrix(), "Pi": x0["Pi"] + s * v[3:]}
        return lgi.tangent_flow(scene, x, np.zeros(6), dt, steps)

    plus, minus = moved(eps), moved(-eps)
    xi = (Rotation.from_matrix(end["R"].T @ plus["R"]).as_rotvec()
          - Rotation.from_matrix(end["R"].T @ minus["R"]).as_rotvec()) / (2 * eps)
    dpi = (plus["Pi"] - minus["Pi"]) / (2 * eps)
    fd = np.concatenate([xi, dpi])
    assert np.abs(end["v"] - fd).max() < 1e-6 * np.abs(fd).max()
    # Several columns at once: each as if alone, bit for bit.
    V = np.stack([v, -2 * v[::-1]], axis=1)
    both = lgi.tangent_flow(scene, x0, V, dt, steps)
    assert both["v"].shape == (6, 2) and np.array_equal(both["v"][:, 0], end["v"])
    assert np.array_equal(both["v"][:, 1], lgi.tangent_flow(scene, x0, V[:, 1], dt, steps)["v"])
    with pytest.raises(ValueError, match="v:"):
        lgi.tangent_flow(scene, x0, np.zeros(5), dt)


def test_stepper_state_setter():
    dt = 1e-3
    book = lgi.Scene.from_file(BOOK)
    R1, P1 = Rotation.from_rotvec([0.4, -0.3, 0.2]).as_matrix(), np.array([0.2, 1.5, -0.3])
    stepper = lgi.Stepper(book, "rkmk4", dt)
    stepper.state = {"R": R1, "Pi": P1}
    stepper.step(30)
    # The same body started there by a scene file: one run, the same grid, bit for bit.
    with open(BOOK) as f:
        text = f.read()
    rows = ", ".join("[" + ", ".join(repr(float(x)) for x in row) + "]" for row in R1)
    there = lgi.Scene.from_toml(text[: text.index("[initial]")] + "[initial]\nmatrix = [" + rows + "]\n"
                                "angular_momentum = [" + ", ".join(repr(float(x)) for x in P1) + "]\n")
    run = lgi.simulate(there, "rkmk4", 30 * dt, dt=dt)
    assert np.array_equal(stepper.state["R"], run.R[-1]) and np.array_equal(stepper.state["Pi"], run.Pi[-1])
    assert stepper.t == run.t[-1]
    g = np.array([0.48, -0.6, 0.64])
    stepper.state = {"gamma": g, "Pi": [0.1, 0.2, 0.3]}
    assert np.abs(stepper.state["R"].T @ [0, 0, 1] - g).max() < 1e-15
    assert stepper.state["Pi"].tolist() == [0.1, 0.2, 0.3] and stepper.t == run.t[-1]  # the time is kept
    with pytest.warns(UserWarning, match="normalised"):
        stepper.state = {"gamma": 2 * g, "Pi": [0.1, 0.2, 0.3]}
    with pytest.raises(ValueError, match="not a rotation"):
        stepper.state = {"R": 1.001 * np.eye(3), "Pi": [0, 0, 1]}
    with pytest.raises(ValueError, match="gamma"):
        stepper.state = {"gamma": [0, 0, 0], "Pi": [0, 0, 1]}
    with pytest.raises(ValueError, match="Pi"):
        stepper.state = {"R": np.eye(3)}
