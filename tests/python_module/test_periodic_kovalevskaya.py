"""lgi.continue_family and lgi.periodic_orbit on the Kovalevskaya top
(experiments/PERIODIC.md, "Kovalevskaya's top: critical orbits"): the Lyapunov
families at l = 0 carry k, recomputed here from Pi and Gamma, on the Appelrot
families k = h^2 and k = 1 to 1e-8; another top's k is NaN."""
import os

import numpy as np

import lgi

from conftest import SCENES

KOVALEVSKAYA = os.path.join(SCENES, "kovalevskaya.toml")


def test_lyapunov_families_on_the_appelrot_curves():
    fam = lgi.continue_family(KOVALEVSKAYA, 0.0, steps=2, h_step=0.05, branch_switching=False)
    pi, gamma, h = fam["angular_momentum"], fam["gamma"], fam["h"]
    w = pi / np.array([2.0, 2.0, 1.0])
    k = (w[:, 0] ** 2 - w[:, 1] ** 2 - gamma[:, 0]) ** 2 + (2 * w[:, 0] * w[:, 1] - gamma[:, 1]) ** 2
    assert np.allclose(fam["k"], k, rtol=0, atol=1e-12)
    on = np.minimum(np.abs(k - h * h), np.abs(k - 1.0)) / (1.0 + k)  # families 1 and 2 at l = 0
    assert np.all(on <= 1e-8) and np.all(fam["appelrot_distance"] <= 1e-8)
    assert set(fam["appelrot_family"]) == {1, 2}
    assert np.all(fam["degenerate"] == 0)
    one = lgi.periodic_orbit(KOVALEVSKAYA, pi[-1], gamma[-1], fam["period"][-1], h=h[-1], l=0.0)
    assert one["converged"] and abs(one["k"][0] - k[-1]) <= 1e-10


def test_another_top_has_no_k():
    fam = lgi.continue_family(os.path.join(SCENES, "general_top_richter.toml"), 3.0, steps=0)
    assert np.all(np.isnan(fam["k"])) and np.all(fam["appelrot_family"] == -1)
