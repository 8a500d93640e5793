"""lgi.periodic_orbit and lgi.continue_family (experiments/PERIODIC.md): a
family of Richter's top through a period doubling; the located orbit
re-integrated for one period by SciPy's DOP853 (another integrator, written
here on the Euler-Poisson equations) returns to its point to 1e-8, and the
monodromy's trace is 4 + tr P; the options of `lgi periodic` as keywords:
multiple shooting (shooting_points), continuation in l (continue_in, l_step),
branch switching at the period doubling (the doubled family: parent 0, period
~2T), seeds from a poincare file and the manifolds of a hyperbolic orbit;
refusals as ValueError."""
import os
import sys
import tomllib

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import lgi

from conftest import SCENES, SOURCE

sys.path.insert(0, os.path.join(SOURCE, "scripts", "plots"))
import periodic_crossings as pc  # noqa: E402

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


def test_multiple_shooting_and_continuation_in_l():
    one = lgi.periodic_orbit(RICHTER, SEED[0], SEED[1], SEED[2] * 1.01)
    three = lgi.periodic_orbit(RICHTER, SEED[0], SEED[1], SEED[2] * 1.01, shooting_points=3)
    assert one["converged"] and three["converged"]
    assert abs(three["period"][0] - one["period"][0]) <= 1e-9
    assert np.linalg.norm(three["monodromy"] - one["monodromy"]) <= 1e-7
    fam = lgi.continue_family(RICHTER, 2.2, seed=SEED, steps=2, continue_in="l", l_step=-0.01, events=False,
                              shooting_points=2)
    assert fam["failures"] == [] and len(fam["l"]) == 3
    assert np.all(np.abs(fam["h"] - fam["h"][0]) <= 1e-10) and np.all(fam["residual"] <= 1e-10)
    assert abs(fam["l"][1] - 2.19) <= 1e-12 and fam["l"][2] < 2.19


def test_branch_switching_at_the_period_doubling():
    fam = lgi.continue_family(RICHTER, 2.2, seed=SEED, steps=3, h_step=0.02, branch_switching=True)
    k = list(fam["event"]).index("period_doubling")
    doubled = np.flatnonzero(fam["parent"] == fam["family"][k])
    assert len(doubled) >= 2
    assert abs(fam["period"][doubled[0]] - 2 * fam["period"][k]) <= 0.05
    assert abs(fam["h"][doubled[0]] - fam["h"][k]) <= 1e-3


# A hyperbolic orbit of Richter's top at l = 3 past its fold (tests/commands/test_periodic.py).
HYPERBOLIC = ([2.737126154036692, 0.8488396292006605, -1.033127987220866, 0.8115814748784526, 0.4064375267217684,
               -0.4196951828487045], 4.535817543042772, 4.938876025487969)


def test_seeds_from_poincare_and_manifolds(tmp_path):
    x0, T, h = np.array(HYPERBOLIC[0]), HYPERBOLIC[1], HYPERBOLIC[2]
    with open(RICHTER) as f:
        J, w = pc.body_of(f.read())
    phi, theta, sheet = pc.crossings(x0, T, J, w, w / np.linalg.norm(w), True)[0]
    section = str(tmp_path / "s.h5")
    lgi.poincare(RICHTER, 3.0, h, 1, 5.0, out=section)
    fam = lgi.continue_family(RICHTER, seeds_from_poincare=section, poincare_points=[(phi, theta, sheet)], steps=0,
                              manifolds=4, manifold_periods=1.0)
    assert fam["l_file"] == 3.0 and fam["failures"] == []
    assert len(fam["period"]) == 1 and abs(fam["period"][0] - T) <= 1e-8
    assert fam["stability"] == ["hyperbolic"]
    m = fam["manifolds"]
    assert set(m["branch"]) == {"unstable", "stable"} and m["angular_momentum"].shape[1] == 3
    assert np.all(m["t"][np.array(m["branch"]) == "stable"] <= 0)
    assert np.all(m["returns"] == m["returns"][0]) and m["multiplier"][0] > 1.5


def test_refusals():
    with pytest.raises(ValueError, match="shooting_points"):
        lgi.periodic_orbit(RICHTER, SEED[0], SEED[1], SEED[2], shooting_points=0)
    with pytest.raises(ValueError, match="continue_in"):
        lgi.continue_family(RICHTER, 2.2, continue_in="x")
    with pytest.raises(ValueError, match="poincare_rows"):
        lgi.continue_family(RICHTER, 2.2, poincare_rows=[0])
    with pytest.raises(ValueError, match="manifolds"):
        lgi.continue_family(RICHTER, 2.2, manifolds=3)
    with pytest.raises(ValueError, match="period"):
        lgi.periodic_orbit(RICHTER, [1, 0, 0], [0, 0, 1], -1.0)
    with pytest.raises(ValueError, match="gamma"):
        lgi.periodic_orbit(RICHTER, [1, 0, 0], [0, 0], 1.0)
    with pytest.raises(ValueError, match="h_step"):
        lgi.continue_family(RICHTER, 2.2, h_step=0.0)
    with pytest.raises(ValueError, match="suspension.tilt"):  # a vertical frame is accepted (test_periodic_cardan.py)
        lgi.continue_family(os.path.join(SCENES, "cardan_general_horizontal.toml"), 1.0)
