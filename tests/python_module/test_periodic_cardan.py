"""lgi.periodic_orbit and lgi.continue_family on a Cardan top with a vertical
outer axis, as `lgi periodic` (experiments/PERIODIC.md, "Cardan tops"; python/README.md):
 - continue_family from the equilibria and from a seed (q, p, T) gives the
   CLI's /periodic rows on the same scene and options (first orbits only, and a
   seed continued one step, to stay fast), every column
   bit-identical (cardan_angles, cardan_momenta, cardan_drift, monodromy_pieces
   included);
 - periodic_orbit from the seed is the CLI's first orbit of --seed-file
   --steps 0, bit-identical, plus converged, iterations and the monodromy;
 - a tilted frame is refused with the CLI's message naming suspension.tilt
   (ValueError), and so is a seed whose p1 is not l;
 - seeds_from_poincare gives the CLI's rows, and manifolds=N its /manifolds
   on an inverse hyperbolic orbit, bit-identical."""
import os
import subprocess

import h5py
import numpy as np
import pytest

import lgi

from conftest import SCENES

UP = os.path.join(SCENES, "cardan_general_asymmetric_up.toml")
# A point of the l = 1 family of period ~5.752 (lgi periodic --l 1 --from-equilibria --steps 1, row 3).
SEED_Q = [0.0, -2.070674441565095, 1.0488206721882751]
SEED_P = [1.0, 0.1189296496136842, -0.368906383056293]
SEED_T = 5.751996188307288 * 1.01
HORIZONTAL = os.path.join(SCENES, "cardan_general_horizontal.toml")


def cli_rows(exe, tmp_path, name, *args):
    out = str(tmp_path / (name + ".h5"))
    subprocess.run([exe, "periodic", "--scene", UP, "--l", "1", *args, "--out", out, "--quiet"], check=True,
                   capture_output=True, text=True)
    with h5py.File(out, "r") as f:
        g = f["periodic"]
        return {c: g[c][()] for c in g}


def same_columns(py, cli):
    assert set(cli) <= set(py), set(cli) - set(py)
    for c, v in cli.items():
        if v.dtype.kind in "OS":
            assert [x.decode() if isinstance(x, bytes) else x for x in v] == list(py[c]), c
        else:
            np.testing.assert_array_equal(np.asarray(py[c]).reshape(v.shape), v, err_msg=c)


def test_families_as_the_cli(lgi_exe, tmp_path):
    cli = cli_rows(lgi_exe, tmp_path, "eq", "--from-equilibria", "--steps", "0")
    fam = lgi.continue_family(UP, 1.0, steps=0)
    assert len(fam["h"]) == len(cli["h"]) == 4 and fam["failures"] == []
    same_columns(fam, cli)
    # A seed with its period 1 % long.
    q, p, T = SEED_Q, SEED_P, SEED_T
    seeds = tmp_path / "seeds.txt"
    seeds.write_text(" ".join(repr(float(v)) for v in [*q, *p, T]) + "\n")
    cli = cli_rows(lgi_exe, tmp_path, "seed", "--seed-file", str(seeds), "--steps", "1")
    same_columns(lgi.continue_family(UP, 1.0, seed=(q, p, T), steps=1), cli)
    first = cli_rows(lgi_exe, tmp_path, "one", "--seed-file", str(seeds), "--steps", "0")
    one = lgi.periodic_orbit(UP, q, p, T)
    assert one["converged"] and one["monodromy"].shape == (6, 6)
    same_columns({c: v for c, v in one.items() if c not in ("family", "index", "omega", "family_end")},
                 {c: v for c, v in first.items() if c not in ("family", "index", "omega", "family_end")})
    assert one["cardan_drift"].shape == (1,) and one["monodromy_pieces"][0] >= 1


def test_refusals():
    with pytest.raises(ValueError, match="suspension.tilt"):
        lgi.continue_family(HORIZONTAL, 1.0)
    with pytest.raises(ValueError, match="suspension.tilt"):
        lgi.periodic_orbit(HORIZONTAL, [0, 1, 0], [1, 0, 0], 5.0)
    with pytest.raises(ValueError, match="p1"):
        lgi.periodic_orbit(UP, [0, 1, 0], [1, 0, 0], 5.0, l=2.0)
    with pytest.raises(ValueError, match="p1"):
        lgi.continue_family(UP, 2.0, seed=([0, 1, 0], [1, 0, 0], 5.0))


def test_seeds_from_a_cardan_section_as_the_cli(lgi_exe, tmp_path):
    """continue_family(seeds_from_poincare=...) on a Cardan file runs the CLI's code: the same rows,
    bit for bit, section columns included."""
    h = repr(-0.6467150009301119)  # the h of the family of period ~5.745 (SEED_Q, SEED_P's family)
    sec = str(tmp_path / "s.h5")
    subprocess.run([lgi_exe, "poincare", "--scene", UP, "--l", "1", "--h", h, "--ics", "1", "--t-end", "1",
                    "--out", sec, "--quiet"], check=True, capture_output=True)
    point = (1.0334887134167072, 4.4302691254879685, -1)  # that orbit's crossing of dq2/dt = 0
    cli = cli_rows(lgi_exe, tmp_path, "sec", "--seeds-from-poincare", sec, "--poincare-point",
                   "%r,%r,%d" % point, "--steps", "1")
    fam = lgi.continue_family(UP, seeds_from_poincare=sec, poincare_points=[point], steps=1)
    assert len(cli["h"]) == 2 and fam["failures"] == [] and fam["l_file"] == 1.0
    assert (cli["section_sheet"] == -1).all()
    same_columns(fam, cli)


def test_manifolds_of_a_cardan_orbit_as_the_cli(lgi_exe, tmp_path):
    """continue_family(manifolds=N) on a Cardan file gives the CLI's /manifolds, bit for bit (cardan_angles,
    cardan_momenta included), on the inverse hyperbolic orbit of tests/commands/test_periodic_cardan.py
    (test_manifolds_of_an_inverse_hyperbolic_cardan_orbit checks the manifolds themselves)."""
    h = repr(-0.005340203719125776)
    sec, out = str(tmp_path / "s.h5"), str(tmp_path / "m.h5")
    subprocess.run([lgi_exe, "poincare", "--scene", UP, "--l", "1", "--h", h, "--ics", "1", "--t-end", "1",
                    "--out", sec, "--quiet"], check=True, capture_output=True)
    point = (0.9341797680757195, 4.766096729250444, -1)
    subprocess.run([lgi_exe, "periodic", "--scene", UP, "--seeds-from-poincare", sec, "--poincare-point",
                    "%r,%r,%d" % point, "--steps", "0", "--manifolds", "4", "--manifold-periods", "1.5", "--out", out,
                    "--quiet"], check=True, capture_output=True)
    with h5py.File(out, "r") as f:
        cli = {c: f["manifolds"][c][()] for c in f["manifolds"]}
    fam = lgi.continue_family(UP, seeds_from_poincare=sec, poincare_points=[point], steps=0, manifolds=4,
                              manifold_periods=1.5)
    assert fam["stability"] == ["inverse_hyperbolic"] and len(cli["s"]) > 0
    assert {"cardan_angles", "cardan_momenta"} <= set(cli)
    same_columns(fam["manifolds"], cli)
