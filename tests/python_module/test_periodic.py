"""lgi.periodic_orbit and lgi.continue_family (experiments/PERIODIC.md): a
family of Richter's top through a period doubling; the located orbit
re-integrated for one period by SciPy's DOP853 (another integrator, written
here on the Euler-Poisson equations) returns to its point to 1e-8, and the
monodromy's trace is 4 + tr P; refusals as ValueError."""
import os
import tomllib

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import lgi

from conftest import SCENES

RICHTER = os.path.join(SCENES, "general_top_richter.toml")
# A point of the l = 2.2 family of period ~4.06 (lgi periodic --l 2.2 --from-equilibria).
SEED = ([-0.5440143623441437, -0.6150665918126653, -2.0653514662689068],
        [-0.33283680104325525, -0.37020048866337674, -0.8672780765503418], 4.061522325732049)


def test_family_through_a_period_doubling():
    fam = lgi.continue_family(RICHTER, 2.2, seed=SEED, steps=3, h_step=0.02, branch_switching=False)
    n = len(fam["h"])
    assert fam["multipliers"].shape == (n, 6, 2) and fam["angular_momentum"].shape == (n, 3)
    assert np.all(fam["residual"] <= 1e-10) and np.all(fam["trivial_deviation"] <= 1e-8)
    events = list(fam["event"])
    assert "period_doubling" in events and set(fam["parent"]) == {-1}
    k = events.index("period_doubling")
    assert abs(fam["reduced_trace"][k] + 2.0) <= 1e-8
    assert 0.693 < fam["h"][k] < 0.694

    one = lgi.periodic_orbit(RICHTER, fam["angular_momentum"][k], fam["gamma"][k], fam["period"][k])
    assert one["converged"] and one["residual"][0] <= 1e-10
    assert one["monodromy"].shape == (6, 6)
    assert abs(np.trace(one["monodromy"]) - 4.0 - one["reduced_trace"][0]) <= 1e-8
    # M maps the flow direction to itself (and is not its transpose): M f = f.
    scene = lgi.Scene.from_file(RICHTER)
    w = scene.mass * tomllib.loads(scene.toml)["gravity"]["g"] * np.asarray(scene.center_of_mass)
    pi, g = one["angular_momentum"][0], one["gamma"][0]
    om = np.linalg.solve(np.asarray(scene.inertia), pi)
    f = np.concatenate([np.cross(pi, om) + np.cross(g, w), np.cross(g, om)])
    assert np.linalg.norm(one["monodromy"] @ f - f) <= 1e-6 * np.linalg.norm(f)
    assert fam["family_end"][-1] != "" and fam["failures"] == []


def test_an_independent_integrator_closes_the_orbit():
    fam = lgi.continue_family(RICHTER, 2.2, seed=SEED, steps=1, h_step=0.02, events=False)
    scene = lgi.Scene.from_file(RICHTER)
    g = tomllib.loads(scene.toml)["gravity"]["g"]
    w = scene.mass * g * np.asarray(scene.center_of_mass)
    Jinv = np.linalg.inv(np.asarray(scene.inertia))

    def f(_, x):
        pi, g = x[:3], x[3:]
        om = Jinv @ pi
        return np.concatenate([np.cross(pi, om) + np.cross(g, w), np.cross(g, om)])

    for k in range(len(fam["h"])):
        x0 = np.concatenate([fam["angular_momentum"][k], fam["gamma"][k]])
        end = solve_ivp(f, (0.0, fam["period"][k]), x0, method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]
        assert np.linalg.norm(end - x0) <= 1e-8


def test_refusals():
    with pytest.raises(ValueError, match="period"):
        lgi.periodic_orbit(RICHTER, [1, 0, 0], [0, 0, 1], -1.0)
    with pytest.raises(ValueError, match="gamma"):
        lgi.periodic_orbit(RICHTER, [1, 0, 0], [0, 0], 1.0)
    with pytest.raises(ValueError, match="h_step"):
        lgi.continue_family(RICHTER, 2.2, h_step=0.0)
    with pytest.raises(ValueError, match="Cardan"):
        lgi.continue_family(os.path.join(SCENES, "cardan_lagrange_upright.toml"), 1.0)
