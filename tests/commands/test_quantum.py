"""`lgi quantum` as a user runs it (experiments/QUANTUM.md):
 - a free asymmetric rotor: every level of every j = |m|..jmax, 2j+1 per j,
   the contract's /spectrum columns, j per level, the D2 classes, all
   converged; the CSV beside it holds the same numbers;
 - the harmonic limit through the command line: Richter's general top at
   m = 0, (E0 - min U)/hbar against (w_a + w_b)/2 from `lgi equilibria --l 0`
   (Grammel's g1, g2 of the hanging equilibrium): within 5% at hbar = 0.01,
   the deviation about halving from hbar = 0.02;
 - a Lagrange top: k conserved, written per level;
 - bad input: one line on stderr and exit 2 (a spring, a bad flag)."""
import csv
import math
import os

import h5py
import numpy as np
from lgi_cli import lgi, refused, table

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
COLUMNS = ["index", "energy", "j", "m", "k", "parity", "converged", "change_with_jmax"]


def test_free_rotor_every_level_of_every_j(tmp_path):
    out = str(tmp_path / "free.h5")
    lgi("quantum", "--scene", os.path.join(SCENES, "free_body_hlw.toml"), "--hbar", "1", "--m", "2",
        "--jmax", "6", "--out", out)
    t, p = table(out, "spectrum")
    for c in COLUMNS:
        assert c in t, c
    assert len(t["energy"]) == sum(2 * j + 1 for j in range(2, 7))
    for j in range(2, 7):
        assert np.count_nonzero(t["j"] == j) == 2 * j + 1
    assert np.all(t["m"] == 2) and np.all(t["k"] == -1) and np.all(t["converged"] == 1)
    assert set(t["parity"]) == {0, 1, 2, 3}
    assert "D2" in p["parity_classes"]
    # j = 2 of the HLW body (I = 2, 1, 2/3): the three levels of Wang's B blocks are
    # hbar^2 [j(j+1)/2 (sum of two 1/(2I)) + ...]; check one closed form: 1/(2I1) + 1/(2I2) + 4/(2I3) = 3.75.
    assert np.isclose(t["energy"][t["j"] == 2], 3.75).any()
    with open(out[:-3] + ".csv") as f:
        rows = list(csv.DictReader(f))
    assert [float(r["energy"]) for r in rows] == list(t["energy"])


def test_harmonic_limit_through_the_command_line(tmp_path):
    scene = os.path.join(SCENES, "general_top_richter.toml")
    eq = str(tmp_path / "eq.h5")
    lgi("equilibria", "--scene", scene, "--l", "0", "--out", eq, "--quiet")
    e, _ = table(eq, "equilibria")
    i = int(np.argmin(e["h"]))
    target = 0.5 * math.sqrt(e["g1"][i] + 2 * math.sqrt(e["g2"][i]))
    u_min = e["h"][i]
    dev = {}
    for hbar, jmax in ((0.02, 40), (0.01, 60)):
        out = str(tmp_path / f"q{hbar}.h5")
        lgi("quantum", "--scene", scene, "--hbar", str(hbar), "--jmax", str(jmax), "--levels", "2",
            "--out", out, "--quiet")
        t, p = table(out, "spectrum")
        assert t["converged"][0] == 1 and p["representation"] == "complex hermitian"
        dev[hbar] = (t["energy"][0] - u_min) / hbar / target - 1
    assert abs(dev[0.01]) <= 0.05
    assert abs(dev[0.01] / dev[0.02] - 0.5) <= 0.05, dev


def test_lagrange_top_writes_k(tmp_path):
    out = str(tmp_path / "lagrange.h5")
    lgi("quantum", "--scene", os.path.join(SCENES, "lagrange_top_cigar.toml"), "--hbar", "0.1", "--m", "1",
        "--jmax", "16", "--levels", "12", "--out", out)
    t, p = table(out, "spectrum")
    assert len(t["energy"]) == 12 and np.all(np.diff(t["energy"]) >= 0)
    assert np.all(t["k_conserved"] == 1) and np.all(t["j"] == -1)
    assert len(set(t["k"])) > 1
    assert np.all(t["change_with_jmax"] <= 1e-12)  # the cut is variational


def test_bad_input_is_refused(tmp_path):
    out = str(tmp_path / "x.h5")
    line = refused("quantum", "--scene", os.path.join(SCENES, "stiff_damped_spring.toml"), "--hbar", "1",
                   "--out", out)
    assert "[spring]" in line
    free = os.path.join(SCENES, "free_body_hlw.toml")
    assert "--hbar" in refused("quantum", "--scene", free, "--hbar", "0", "--out", out)
    assert "--jmax" in refused("quantum", "--scene", free, "--hbar", "1", "--m", "5", "--jmax", "3", "--out", out)
    assert "--levels" in refused("quantum", "--scene", free, "--hbar", "1", "--levels", "0", "--out", out)
    assert not os.path.exists(out)


def ebk_error(tmp_path, hbar, jmax, m):
    out = str(tmp_path / f"ebk_{hbar}_{m}.h5")
    lgi("quantum", "--scene", os.path.join(SCENES, "lagrange_top_cigar.toml"), "--hbar", str(hbar), "--m", str(m),
        "--jmax", str(jmax), "--levels", "10", "--ebk", "--out", out)
    t, _ = table(out, "ebk")
    s, _ = table(out, "spectrum")
    assert np.all(t["converged"] == 1) and np.all(t["m"] == m)
    assert np.array_equal(t["energy_exact"], s["energy"]) and np.array_equal(t["k"], s["k"])
    assert np.allclose(t["difference"], t["energy_ebk"] - t["energy_exact"], rtol=0, atol=0)
    for k in set(t["k"]):  # n counts the levels of each k block from 0
        assert list(t["n"][t["k"] == k]) == list(range(np.count_nonzero(t["k"] == k)))
    return np.max(np.abs(t["difference"]))


def test_ebk_lagrange_is_second_order(tmp_path):
    # docs/quantum.md section 7: the EBK levels differ from the exact ones by O(hbar^2).
    for m in (0, 2):
        ratio = ebk_error(tmp_path, 0.1, 30, m) / ebk_error(tmp_path, 0.05, 40, m)
        assert 3.6 < ratio < 4.4, ratio


def test_ebk_refused_off_lagrange(tmp_path):
    line = refused("quantum", "--scene", os.path.join(SCENES, "general_top_richter.toml"), "--hbar", "1", "--jmax",
                   "4", "--ebk", "--out", str(tmp_path / "x.h5"))
    assert "--ebk" in line and "general_top_richter.toml" in line


def test_ebk_euler_top(tmp_path):
    # docs/quantum.md section 9: one j of the HLW body; doublets n = 0, 0, 1, 1, ... from either
    # steady rotation, the axis of the largest moment below the separatrix, the smallest above it.
    out = str(tmp_path / "euler.h5")
    lgi("quantum", "--scene", os.path.join(SCENES, "free_body_hlw.toml"), "--hbar", "0.05", "--m", "20", "--jmax",
        "20", "--ebk", "--out", out)
    t, attrs = table(out, "ebk")
    s, _ = table(out, "spectrum")
    assert len(t["n"]) == 41 and np.all(t["j"] == 20) and np.all(t["k"] == -1)
    assert np.array_equal(t["energy_exact"], s["energy"])
    assert list(t["n"][:6]) == [0, 0, 1, 1, 2, 2] and list(t["n"][-6:]) == [2, 2, 1, 1, 0, 0]
    assert len(set(t["axis"][:6])) == 1 and len(set(t["axis"][-6:])) == 1 and t["axis"][0] != t["axis"][-1]
    finite = np.isfinite(t["energy_ebk"])
    assert np.count_nonzero(~finite) <= 3  # only at the separatrix
    # Away from the separatrix (E/|L|^2 = 1/2 here) EBK is within O(hbar^2) of the exact level.
    e = t["energy_exact"] / (0.05 * 20.5) ** 2
    far = finite & (np.abs(e - 0.5) > 0.08)
    assert np.count_nonzero(far) >= 20
    assert np.max(np.abs(t["difference"][far] / t["energy_exact"][far])) < 3e-3


def test_statistics_of_the_free_asymmetric_rotor(tmp_path):
    # One j (m = jmax = 80), its four D2 classes: the Manfredi-Salasnich anomaly,
    # near a picket fence (Brody fit at its bound 1, Delta_3 far below Poisson).
    out = str(tmp_path / "stat.h5")
    lgi("quantum", "--scene", os.path.join(SCENES, "free_body_hlw.toml"), "--hbar", "1", "--m", "80", "--jmax", "80",
        "--statistics", "--out", out)
    t, _ = table(out, "statistics")
    assert list(t["j"]) == [80] * 4 and list(t["parity"]) == [0, 1, 2, 3]
    assert sum(t["levels"]) == 161
    assert np.all(t["brody_bound"] == 1) and np.all(t["brody_beta"] == 1.0)
    n_bins, n_lengths = len(t["bin_centre"]), len(t["length"])
    assert t["spacing_density"].shape == (4, n_bins) and t["rigidity"].shape == (4, n_lengths)
    # Delta_3 follows Poisson's L/15 at small L and then saturates near the
    # picket fence's 1/12, below both Poisson and GOE.
    far = t["length"] >= 3
    assert np.all(t["rigidity"][:, far] < 0.1) and np.all(t["rigidity"][:, far] < t["goe_rigidity"][far])
    assert np.allclose(t["poisson_rigidity"], t["length"] / 15)
    assert np.all(t["gue_rigidity"][far] < t["goe_rigidity"][far]) and t["gue_density"].shape == (n_bins,)


def test_statistics_of_a_heavy_top(tmp_path):
    # Kovalevskaya's top at m = 1: two classes (parity of k), each unfolded by Weyl's law/2.
    out = str(tmp_path / "kov.h5")
    lgi("quantum", "--scene", os.path.join(SCENES, "kovalevskaya.toml"), "--hbar", "0.2", "--m", "1",
        "--jmax", "20", "--levels", "60", "--statistics", "--out", out)
    t, _ = table(out, "statistics")
    s, _ = table(out, "spectrum")
    assert list(t["parity"]) == [0, 1] and list(t["j"]) == [-1, -1]
    assert sum(t["levels"]) == np.count_nonzero(s["converged"] == 1)
    assert np.all((t["brody_beta"] >= 0) & (t["brody_beta"] <= 1)) and np.all(t["brody_error"] > 0)
    # Weyl's law follows the staircase of all converged levels to a few levels.
    w, _ = table(out, "weyl")
    ok = s["converged"] == 1
    staircase = np.arange(np.count_nonzero(ok)) + 0.5
    assert np.max(np.abs(w["weyl_count"][ok] - staircase)) < 5


def test_statistics_in_an_energy_window(tmp_path):
    # --energy-window LO:HI: only the converged levels in [LO, HI] enter /statistics; the
    # attributes state the window and the Brody fit of all classes' spacings pooled.
    out = str(tmp_path / "win.h5")
    lgi("quantum", "--scene", os.path.join(SCENES, "kovalevskaya.toml"), "--hbar", "0.2", "--m", "1",
        "--jmax", "20", "--levels", "60", "--statistics", "--energy-window", "0:1.5", "--out", out)
    t, _ = table(out, "statistics")
    s, _ = table(out, "spectrum")
    inside = (s["converged"] == 1) & (s["energy"] >= 0) & (s["energy"] <= 1.5)
    assert 10 < sum(t["levels"]) == np.count_nonzero(inside) < len(s["energy"])
    with h5py.File(out, "r") as f:
        a = {k: (v.decode() if isinstance(v, bytes) else str(v)) for k, v in f["statistics"].attrs.items()}
    assert float(a["energy_low"]) == 0 and float(a["energy_high"]) == 1.5
    assert int(a["pooled_spacings"]) == sum(t["levels"]) - len(t["levels"])
    assert 0 <= float(a["pooled_brody_beta"]) <= 1 and float(a["pooled_brody_error"]) > 0
    scene = os.path.join(SCENES, "kovalevskaya.toml")
    for flags, word in ((["--energy-window", "0:1"], "--statistics"),
                        (["--statistics", "--energy-window", "2:1"], "LO < HI"),
                        (["--statistics", "--energy-window", "0:x"], "LO:HI")):
        line = refused("quantum", "--scene", scene, "--hbar", "0.2", "--jmax", "6", *flags,
                       "--out", str(tmp_path / "x.h5"))
        assert "--energy-window" in line and word in line, line
