"""`lgi actions` as a user runs it (experiments/ACTIONS.md, docs/actions.md):
 - the scene's torus: the Lagrange closed form and the numerical torus agree up to the
   integer change of basis (I_a = |L3|, I_b = I_theta + n |L3|, omega.I the same);
 - the Euler top's energy surface: every row has H(G, I_l) = h (checked through the
   free body's energy range: G^2/(2 J_max) <= h <= G^2/(2 J_min)), |l| <= G, omega_l < 0;
 - the Lagrange energy surface: I_theta >= 0 and the plot script draws it;
 - the Kovalevskaya torus of a level (h, l, k) (--k): found on the level, Maslov indices (2, 4),
   its libration actions near the harmonic ones;
 - bad flags exit 2 with one line naming the flag."""
import os
import subprocess
import sys

import numpy as np
from lgi_cli import ROOT, SCENES, columns, lgi

LAGRANGE = os.path.join(SCENES, "lagrange_top_cigar.toml")
FREE = os.path.join(SCENES, "free_body_hlw.toml")
KOVALEVSKAYA = os.path.join(SCENES, "kovalevskaya.toml")


def test_single_lagrange_torus_closed_form_and_numerical(tmp_path):
    out = str(tmp_path / "a.h5")
    r = lgi("actions", "--scene", LAGRANGE, "--dt", "0.002", "--crossings", "200", "--out", out)
    assert r.stdout.count("method=") == 2
    t = columns(out, "tori")
    assert list(t["method"]) == [0, 2] and list(t["ok"]) == [1, 1]
    (l0, L3, I_theta), (l1, Ia, Ib) = t["actions"]
    assert abs(l0 - l1) < 1e-14 * abs(l0)
    assert abs(Ia - abs(L3)) < 1e-9 * abs(L3)
    assert abs(Ib - I_theta) < 1e-8 * (abs(L3) + I_theta)  # cycle b: the nutation (docs/actions.md §3)
    assert list(t["reason"]) == [0, 0] and t["section"][1] == 5  # the section Gamma3 = c
    w0, w1 = t["frequencies"]
    assert abs(w1[2] - w0[2]) < 1e-8 * w0[2]
    assert abs((w1[1] * Ia + w1[2] * Ib) - (w0[1] * L3 + w0[2] * I_theta)) < 1e-8 * abs(w0[1] * L3)
    assert os.path.exists(str(tmp_path / "a.csv"))


def test_euler_energy_surface(tmp_path):
    out = str(tmp_path / "e.h5")
    lgi("actions", "--scene", FREE, "--h", "0.5", "--grid", "21", "--out", out, "--quiet")
    t = columns(out, "tori")
    l, G, I = t["actions"].T
    assert len(l) > 300 and np.all(t["method"] == 1)
    J = np.array([2.0, 1.0, 2.0 / 3.0])
    assert np.all(G**2 / (2 * J.max()) <= 0.5 + 1e-12) and np.all(G**2 / (2 * J.min()) >= 0.5 - 1e-12)
    assert np.all(np.abs(l) <= G * (1 + 1e-12)) and np.all((I >= 0) & (I <= G))
    assert np.all(t["frequencies"][:, 0] == 0) and np.all(t["frequencies"][:, 2] < 0)


def test_lagrange_energy_surface_and_plot(tmp_path):
    out = str(tmp_path / "lag.h5")
    lgi("actions", "--scene", LAGRANGE, "--h", "2", "--grid", "25", "--out", out, "--quiet")
    t = columns(out, "tori")
    assert len(t["h"]) > 50 and np.all(t["actions"][:, 2] >= 0) and np.all(t["h"] == 2.0)
    script = os.path.join(ROOT, "scripts", "plots", "actions.py")
    r = subprocess.run([sys.executable, script, "--out", str(tmp_path / "figs"), out], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert os.path.getsize(str(tmp_path / "figs" / "actions.png")) > 1000


def test_lagrange_energy_surface_through_the_separatrix(tmp_path):
    # h = w on a Lagrange top: the grid's apex l = L3 = 0 is the pendulum's homoclinic orbit
    # (u2 = u3), no torus; the surface is written without it (was exit 1, a Boost domain error).
    out = str(tmp_path / "sep.h5")
    lgi("actions", "--scene", os.path.join(SCENES, "lagrange_top_oblate.toml"), "--h", "1", "--out", out, "--quiet")
    t = columns(out, "tori")
    a = t["actions"]
    assert len(a) > 100 and np.all(np.isfinite(a[:, 2]))
    assert not np.any((a[:, 0] == 0.0) & (a[:, 1] == 0.0))


def test_failed_torus_has_reason_and_nan_actions(tmp_path):
    out = str(tmp_path / "k.h5")
    # The first torus of l = 0 at h = 2 is a periodic orbit: its section is one point.
    r = lgi("actions", "--scene", KOVALEVSKAYA, "--h", "2", "--l", "0", "--tori", "1", "--out", out)
    assert "torus 0 (l = 0): failed, reason 4: the section is one point" in r.stdout
    assert "1 tori on H = 2, 0 ok" in r.stdout
    t = columns(out, "tori")
    assert list(t["ok"]) == [0] and list(t["reason"]) == [4]
    assert np.all(np.isnan(t["actions"][:, 1:])) and np.all(np.isnan(t["frequencies"]))


def test_kovalevskaya_torus_of_a_level(tmp_path):
    # Near the hanging position (h = -1 + w_s I_s + w_f I_f, k = 1 - 2 w_s I_s with I_s = I_f = 0.05):
    # the section cuts the slow swing, cycle b = slow + fast (docs/actions.md section 5).
    out = str(tmp_path / "k.h5")
    r = lgi("actions", "--scene", KOVALEVSKAYA, "--h", "-0.91464", "--l", "0", "--k", "0.92929", "--crossings", "100",
            "--harmonics", "16", "--out", out)
    assert "maslov=(2, 4)" in r.stdout and "ok=1" in r.stdout, r.stdout
    t = columns(out, "tori")
    assert abs(t["k"][0] - 0.92929) < 1e-9 and abs(t["h"][0] + 0.91464) < 1e-9
    assert list(t["maslov"][0]) == [2, 4]
    slow, fast = t["libration_actions"][0]
    assert abs(slow - 0.05) < 0.005 and abs(fast - 0.05) < 0.005, (slow, fast)
    for args, flag in [(["--k", "0.9", "--h", "-0.9"], "--k"), (["--k", "0.9"], "--k")]:
        r = lgi("actions", "--scene", KOVALEVSKAYA, *args, "--out", out + "x", check=False)
        assert r.returncode == 2 and flag in r.stderr and r.stderr.count("\n") == 1, (args, r.stderr)
    r = lgi("actions", "--scene", LAGRANGE, "--h", "2", "--l", "0", "--k", "0.9", "--out", out + "x", check=False)
    assert r.returncode == 2 and "--k" in r.stderr and "Kovalevskaya" in r.stderr
    r = lgi("actions", "--scene", KOVALEVSKAYA, "--h", "-0.9", "--l", "0", "--k", "5", "--out", out + "x", check=False)
    assert r.returncode == 2 and "no point" in r.stderr


def test_bad_flags(tmp_path):
    out = str(tmp_path / "x.h5")
    for args, flag in [(["--h", "nan"], "--h"), (["--l", "1"], "--l"), (["--grid", "1", "--h", "1"], "--grid"),
                       (["--scheme", "nope"], "--scheme"), (["--crossings", "3"], "--crossings")]:
        r = lgi("actions", "--scene", LAGRANGE, *args, "--out", out, check=False)
        assert r.returncode == 2 and flag in r.stderr and r.stderr.count("\n") == 1, (args, r.stderr)
    r = lgi("actions", "--scene", KOVALEVSKAYA, "--h", "2", "--out", out, check=False)
    assert r.returncode == 2 and "--l" in r.stderr
    assert not os.path.exists(out)
