"""`lgi periodic --from-critical` on the Kovalevskaya top (experiments/PERIODIC.md,
"Kovalevskaya's top: critical orbits"):
 - at l = 1, the critical orbits seeded at h = 1 and continued one step in h:
   k recomputed here from Pi and Gamma equals the file's `k`, and (h, k) lies on
   an Appelrot family evaluated here (docs/atlas.md section 9) to 1e-8; the
   families 0, 1 and 2 are all met, no orbit is degenerate; the CSV has the columns;
   each orbit integrated for one period by SciPy's DOP853 (another integrator)
   returns to its point to 1e-8;
 - at l = 0, h = 0.9 (default options, single shooting) the strongly hyperbolic
   critical orbit (tr P = 1.05e4) meets the bar of issue 51 from the file's
   multipliers: residual <= 1e-10, four multipliers within 1e-8 of 1, their
   product within 1e-8 of 1; it was read from more than one monodromy piece,
   and the pair is (lambda, 1/lambda) with lambda + 1/lambda = reduced_trace;
 - a general top's rows have k = NaN and appelrot_family = -1;
 - bad input: --from-critical on a top that is not Kovalevskaya's, a malformed
   list, or with --from-equilibria: one line naming the flag, exit 2."""
import os

import h5py
import numpy as np
from scipy.integrate import solve_ivp
from lgi_cli import lgi, refused

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
KOVALEVSKAYA = os.path.join(ROOT, "experiments", "scenes", "kovalevskaya.toml")
GENERAL = os.path.join(ROOT, "experiments", "scenes", "general_top_richter.toml")


def appelrot_gap(h, k, l):
    """min |k - k_f(h)| / (1 + k) over the Appelrot families at l (J3 = c = 1)."""
    G = 0.5 * l * l
    values = [0.0, (h - G) ** 2]
    if G == 0.0:
        values += [1.0] + ([1.0 + h * h] if h > 0 else [])
    else:
        for s in np.roots([2.0, -2.0 * h, 0.0, G]):  # h = s + G/(2 s^2)
            if abs(s.imag) < 1e-9 and s.real != 0.0:
                s = s.real
                values.append(1.0 - G / s + G * G / (4.0 * s ** 4))
    return min(abs(k - v) for v in values) / (1.0 + k)


def test_critical_orbits_on_the_appelrot_curves(tmp_path):
    out = str(tmp_path / "k.h5")
    r = lgi("periodic", "--scene", KOVALEVSKAYA, "--l", "1", "--from-critical", "1", "--steps", "1",
            "--h-step", "0.05", "--out", out)
    assert "on an Appelrot family" in r.stdout
    with h5py.File(out, "r") as f:
        g = f["periodic"]
        t = {c: g[c][()] for c in g}
        assert f["parameters"].attrs["from_critical"] in ("1", b"1")
    n = len(t["h"])
    assert n >= 6
    pi, gamma = t["angular_momentum"], t["gamma"]
    w = pi / np.array([2.0, 2.0, 1.0])
    k = (w[:, 0] ** 2 - w[:, 1] ** 2 - gamma[:, 0]) ** 2 + (2 * w[:, 0] * w[:, 1] - gamma[:, 1]) ** 2
    assert np.allclose(k, t["k"], rtol=0, atol=1e-12)
    for i in range(n):
        assert appelrot_gap(t["h"][i], k[i], t["l"][i]) <= 1e-8, (i, t["h"][i], k[i])
    assert np.all(t["appelrot_distance"] <= 1e-8)
    assert set(t["appelrot_family"]) == {0, 1, 2}
    assert np.all(t["degenerate"] == 0)
    multiplier_bar(t)
    J, weight = np.array([2.0, 2.0, 1.0]), np.array([1.0, 0.0, 0.0])  # the scene's J and m g chi

    def field(_, x):
        return np.concatenate([np.cross(x[:3], x[:3] / J) + np.cross(x[3:], weight), np.cross(x[3:], x[:3] / J)])

    for i in range(n):
        x0 = np.concatenate([pi[i], gamma[i]])
        end = solve_ivp(field, (0.0, t["period"][i]), x0, method="DOP853", rtol=1e-13, atol=1e-13).y[:, -1]
        assert np.abs(end - x0).max() <= 1e-8, i
    with open(str(tmp_path / "k.csv")) as c:
        header = c.readline()
    for col in ("k", "appelrot_family", "appelrot_distance", "critical_rank_gap"):
        assert col in header


def multiplier_bar(t):
    """The multipliers' checks of the file, recomputed from its `multipliers` column."""
    mu = t["multipliers"].reshape(-1, 6, 2)
    mu = mu[..., 0] + 1j * mu[..., 1]
    assert np.all(t["residual"] <= 1e-10)
    assert np.all(np.abs(mu[:, :4] - 1.0) <= 1e-8)
    assert np.all(np.abs(np.prod(mu, axis=1) - 1.0) <= 1e-8)
    return mu


def test_strongly_hyperbolic_orbit_meets_the_bar(tmp_path):
    out = str(tmp_path / "h.h5")
    lgi("periodic", "--scene", KOVALEVSKAYA, "--l", "0", "--from-critical", "0.9", "--steps", "0", "--out", out,
        "--quiet")
    with h5py.File(out, "r") as f:
        t = {c: f["periodic"][c][()] for c in f["periodic"]}
    mu = multiplier_bar(t)
    strong = np.abs(t["reduced_trace"]) > 800
    assert strong.sum() >= 1
    assert np.all(t["monodromy_pieces"][strong] > 1) and np.all(t["monodromy_pieces"] >= 1)
    pair = mu[strong][:, 4:].real
    assert np.allclose(pair.sum(axis=1), t["reduced_trace"][strong], rtol=1e-12, atol=0)


def test_general_top_and_bad_input(tmp_path):
    out = str(tmp_path / "g.h5")
    lgi("periodic", "--scene", GENERAL, "--l", "3", "--from-equilibria", "--steps", "0", "--out", out, "--quiet")
    with h5py.File(out, "r") as f:
        g = f["periodic"]
        assert np.all(np.isnan(g["k"][()])) and np.all(g["appelrot_family"][()] == -1)
    bad = str(tmp_path / "x.h5")
    assert "--from-critical" in refused("periodic", "--scene", GENERAL, "--l", "1", "--from-critical", "1",
                                        "--out", bad)
    assert "--from-critical" in refused("periodic", "--scene", KOVALEVSKAYA, "--l", "1", "--from-critical", "1,x",
                                        "--out", bad)
    assert "--from-critical" in refused("periodic", "--scene", KOVALEVSKAYA, "--l", "1", "--from-critical", "1",
                                        "--from-equilibria", "--out", bad)
    assert not os.path.exists(bad)
