"""lgi.indicators(..., gali=True) (python/README.md, experiments/INDICATORS.md):
the GALI columns and the /gali group of `lgi indicators --gali` bit for bit
(an SO(3) scene's states and a Cardan scene), and the laws it shows: on the
Lagrange top's 3-torus GALI_4 falls as t^-2; on Richter's chaotic orbit
GALI_2 is at the round-off floor by t = 300."""
import os
import subprocess

import h5py
import numpy as np
import pytest

import lgi

from conftest import SCENES

GENERAL = os.path.join(SCENES, "general_top_richter.toml")
LAGRANGE = os.path.join(SCENES, "lagrange_top_cigar.toml")
CARDAN = os.path.join(SCENES, "cardan_euler_tilted.toml")


def read(path):
    with h5py.File(path, "r") as f:
        return ({k: f["indicators"][k][()] for k in f["indicators"]}, {k: f["gali"][k][()] for k in f["gali"]})


@pytest.mark.parametrize("scene,args", [(GENERAL, ["--t-end", "12", "--dt", "0.01", "--seed", "5"]),
                                        (CARDAN, ["--t-end", "5", "--dt", "0.01", "--seed", "5"])])
def test_gali_matches_the_command(lgi_exe, tmp_path, scene, args):
    out = str(tmp_path / "g.h5")
    r = subprocess.run([lgi_exe, "indicators", "--scene", scene, *args, "--gali", "--gali-samples", "20",
                        "--gali-spacing", "linear", "--out", out, "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    cli, cli_gali = read(out)
    t_end = float(args[1])
    mine = lgi.indicators(scene, t_end=t_end, dt=0.01, seed=5, gali=True, gali_samples=20, gali_spacing="linear")
    assert sorted(k for k in mine if k != "gali") == sorted(cli)
    for k in cli:
        assert np.array_equal(mine[k], cli[k], equal_nan=True), k
    for k in cli_gali:
        assert np.array_equal(mine["gali"][k], cli_gali[k]), k


def test_gali_laws():
    d = lgi.indicators(LAGRANGE, t_end=1000, dt=0.01, gali=True)
    g = d["gali"]
    keep = g["t"] >= 50
    slope = np.polyfit(np.log10(g["t"][keep]), g["log10_gali"][keep, 2], 1)[0]
    assert slope == pytest.approx(-2.0, abs=0.25)
    chaos = lgi.indicators(GENERAL, t_end=300, dt=0.01, gali=True)
    assert chaos["log10_gali_2"][0] < -12 and chaos["megno"][0] > 4


def test_gali_bad_arguments():
    with pytest.raises(ValueError, match="gali_spacing"):
        lgi.indicators(GENERAL, t_end=1, gali=True, gali_spacing="cubic")
    with pytest.raises(ValueError, match="gali_samples"):
        lgi.indicators(GENERAL, t_end=1, gali=True, gali_samples=0)
    with pytest.raises(ValueError, match="Cardan"):
        lgi.indicators(CARDAN, t_end=1, states={"angular_momentum": [[0, 0, 1]], "gamma": [[0, 0, 1]]})
