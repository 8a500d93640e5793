"""`lgi indicators --gali` as a user runs it (experiments/INDICATORS.md, "GALI"):
 - /indicators gains log10_gali_2 .. log10_gali_6 (the values at T, also in the
   CSV) and /gali holds the curves: index, t, log10_gali (rows x 5), one row per
   (state, sample time), the same times for every state, T last;
 - the file is the same on 1 and 2 threads (several states of a state file);
 - a Cardan scene: lyapunov, megno, the spectrum and GALI from the torus
   tangent flow, its state in cardan_angles and cardan_momenta;
 - bad input (a bad --gali-spacing or --gali-samples, a state file or rkmk4
   with a Cardan scene): one line on stderr and exit 2."""
import os

import h5py
import numpy as np
from lgi_cli import lgi, refused, table

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
GENERAL = os.path.join(SCENES, "general_top_richter.toml")
CARDAN = os.path.join(SCENES, "cardan_euler_tilted.toml")
GALI = ["log10_gali_%d" % k for k in range(2, 7)]


def gali_group(path):
    with h5py.File(path, "r") as f:
        return {k: f["gali"][k][()] for k in f["gali"]}, dict(f["gali"].attrs)


def test_gali_layout_and_threads(tmp_path):
    eq = str(tmp_path / "eq.h5")
    lgi("equilibria", "--scene", GENERAL, "--l", "3", "--out", eq, "--quiet")
    outs = []
    for threads in ("1", "2"):
        out = str(tmp_path / ("g%s.h5" % threads))
        lgi("indicators", "--scene", GENERAL, "--state-file", eq, "--t-end", "20", "--dt", "0.01", "--gali",
            "--gali-samples", "30", "--threads", threads, "--out", out, "--quiet")
        outs.append(out)
    d, p = table(outs[0], "indicators")
    g, attrs = gali_group(outs[0])
    n = len(d["index"])
    assert n >= 4 and p["gali"] == "yes" and p["gali_samples"] == "30" and p["gali_spacing"] == "log"
    for c in GALI:
        assert d[c].shape == (n,) and np.all(np.isfinite(d[c])), c
    rows = len(g["index"])
    assert rows % n == 0 and g["log10_gali"].shape == (rows, 5) and g["t"].shape == (rows,)
    m = rows // n
    assert 1 < m <= 30 and attrs["times_per_state"] == str(m) and attrs["spacing"] == "log"
    assert np.array_equal(g["index"], np.repeat(np.arange(n), m))
    t = g["t"].reshape(n, m)
    assert np.all(t == t[0]) and t[0, -1] == 20.0 and np.all(np.diff(t[0]) > 0)
    curves = g["log10_gali"].reshape(n, m, 5)
    for k, c in enumerate(GALI):
        assert np.array_equal(curves[:, -1, k], d[c]), c
    assert np.all(curves[:, :, 0] <= 1e-12)  # a volume of unit vectors is at most 1
    with open(str(tmp_path / "g1.csv")) as f:
        header = f.readline().strip().split(",")
    assert header[-5:] == GALI
    # 1 and 2 threads: the same numbers to the bit.
    d2, _ = table(outs[1], "indicators")
    g2, _ = gali_group(outs[1])
    for c in ["lyapunov", "megno"] + GALI:
        assert np.array_equal(d[c], d2[c]), c
    for c in g:
        assert np.array_equal(g[c], g2[c]), c


def test_cardan_scene(tmp_path):
    out = str(tmp_path / "c.h5")
    r = lgi("indicators", "--scene", CARDAN, "--t-end", "30", "--gali", "--gali-spacing", "linear",
            "--gali-samples", "10", "--spectrum", "--out", out)
    assert "log10_gali_2..6=" in r.stdout
    d, p = table(out, "indicators")
    g, _ = gali_group(out)
    assert p["scheme"] == "cardan-rk4" and "cardan_tangent_kernel" in p["indicators"]
    assert d["cardan_angles"].shape == (1, 3) and d["cardan_momenta"].shape == (1, 3)
    assert np.array_equal(d["cardan_angles"][0], [0.0, 1.0, 0.0])
    assert d["lyapunov"][0] > 0.2 and d["megno"][0] > 4  # the tilted Euler top's chaos (docs/cardan.md §9)
    assert abs(d["spectrum"][0].sum()) < 1e-6
    assert np.allclose(g["t"], np.arange(1, 11) * 3.0, rtol=0, atol=1e-9)
    assert d["log10_gali_2"][0] < -2.0


def test_bad_gali_input(tmp_path):
    out = str(tmp_path / "x.h5")
    assert "--gali-spacing" in refused("indicators", "--scene", GENERAL, "--gali", "--gali-spacing", "cubic",
                                       "--out", out)
    assert "--gali-samples" in refused("indicators", "--scene", GENERAL, "--gali", "--gali-samples", "0",
                                       "--out", out)
    assert "--state-file" in refused("indicators", "--scene", CARDAN, "--state-file", GENERAL, "--out", out)
    assert "--scheme" in refused("indicators", "--scene", CARDAN, "--scheme", "rkmk4", "--out", out)
    assert not os.path.exists(out)
