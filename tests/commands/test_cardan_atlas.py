"""The tops atlas on T^3 as a user runs it (docs/cardan.md section 9):
 - `lgi equilibria --l` on a Cardan top with massless rings gives each of
   `lgi equilibria` on the same top on SO(3) twice (the ZXZ double cover),
   with its energy and class; the table has the heavy top's columns plus
   cardan_angles, degenerate and pole;
 - `lgi bifurcation` on a Cardan top: branches in omega, a CSV beside;
 - `lgi poincare` on a Cardan top: /sweep and /events with the pieces of the
   section, crossings on S = 0, bit-identical for 1 and 2 threads; the figure
   script draws it;
 - refusals with exit 2 and one line: a tilted frame for equilibria, --axis
   and --section, h below the least energy at l, an SO(3) scheme."""
import os
import subprocess

import h5py
import numpy as np
from lgi_cli import ROOT, SCENES, columns, lgi

GENERAL = os.path.join(SCENES, "general_top_richter.toml")
UPRIGHT = os.path.join(SCENES, "cardan_lagrange_upright.toml")
HORIZONTAL = os.path.join(SCENES, "cardan_lagrange_horizontal.toml")
GENERAL_UP = os.path.join(SCENES, "cardan_general_asymmetric_up.toml")

MASSLESS = """name = "Richter's general top in massless rings"
[body]
mass = 1.0
inertia = [1.0, 1.5, 2.0]
center_of_mass = [0.8, 0.4, 0.3]
[gravity]
g = 1.0
[suspension]
tilt = 0.0
outer_inertia = 0.0
inner_inertia = [0.0, 0.0, 0.0]
[initial]
cardan_angles = [0.0, 1.0, 0.5]
cardan_rates = [0.3, 0.2, 1.0]
[run]
t_end = 10.0
dt = 1.0e-2
"""


def refused(r, *words):
    assert r.returncode == 2, (r.returncode, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1, r.stderr
    for w in words:
        assert w in lines[0], lines[0]


def test_equilibria_massless_rings_double_staude(tmp_path):
    scene = tmp_path / "massless.toml"
    scene.write_text(MASSLESS)
    lgi("equilibria", "--scene", str(scene), "--l", "1", "--out", str(tmp_path / "t3.h5"), "--quiet")
    lgi("equilibria", "--scene", GENERAL, "--l", "1", "--out", str(tmp_path / "so3.h5"), "--quiet")
    t3, so3 = columns(tmp_path / "t3.h5", "equilibria"), columns(tmp_path / "so3.h5", "equilibria")
    for column in ("omega", "gamma", "angular_momentum", "l", "h", "branch", "g1", "g2", "stability",
                   "nonlinearly_stable", "fold", "residual", "cardan_angles", "degenerate", "pole"):
        assert column in t3, column
    assert len(t3["h"]) == 2 * len(so3["h"])
    for g, h, s in zip(so3["gamma"], so3["h"], so3["stability"]):
        match = np.linalg.norm(t3["gamma"] - g, axis=1) < 1e-9
        assert match.sum() == 2
        assert np.allclose(t3["h"][match], h, rtol=1e-11)
        assert (t3["stability"][match] == s).all()
    assert os.path.exists(tmp_path / "t3.csv")


def test_bifurcation_of_a_cardan_top(tmp_path):
    out = tmp_path / "b.h5"
    r = lgi("bifurcation", "--scene", GENERAL_UP, "--samples", "60", "--omega-max", "2", "--out", str(out))
    assert "Cardan" in r.stdout
    e = columns(out, "equilibria")
    assert len(e["h"]) > 60
    assert np.abs(e["omega"]).max() <= 2.0
    assert (e["residual"] < 1e-9).all()
    assert len(np.unique(e["branch"])) >= 4
    with h5py.File(out, "r") as f:
        assert f["parameters"].attrs["subcommand"] in ("bifurcation", b"bifurcation")


def test_poincare_of_a_cardan_top(tmp_path):
    args = ["poincare", "--scene", GENERAL_UP, "--l", "1.68", "--h", "2.2", "--ics", "6", "--t-end", "60",
            "--dt", "0.01", "--megno", "--lyapunov", "--quiet"]
    lgi(*args, "--threads", "1", "--out", str(tmp_path / "one.h5"))
    lgi(*args, "--threads", "2", "--out", str(tmp_path / "two.h5"))
    s, e = columns(tmp_path / "one.h5", "sweep"), columns(tmp_path / "one.h5", "events")
    s2, e2 = columns(tmp_path / "two.h5", "sweep"), columns(tmp_path / "two.h5", "events")
    for k in s:
        if k != "cpu_seconds":
            assert np.array_equal(s[k], s2[k]), k
    for k in e:
        assert np.array_equal(e[k], e2[k]), k
    assert (s["status"] == 0).all()
    assert np.array_equal(s["initial_cardan_momenta"][:, 0], np.full(6, 1.68))
    assert (s["max_energy_error"] < 1e-6).all()
    assert (s["megno"] > 0).all() and np.isfinite(s["lyapunov"]).all()
    assert set(np.unique(e["piece"])) <= {-1, 1, 2, 3}
    assert len(e["t"]) == s["crossings"].sum()
    torus = np.abs(e["piece"]) == 1
    # On the torus copies the height of the body's axis, Gamma_3 = cos q2, is stationary: the
    # body's gamma and the Cardan angles agree.
    assert np.allclose(e["gamma"][:, 2], np.cos(e["cardan_angles"][:, 1]), atol=1e-12)
    assert np.allclose(np.mod(e["cardan_angles"][torus, 1], 2 * np.pi), e["y"][torus], atol=1e-12)
    plot = subprocess.run(["/usr/bin/python3", os.path.join(ROOT, "scripts", "plots", "poincare.py"),
                           "--out", str(tmp_path), str(tmp_path / "one.h5")],
                          capture_output=True, text=True, timeout=300)
    assert plot.returncode == 0, plot.stderr
    assert os.path.getsize(tmp_path / "poincare_one.png") > 10000


def test_cardan_refusals(tmp_path):
    refused(lgi("equilibria", "--scene", HORIZONTAL, "--l", "1", "--out", str(tmp_path / "x.h5"), check=False),
            "tilt", "vertical")
    base = ["poincare", "--scene", UPRIGHT, "--l", "1", "--ics", "1", "--t-end", "1", "--out", str(tmp_path / "p.h5")]
    refused(lgi(*base, "--h", "-1000", check=False), "--h", "minimum energy")
    refused(lgi(*base, "--h", "0", "--axis", "e1", check=False), "--axis")
    refused(lgi(*base, "--h", "0", "--section", "gamma", check=False), "--section")
    refused(lgi(*base, "--h", "0", "--scheme", "rkmk4", check=False), "--scheme")
    refused(lgi(*base, "--h", "0", "--scheme", "cardan-dp54", check=False), "--scheme")
    refused(lgi("work-precision", "--scene", UPRIGHT, "--schemes", "rkmk4", "--dt", "0.01", "--out",
                str(tmp_path / "w.h5"), check=False), "[suspension]", "work-precision")
    refused(lgi("equilibria", "--scene", GENERAL, "--l", "1", "--omega-max", "2", "--out", str(tmp_path / "y.h5"),
                check=False), "--omega-max")
