"""lgi.quantum_spectrum (python/README.md): the columns of `lgi quantum`
bit for bit; the free asymmetric rotor against an independent NumPy
reference (angular momentum matrices built from scratch in the standard
|j, k> basis, Sum L_i^2/(2 J_i) diagonalised per j: the anomalous sign of
the body-fixed components does not change the spectrum); refusals."""
import os
import subprocess

import h5py
import numpy as np
import pytest

import lgi

from conftest import SCENES

FREE = os.path.join(SCENES, "free_body_hlw.toml")


def numpy_rotor_levels(j, moments, hbar):
    k = np.arange(-j, j + 1, dtype=float)
    up = np.sqrt(j * (j + 1) - k[:-1] * (k[:-1] + 1))  # <k+1| J+ |k>
    jp = np.diag(up, -1).astype(complex)
    jx, jy, jz = (jp + jp.T) / 2, (jp - jp.T) / 2j, np.diag(k).astype(complex)
    h = sum(a @ a / (2 * m) for a, m in zip((jx, jy, jz), moments)) * hbar**2
    return np.linalg.eigvalsh(h)


def test_matches_the_command_line(lgi_exe, tmp_path):
    scene = os.path.join(SCENES, "general_top_richter.toml")
    out = str(tmp_path / "q.h5")
    r = subprocess.run([lgi_exe, "quantum", "--scene", scene, "--hbar", "0.1", "--m", "1", "--jmax", "14",
                        "--levels", "15", "--out", out, "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(out, "r") as f:
        cli = {k: f["spectrum"][k][()] for k in f["spectrum"]}
    mine = lgi.quantum_spectrum(scene, 0.1, m=1, jmax=14, levels=15)
    for k in cli:
        assert np.array_equal(mine[k], cli[k]), k
    assert mine["symmetry"] == "no symmetry used"


def test_free_rotor_against_numpy():
    hbar, moments = 0.5, (2.0, 1.0, 2.0 / 3.0)
    q = lgi.quantum_spectrum(lgi.Scene.from_file(FREE), hbar, m=0, jmax=12)
    for j in range(13):
        mine = np.sort(q["energy"][q["j"] == j])
        ref = numpy_rotor_levels(j, moments, hbar)
        assert np.allclose(mine, ref, rtol=1e-10, atol=1e-12 * hbar**2), j


def test_refusals():
    with pytest.raises(ValueError, match=r"\[spring\]"):
        lgi.quantum_spectrum(os.path.join(SCENES, "stiff_damped_spring.toml"), 1.0)
    with pytest.raises(ValueError, match="hbar"):
        lgi.quantum_spectrum(FREE, -1.0)


def test_weyl_and_ebk_match_the_command_line(lgi_exe, tmp_path):
    # weyl=True and ebk=True give the file's /weyl and /ebk columns bit for bit.
    scene = os.path.join(SCENES, "lagrange_top_cigar.toml")
    out = str(tmp_path / "e.h5")
    r = subprocess.run([lgi_exe, "quantum", "--scene", scene, "--hbar", "0.1", "--m", "1", "--jmax", "20",
                        "--levels", "12", "--ebk", "--statistics", "--out", out, "--quiet"], capture_output=True,
                       text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(out, "r") as f:
        weyl, ebk, n = f["weyl"]["weyl_count"][()], f["ebk"]["energy_ebk"][()], f["ebk"]["n"][()]
    mine = lgi.quantum_spectrum(scene, 0.1, m=1, jmax=20, levels=12, weyl=True, ebk=True)
    assert np.array_equal(mine["weyl_count"], weyl)
    assert np.array_equal(mine["energy_ebk"], ebk) and np.array_equal(mine["ebk_n"], n)
    assert "weyl_count" not in lgi.quantum_spectrum(scene, 0.1, m=1, jmax=20, levels=2)
    with pytest.raises(ValueError, match="Lagrange"):
        lgi.quantum_spectrum(os.path.join(SCENES, "general_top_richter.toml"), 0.1, jmax=6, levels=2, ebk=True)
    free = lgi.quantum_spectrum(FREE, 1.0, m=3, jmax=3, ebk=True)  # the Euler top at j = 3 (docs/quantum.md §9)
    assert list(free["ebk_n"]) == [0, 0, 1, 1, 1, 0, 0]


def test_kovalevskaya_ebk_matches_the_command_line(lgi_exe, tmp_path):
    # The Kovalevskaya top's EBK level from its numerical tori (docs/quantum.md section 10): the
    # ground level at hbar = 0.2 (one torus family solved), bit for bit with the file, within
    # 0.3 hbar^2 above the exact level (measured 0.152 hbar^2). A few seconds of CPU.
    scene = os.path.join(SCENES, "kovalevskaya.toml")
    out = str(tmp_path / "k.h5")
    r = subprocess.run([lgi_exe, "quantum", "--scene", scene, "--hbar", "0.2", "--jmax", "16", "--levels", "1",
                        "--ebk", "--out", out, "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(out, "r") as f:
        ebk, n, n_fast = f["ebk"]["energy_ebk"][()], f["ebk"]["n"][()], f["ebk"]["n_fast"][()]
    mine = lgi.quantum_spectrum(scene, 0.2, jmax=16, levels=1, ebk=True)
    assert np.array_equal(mine["energy_ebk"], ebk)
    assert list(mine["ebk_n"]) == list(n) == [0] and list(mine["ebk_n_fast"]) == list(n_fast) == [0]
    assert 0 < ebk[0] - mine["energy"][0] < 0.3 * 0.2 ** 2
