"""The atlas bindings lgi.equilibria, lgi.bifurcation, lgi.region,
lgi.region_cells and lgi.poincare against the files of the commands
`lgi equilibria`, `lgi bifurcation`, `lgi region` and `lgi poincare` on small
cases (CTest python_module): the same columns, bit for bit, and the same
messages for bad input."""
import os
import subprocess

import h5py
import numpy as np
import pytest

import lgi

from conftest import SCENES

RICHTER = os.path.join(SCENES, "general_top_richter.toml")
KOVALEVSKAYA = os.path.join(SCENES, "kovalevskaya.toml")


def run_cli(exe, *args):
    r = subprocess.run([exe, *args, "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r


def group(f, name):
    return {k: f[name][k][()] for k in f[name]}


def text(value):
    return value.decode() if isinstance(value, bytes) else str(value)


def assert_same_columns(got, ref, skip=()):
    """Every column of the file's group is in the dict, equal bit for bit (NaN where NaN)."""
    for name, values in ref.items():
        if name in skip:
            continue
        assert name in got, name
        assert got[name].shape == values.shape, name
        if values.dtype.kind == "S":  # fixed-length text: h5py gives bytes, the module str
            assert list(got[name]) == [v.decode() for v in values], name
            continue
        # the module's integers are int64 (the file has some int32 columns: direction, event)
        assert got[name].dtype == (np.int64 if values.dtype.kind == "i" else values.dtype), name
        assert np.array_equal(got[name], values, equal_nan=values.dtype.kind == "f"), name


def test_equilibria_matches_cli(lgi_exe, tmp_path):
    path = str(tmp_path / "eq.h5")
    run_cli(lgi_exe, "equilibria", "--scene", RICHTER, "--l", "3", "--out", path)
    got = lgi.equilibria(RICHTER, 3.0)
    with h5py.File(path, "r") as f:
        ref = group(f, "/equilibria")
        branches = text(f["/parameters"].attrs["branches"])
    assert len(got["h"]) in (2, 4, 6)
    assert_same_columns(got, ref)
    assert "".join(f"{k}: {v}\n" for k, v in got["branches"].items()) == branches
    assert set(got["stability"]) >= {0, 1}  # stable and singly unstable rotations at l = 3


def test_bifurcation_matches_cli(lgi_exe, tmp_path):
    path = str(tmp_path / "bif.h5")
    run_cli(lgi_exe, "bifurcation", "--scene", RICHTER, "--samples", "40", "--out", path)
    got = lgi.bifurcation(lgi.Scene.from_file(RICHTER), samples=40)
    with h5py.File(path, "r") as f:
        assert_same_columns(got, group(f, "/equilibria"))
    assert got["fold"].sum() >= 1


def test_bifurcation_appelrot_matches_cli(lgi_exe, tmp_path):
    path = str(tmp_path / "kov.h5")
    run_cli(lgi_exe, "bifurcation", "--scene", KOVALEVSKAYA, "--samples", "20", "--appelrot", "1",
            "--appelrot-h", "0:2:3", "--out", path)
    got = lgi.bifurcation(KOVALEVSKAYA, samples=20, appelrot=[1.0], appelrot_h="0:2:3")
    with h5py.File(path, "r") as f:
        for name in ("appelrot", "appelrot_equilibria", "appelrot_range", "appelrot_critical", "appelrot_regions"):
            assert_same_columns(got[name], group(f, "/" + name))
            for key, value in f["/" + name].attrs.items():
                assert got[name][key] == text(value), (name, key)
    with pytest.raises(ValueError, match="is not a Kovalevskaya top"):
        lgi.bifurcation(RICHTER, samples=20, appelrot=[1.0])


def test_region_matches_cli(lgi_exe, tmp_path):
    path = str(tmp_path / "region.h5")
    run_cli(lgi_exe, "region", "--scene", RICHTER, "--l", "2", "--h", "2.2", "--grid", "40", "--out", path)
    got = lgi.region(RICHTER, 2.0, 2.2, grid=40)
    with h5py.File(path, "r") as f:
        for name in ("potential", "critical_points", "components"):
            assert_same_columns(got[name], group(f, "/" + name))
        assert got["components"]["topology"] == text(f["/components"].attrs["topology"]).split("\n")
        p = f["/parameters"].attrs
        assert got["topology"] == text(p["topology"])
        assert got["resolved"] == (text(p["resolved"]) == "yes")
        assert got["u_constant"] == (text(p["u_constant"]) == "yes")
    assert got["potential"]["U"].shape == (41, 80)


def test_region_cells_matches_cli(lgi_exe, tmp_path):
    path = str(tmp_path / "cells.h5")
    run_cli(lgi_exe, "region", "--scene", RICHTER, "--cells", "--l-range", "0:3:4", "--h-range", "-1:3:5",
            "--grid", "24", "--samples", "20", "--out", path)
    got = lgi.region_cells(RICHTER, (0, 3, 4), "-1:3:5", grid=24, samples=20)
    with h5py.File(path, "r") as f:
        assert_same_columns(got["cells"], group(f, "/cells"))
        assert_same_columns(got["equilibria"], group(f, "/equilibria"))
        assert got["cells"]["topology_names"] == text(f["/cells"].attrs["topology_names"]).split("\n")
    assert got["cells"]["topology"].shape == (4, 5)
    assert got["unresolved"] == int((got["cells"]["resolved"] == 0).sum())


POINCARE_FLAGS = dict(l=1.0, h=2.5, ics=3, t_end=40.0, dt=0.01, seed=7)


@pytest.fixture(scope="module")
def cli_poincare(lgi_exe, tmp_path_factory):
    path = str(tmp_path_factory.mktemp("poincare") / "p.h5")
    p = POINCARE_FLAGS
    run_cli(lgi_exe, "poincare", "--scene", RICHTER, "--l", str(p["l"]), "--h", str(p["h"]), "--ics", str(p["ics"]),
            "--t-end", str(p["t_end"]), "--dt", str(p["dt"]), "--seed", str(p["seed"]), "--megno", "--lyapunov",
            "--threads", "1", "--out", path)
    return path


def compare_poincare(got, path):
    timing = {"cpu_seconds"}
    with h5py.File(path, "r") as f:
        assert_same_columns(got["events"], group(f, "/events"))
        assert_same_columns(got["sweep"], group(f, "/sweep"), skip=timing)
        for key in ("l", "h", "dt", "t_end", "seed", "axis_1", "axis_2", "axis_3"):
            assert got["parameters"][key] == f["/parameters"].attrs[key], key


def test_poincare_matches_cli(cli_poincare):
    got = lgi.poincare(RICHTER, megno=True, lyapunov=True, threads=2, **POINCARE_FLAGS)
    compare_poincare(got, cli_poincare)
    assert len(got["sweep"]["megno"]) == 3 and np.all(np.isfinite(got["sweep"]["lyapunov"]))
    assert len(got["events"]["t"]) > 10 and set(np.unique(got["events"]["sheet"])) <= {-1, 1}
    assert got["out"] is None


def test_poincare_scene_object_and_out(cli_poincare, tmp_path):
    """An lgi.Scene without a file (its TOML written to a temporary file) gives the same section;
    out= keeps the file."""
    text_ = open(RICHTER).read()
    scene = lgi.Scene.from_toml(text_, name="richter-in-memory")
    out = str(tmp_path / "kept.h5")
    got = lgi.poincare(scene, megno=True, lyapunov=True, out=out, **POINCARE_FLAGS)
    compare_poincare(got, cli_poincare)
    assert got["out"] == out and os.path.exists(out)
    with pytest.raises(OSError, match="exists"):  # python/README.md: an output that exists is an OSError
        lgi.poincare(scene, out=out, **POINCARE_FLAGS)


def test_atlas_messages_match_cli(lgi_exe, tmp_path):
    r = subprocess.run([lgi_exe, "region", "--scene", RICHTER, "--l", "1", "--h", "-5", "--quiet", "--out",
                        str(tmp_path / "r.h5")],
                       capture_output=True, text=True)
    assert r.returncode == 2
    with pytest.raises(ValueError) as e:
        lgi.region(RICHTER, 1.0, -5.0)
    assert str(e.value) == r.stderr.strip()[len("lgi: "):]
    with pytest.raises(ValueError, match="h is below the minimum energy"):
        lgi.poincare(RICHTER, 1.0, -5.0, 2, 10.0)
    spring = lgi.Scene(name="spring", body={"inertia": [1, 2, 3]}, spring={"stiffness": 1.0, "damping": 0.0})
    for call in (lambda: lgi.equilibria(spring, 1.0), lambda: lgi.region(spring, 1.0, 1.0)):
        with pytest.raises(ValueError, match="needs a heavy top"):
            call()
    with pytest.raises(ValueError, match="--grid"):
        lgi.region(RICHTER, 1.0, 2.0, grid=4)
