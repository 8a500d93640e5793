"""The window and colour options of the atlas figure scripts (issue 49): --l-range,
--h-range and --l-nonneg on bifurcation.py, region.py and the Appelrot figure; the
default window of the (l, h) diagram frames the folds and class changes; the arcs of
the Appelrot families are kept only where (h, k) is attained; poincare.py --colour
direction and the accessible-region boundary; a bad range is refused by argparse."""
import subprocess
import sys

import h5py
import numpy as np
from script_env import ENV, LGI, PLOTS, SCENES, lgi

sys.path.insert(0, str(PLOTS))

import bifurcation  # noqa: E402
import lgi_plot_common  # noqa: E402


def plot(script, out, *args, code=0):
    r = subprocess.run(["/usr/bin/python3", str(PLOTS / script), "--out", str(out), *map(str, args)], env=ENV,
                       capture_output=True, text=True)
    assert r.returncode == code, r.stderr
    return r


def written(out, name):
    return all((out / f"{name}.{ext}").stat().st_size > 1000 for ext in ("pdf", "png"))


def test_bifurcation_window_labels_and_class_changes(tmp_path):
    path = tmp_path / "general.h5"
    lgi("bifurcation", "--scene", SCENES / "general_top_richter.toml", "--samples", "150", "--out", path)
    with h5py.File(path, "r") as f:
        t = {k: np.asarray(f["equilibria"][k][()]) for k in f["equilibria"]}
        labels = bifurcation.branch_labels(f)
    assert t["class_change"].sum() >= 2 and t["fold"].sum() >= 2
    assert {"hanging", "upright"} <= {end for v in labels.values() for end in v.split(" - ")}
    args = lgi_plot_common.add_plane_options(lgi_plot_common.parser("x"), k_range=True).parse_args(["--out", str(tmp_path)])
    l0, l1, h0, h1 = bifurcation.default_window(t, args)
    marks = (t["fold"] == 1) | (t["class_change"] == 1)
    # Every fold and class change in view, and the window not the whole branch (the cusps framed).
    assert l0 < t["l"][marks].min() and t["l"][marks].max() < l1
    assert h0 < t["h"][marks].min() and t["h"][marks].max() < h1
    assert l1 < 0.5 * np.abs(t["l"]).max()
    args = lgi_plot_common.add_plane_options(lgi_plot_common.parser("x")).parse_args(
        ["--out", str(tmp_path), "--l-nonneg"])
    assert bifurcation.default_window(t, args)[0] == 0.0
    out = tmp_path / "fig"
    plot("bifurcation.py", out, "--l-range", "0:4", "--h-range=-1:3", path)
    assert written(out, "bifurcation_general")
    r = plot("bifurcation.py", out / "c", "--l-range", "3:1", path, code=2)
    assert "--l-range" in r.stderr


def test_appelrot_arcs_only_where_attained(tmp_path):
    # A range k in [0, 1] for h in [0, 2]: a point at k = 1 is on its edge, k = 0.5 inside, k = 3 outside.
    h = np.array([0.5, 1.0, 1.0, 1.5, 3.0])
    k = np.array([1.0, 0.5, 3.0, 0.0, 0.5])
    rng_h = np.linspace(0, 2, 5)
    where = bifurcation.attained(h, k, rng_h, np.zeros(5), np.ones(5), np.zeros(5, dtype=int))
    assert list(where) == [2, 1, 0, 2, 0]
    kov = tmp_path / "kov.h5"
    lgi("bifurcation", "--scene", SCENES / "kovalevskaya.toml", "--samples", "60", "--appelrot", "-1,0,1",
        "--appelrot-h", "-1:3:9", "--out", kov)
    out = tmp_path / "fig"
    plot("bifurcation.py", out, "--l-nonneg", "--h-range=-1:3", "--k-range=-0.2:5", kov)
    assert written(out, "appelrot_kov")
    r = plot("bifurcation.py", out / "x", "--l-range", "5:6", kov, code=2)
    assert "no value of l" in r.stderr


def test_appelrot_chambers():
    # A range 0 < k < 4 for h in [0, 4], cut by a realised wall k = 2 on h in [0, 4] with a hole
    # (not realised) for h in [1.5, 2.5]: one chamber; with the hole filled: two.
    rng = {"l": np.zeros(9), "h_scaled": np.linspace(0, 4, 9), "k_min": np.zeros(9), "k_max": np.full(9, 4.0),
           "component": np.zeros(9, dtype=int)}
    r = rng["l"] == 0
    h = np.linspace(0, 4, 81)
    k = np.full(81, 2.0)
    hole = np.where((h > 1.5) & (h < 2.5), np.nan, k)
    _, count, _, _ = bifurcation.chamber_map([(h, hole)], rng, r, (0, 4), (0, 4))
    assert count == 1
    labels, count, hs, ks = bifurcation.chamber_map([(h, k)], rng, r, (0, 4), (0, 4))
    assert count == 2
    assert labels[np.searchsorted(ks, 1.0), 120] != labels[np.searchsorted(ks, 3.0), 120]


def test_region_cells_window(tmp_path):
    cells = tmp_path / "cells.h5"
    lgi("region", "--scene", SCENES / "lagrange_top_oblate.toml", "--cells", "--l-range", "-1:3:9", "--h-range",
        "-1.2:3:9", "--grid", "40", "--samples", "60", "--out", cells)
    out = tmp_path / "fig"
    plot("region.py", out, "--l-nonneg", "--h-range=-1:2.5", cells)
    assert written(out, "region_cells_cells")


def test_poincare_direction_colour_and_cardan_titles(tmp_path):
    kov = tmp_path / "kov.h5"
    lgi("poincare", "--scene", SCENES / "kovalevskaya.toml", "--l", "1", "--h", "2", "--ics", "3", "--t-end", "30",
        "--out", kov)
    out = tmp_path / "fig"
    plot("poincare.py", out, "--colour", "direction", kov)
    assert written(out, "poincare_kov")
    car = tmp_path / "car.h5"
    subprocess.run([str(LGI), "poincare", "--scene", str(SCENES / "cardan_lagrange_horizontal.toml"), "--l", "10",
                    "--h", "204", "--ics", "1", "--t-end", "2", "--dt", "0.001", "--out", str(car), "--quiet"],
                   check=True, capture_output=True)
    with h5py.File(car, "r") as f:
        assert f["parameters"].attrs["p1_conserved"] in (b"no", "no")
        assert np.all(np.isnan(f["sweep"]["max_cardan_momentum_1_error"][()]))
    plot("poincare.py", out, "--colour", "direction", car)
    assert written(out, "poincare_car")


def test_numbers_in_titles_have_six_digits():
    assert lgi_plot_common.num(2.2000000000000002) == "2.2"
    assert lgi_plot_common.num(1 / 3) == "0.333333"
