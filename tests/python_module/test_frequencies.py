"""lgi.frequencies (python/README.md, experiments/FREQUENCIES.md): the tables
of `lgi frequencies` bit for bit on the same run; the Lagrange top's nutation
frequency against the closed form's period as `lgi actions` writes it (1e-9);
a complex pair A+iB has signed frequencies; bad arguments raise ValueError."""
import os
import subprocess

import h5py
import numpy as np
import pytest

import lgi

from conftest import SCENES

LAGRANGE = os.path.join(SCENES, "lagrange_top_cigar.toml")


def test_frequencies_match_the_command(lgi_exe, tmp_path):
    out = str(tmp_path / "f.h5")
    args = ["--scene", LAGRANGE, "--t-end", "300", "--window-order", "2", "--terms", "3",
            "--observable", "gamma_3,gamma_1", "--out", out, "--quiet"]
    assert subprocess.run([lgi_exe, "frequencies", *args], capture_output=True).returncode == 0
    r = lgi.frequencies(LAGRANGE, 300.0, observables=["gamma_3", "gamma_1"], terms=3, window_order=2)
    with h5py.File(out, "r") as f:
        for k in ("term", "frequency", "amplitude", "phase", "period"):
            assert np.array_equal(r["frequencies"][k], f["frequencies"][k][()]), k
        assert r["frequencies"]["observable"] == [s.decode() for s in f["frequencies/observable"][()]]
        for k in ("frequency", "frequency_first_half", "frequency_second_half", "relative_change", "mean"):
            assert np.array_equal(r["diffusion"][k], f["frequency_diffusion"][k][()]), k
    # The nutation frequency against the closed form's period (the return_time of `lgi actions`, method 0).
    actions = str(tmp_path / "a.h5")
    assert subprocess.run([lgi_exe, "actions", "--scene", LAGRANGE, "--out", actions, "--quiet"]).returncode == 0
    with h5py.File(actions, "r") as f:
        period = f["tori/return_time"][0]
        assert f["tori/method"][0] == 0
    nutation = r["frequencies"]["frequency"][0]
    assert abs(nutation - 2 * np.pi / period) < 1e-9 * nutation
    assert r["samples"] == 30001 and r["diffusion"]["log10_relative_change"][0] < -8


def test_complex_pair():
    """Pi_1 + i Pi_2 of HLW's body turns clockwise: a negative frequency, the same magnitude as Pi_1's."""
    free = os.path.join(SCENES, "free_body_hlw.toml")
    r = lgi.frequencies(free, 300.0, observables=["angular_momentum_1+iangular_momentum_2", "angular_momentum_1"],
                        terms=2, window_order=2, scheme="exact", dt=0.02)
    f = r["frequencies"]
    assert f["observable"][0] == "angular_momentum_1+iangular_momentum_2" and f["frequency"][0] < 0
    assert abs(f["frequency"][0] + f["frequency"][2]) < 1e-10 * f["frequency"][2]
    assert r["diffusion"]["mean"][0] == 0.0


def test_bad_arguments():
    with pytest.raises(ValueError, match="observable"):
        lgi.frequencies(LAGRANGE, 10.0, observables=["energy"])
    with pytest.raises(ValueError, match="t_end"):
        lgi.frequencies(LAGRANGE, -1.0)
    with pytest.raises(ValueError):
        lgi.frequencies(LAGRANGE, 10.0, terms=0)
