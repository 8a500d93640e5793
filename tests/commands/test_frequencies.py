"""`lgi frequencies` as a user runs it (experiments/FREQUENCIES.md):
 - the contract's layout (/frequencies/<column>, one row per observable and
   term, with the observable's diffusion index; /frequency_diffusion, one row per observable) and the CSV beside it;
 - on the free body, the leading frequency of Pi_1 and Pi_2 is 2 pi / T with
   T = 4K(k)/lambda (Landau & Lifshitz §37, scipy's ellipk) to 1e-10, the
   same for both, and the diffusion index of a torus is tiny;
 - a complex pair A+iB: signed frequencies, the sign flipped with the order;
 - bad input (an unknown observable, a flag out of range, a scheme that cannot
   run the scene, an observable or --state-file of the other kind of scene): one
   line on stderr and exit 2;
 - a Cardan top (T^3 x R^3): on the invariant set q2 = 0 of an upright, gravity-free
   symmetric body q1 and q3 turn uniformly, and NAFF gives their rates; --state-file
   rows (an lgi indicators file, lgi chaos-map's /orbits) give the records of the
   scene's own run bit for bit, one `index` per state, the same on 1 and 2 threads."""
import math
import os

import h5py
import numpy as np
from lgi_cli import lgi, refused
from scipy.special import ellipk

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
FREE = os.path.join(SCENES, "free_body_hlw.toml")
LAGRANGE = os.path.join(SCENES, "lagrange_top_cigar.toml")


def free_body_frequency(moments, pi):
    """HLW's body circulates about its smallest moment (axis 3): 2 pi lambda / 4K(k)."""
    e2 = sum(p * p / i for p, i in zip(pi, moments))
    g2 = sum(p * p for p in pi)
    i1, i2, i3 = sorted(moments)
    assert g2 < e2 * i2
    i1, i3 = i3, i1
    lam = math.sqrt((i3 - i2) * (g2 - e2 * i1) / (i1 * i2 * i3))
    k2 = (i2 - i1) * (e2 * i3 - g2) / ((i3 - i2) * (g2 - e2 * i1))
    return 2 * math.pi * lam / (4 * ellipk(k2))


def table(path, name):
    """The datasets of group /name and /parameters."""
    with h5py.File(path, "r") as f:
        g = f[name]
        return {k: g[k][()] for k in g if isinstance(g[k], h5py.Dataset)}, dict(f["parameters"].attrs)


def test_layout_and_free_body(tmp_path):
    out = str(tmp_path / "fb.h5")
    r = lgi("frequencies", "--scene", FREE, "--t-end", "600", "--scheme", "exact", "--dt", "0.02",
            "--window-order", "2", "--terms", "3", "--observable", "angular_momentum_1,angular_momentum_2,gamma_3",
            "--out", out)
    assert "wrote" in r.stdout
    d, p = table(out, "frequencies")
    assert {"observable", "term", "frequency", "amplitude", "phase"} <= set(d)
    names = [s.decode() for s in d["observable"]]
    assert names[:3] == ["angular_momentum_1"] * 3 and len(names) == 9
    assert d["term"].dtype == np.int64 and d["term"].tolist()[:3] == [0, 1, 2]
    assert np.all(np.diff(d["amplitude"][:3]) <= 0)
    assert p["subcommand"] == "frequencies" and p["scheme"] == "exact" and p["window_order"] == "2"
    exact = free_body_frequency([2.0, 1.0, 2.0 / 3.0], [math.cos(1.1), 0.0, math.sin(1.1)])
    for i in (0, 3):
        assert abs(d["frequency"][i] - exact) <= 1e-10 * exact, (d["frequency"][i], exact)
    diff, _ = table(out, "frequency_diffusion")
    assert [s.decode() for s in diff["observable"]] == ["angular_momentum_1", "angular_momentum_2", "gamma_3"]
    for c in ("frequency", "frequency_first_half", "frequency_second_half", "relative_change",
              "log10_relative_change"):
        assert diff[c].shape == (3,), c
    assert diff["log10_relative_change"][0] < -9
    assert np.all(d["diffusion"][:3] == diff["log10_relative_change"][0])  # the contract's /frequencies/diffusion
    with open(str(tmp_path / "fb.csv")) as f:
        assert f.readline().strip().split(",")[:5] == ["observable", "term", "frequency", "amplitude", "phase"]


def test_default_observables_and_threads(tmp_path):
    """All nine observables by default; the records do not depend on --threads."""
    runs = []
    for threads in ("1", "2"):
        out = str(tmp_path / f"lt{threads}.h5")
        lgi("frequencies", "--scene", LAGRANGE, "--t-end", "50", "--terms", "2", "--threads", threads, "--out", out,
            "--quiet")
        runs.append((table(out, "frequencies")[0], table(out, "frequency_diffusion")))
    (d1, (diff, p)), (d2, (diff2, _)) = runs
    assert len(diff["observable"]) == 9 and p["scheme"] == "split-symmetric@kahan-li8" and p["output_dt"] == "0.01"
    for k in ("frequency", "amplitude", "phase"):
        assert np.array_equal(d1[k], d2[k]), k
    assert np.array_equal(diff["relative_change"], diff2["relative_change"], equal_nan=True)


def test_bad_input(tmp_path):
    out = str(tmp_path / "x.h5")
    assert "--observable" in refused("frequencies", "--scene", FREE, "--t-end", "10", "--observable", "energy",
                                     "--out", out)
    assert "--terms" in refused("frequencies", "--scene", FREE, "--t-end", "10", "--terms", "0", "--out", out)
    assert "--window-order" in refused("frequencies", "--scene", FREE, "--t-end", "10", "--window-order", "-1",
                                       "--out", out)
    assert "--t-end" in refused("frequencies", "--scene", FREE, "--t-end", "0.05", "--out", out)
    assert "--output-dt" in refused("frequencies", "--scene", FREE, "--t-end", "10", "--output-dt", "0.015",
                                    "--out", out)
    assert "--scheme" in refused("frequencies", "--scene", LAGRANGE, "--t-end", "10", "--scheme", "exact",
                                 "--out", out)
    cardan = os.path.join(SCENES, "cardan_lagrange_upright.toml")
    assert "Cardan" in refused("frequencies", "--scene", FREE, "--t-end", "10", "--observable", "cardan_angle_1",
                               "--out", out)
    assert "--observable" in refused("frequencies", "--scene", cardan, "--t-end", "10", "--observable", "gamma_3",
                                     "--out", out)
    assert "--state-file" in refused("frequencies", "--scene", FREE, "--t-end", "10", "--state-file", cardan,
                                     "--out", out)
    assert "--state-file" not in refused("frequencies", "--scene", cardan, "--t-end", "10", "--state-file",
                                         cardan, "--out", out)  # a TOML file: not HDF5, named
    assert "adaptive" in refused("frequencies", "--scene", cardan, "--t-end", "10", "--scheme", "cardan-dp54",
                                 "--out", out)
    assert "--scheme" in refused("frequencies", "--scene", cardan, "--t-end", "10", "--scheme", "rkmk4", "--out", out)
    assert not os.path.exists(out)


def test_complex_pair(tmp_path):
    """Pi_1 + i Pi_2 on HLW's body: one signed line at -/+ 2 pi / T, its sign flipped with the pair's order."""
    out = str(tmp_path / "c.h5")
    lgi("frequencies", "--scene", FREE, "--t-end", "600", "--scheme", "exact", "--dt", "0.02", "--window-order", "2",
        "--terms", "2", "--observable", "angular_momentum_1+iangular_momentum_2,angular_momentum_2+iangular_momentum_1",
        "--out", out, "--quiet")
    d, _ = table(out, "frequencies")
    exact = free_body_frequency([2.0, 1.0, 2.0 / 3.0], [math.cos(1.1), 0.0, math.sin(1.1)])
    assert abs(abs(d["frequency"][0]) - exact) <= 1e-10 * exact
    assert abs(d["frequency"][2] + d["frequency"][0]) <= 1e-13 * exact
    assert abs(d["amplitude"][2] - d["amplitude"][0]) <= 1e-12 * d["amplitude"][0]
    assert "energy" in refused("frequencies", "--scene", FREE, "--t-end", "10", "--observable", "gamma_1+ienergy",
                               "--out", out)


def cardan_scene(tmp_path, angles, rates):
    """cardan_euler_symmetric_up.toml with another initial state."""
    text = open(os.path.join(SCENES, "cardan_euler_symmetric_up.toml")).read()
    text = text.replace("cardan_angles = [0.0, 1.0, 0.0]", f"cardan_angles = {angles}")
    text = text.replace("cardan_rates = [1.0, 0.7, 3.0]", f"cardan_rates = {rates}")
    path = tmp_path / "cardan.toml"
    path.write_text(text)
    return str(path)


def test_cardan_uniform_rotation(tmp_path):
    """q2 = 0, p2 = 0 is invariant for the upright gravity-free symmetric body: q1 and q3 turn at
    their initial rates, q2 stays 0 (no line), and NAFF's leading lines are those rates."""
    scene = cardan_scene(tmp_path, "[0.0, 0.0, 0.0]", "[0.7, 0.0, 3.0]")
    out = str(tmp_path / "u.h5")
    lgi("frequencies", "--scene", scene, "--t-end", "100", "--dt", "0.01", "--output-dt", "0.05", "--window-order",
        "2", "--terms", "2", "--observable", "sin_cardan_angle_1,cardan_angle_2,cos_cardan_angle_3+isin_cardan_angle_3",
        "--out", out, "--quiet")
    d, p = table(out, "frequencies")
    names = [s.decode() for s in d["observable"]]
    assert p["scheme"] == "cardan-rk4" and p["state_count"] == "1" and "cardan_angle_2" not in names
    assert abs(d["frequency"][names.index("sin_cardan_angle_1")] - 0.7) <= 1e-10
    assert abs(d["frequency"][names.index("cos_cardan_angle_3+isin_cardan_angle_3")] - 3.0) <= 3e-10
    assert np.all(d["index"] == 0)


def test_cardan_state_file(tmp_path):
    """Rows of an lgi indicators file (the scene's own state) give the scene's records bit for bit; rows
    of a chaos-map file's /orbits are analysed each, with their index, the same on 1 and 2 threads."""
    scene = os.path.join(SCENES, "cardan_euler_tilted.toml")
    ind, own, rows = (str(tmp_path / n) for n in ("ind.h5", "own.h5", "rows.h5"))
    lgi("indicators", "--scene", scene, "--t-end", "1", "--out", ind, "--quiet")
    lgi("frequencies", "--scene", scene, "--t-end", "20", "--terms", "2", "--out", own, "--quiet")
    lgi("frequencies", "--scene", scene, "--t-end", "20", "--terms", "2", "--state-file", ind, "--out", rows, "--quiet")
    a, b = table(own, "frequencies")[0], table(rows, "frequencies")[0]
    for k in ("frequency", "amplitude", "phase", "diffusion"):
        assert np.array_equal(a[k], b[k], equal_nan=True), k
    cmap = str(tmp_path / "cmap.h5")
    lgi("chaos-map", "--scene", scene, "--vary", "suspension.tilt=0.3:0.3:1", "--h-range", "2:2:1", "--ics", "3",
        "--t-end", "1", "--threads", "1", "--out", cmap, "--quiet")
    runs = []
    for threads in ("1", "2"):
        out = str(tmp_path / f"m{threads}.h5")
        lgi("frequencies", "--scene", scene, "--t-end", "20", "--terms", "2", "--observable",
            "sin_cardan_angle_1,sin_cardan_angle_2", "--state-file", cmap, "--threads", threads, "--out", out,
            "--quiet")
        runs.append(table(out, "frequency_diffusion"))
    (d1, p1), (d2, _) = runs
    assert p1["state_count"] == "3" and d1["index"].tolist() == [0, 0, 1, 1, 2, 2]
    for k in ("frequency", "frequency_first_half", "frequency_second_half"):
        assert np.array_equal(d1[k], d2[k], equal_nan=True), k
