"""lgi.spectral_statistics (python/README.md, docs/spectral_statistics.md):
Poisson levels give beta near 0 and Delta3 = L/15; a GOE matrix's levels
unfolded by the semicircle give beta near 1; two GOE spectra mixed look
intermediate and split by their labels are GOE again; the staircase fit
unfolds an unfolded spectrum back to itself; bad input is a ValueError."""
import numpy as np
import pytest

import lgi


def goe_unfolded(n, rng):
    a = rng.normal(size=(n, n)) / np.sqrt(n)
    e = np.linalg.eigvalsh((a + a.T) / np.sqrt(2.0))  # off-diagonal variance 1/n
    e = e[np.abs(e) < 1.6]
    return n * (0.5 + e * np.sqrt(4 - e**2) / (4 * np.pi) + np.arcsin(e / 2) / np.pi)


def test_poisson_and_goe():
    rng = np.random.default_rng(5)
    x = np.cumsum(rng.exponential(size=1000))
    p = lgi.spectral_statistics(x, unfolded=True, lengths=[2.0, 5.0])
    assert p["levels"] == 1000 and len(p["spacings"]) == 999
    assert abs(np.mean(p["spacings"]) - 1.0) < 1e-12
    assert p["brody"]["beta"] < 4 * p["brody"]["standard_error"]
    assert np.all(np.abs(p["rigidity"] - p["poisson"]["rigidity"]) < 4 * p["rigidity_error"])
    assert np.allclose(p["poisson"]["rigidity"], [2 / 15, 5 / 15])
    assert p["histogram"]["counts"].sum() + p["histogram"]["above"] == 999
    g = lgi.spectral_statistics(goe_unfolded(400, rng), unfolded=True, lengths=[2.0, 5.0])
    assert g["brody"]["beta"] > 0.75
    assert np.all(np.abs(g["rigidity"] - g["goe"]["rigidity"]) < 4 * g["rigidity_error"])


def test_classes_split_a_mixed_spectrum():
    rng = np.random.default_rng(6)
    a, b = goe_unfolded(300, rng), goe_unfolded(300, rng)
    levels = np.concatenate([a, b])
    labels = [0] * len(a) + [1] * len(b)
    mixed = lgi.spectral_statistics(np.sort(levels) / 2, unfolded=True)
    split = lgi.spectral_statistics(levels, classes=labels, unfolded=True)
    assert sorted(split) == [0, 1]
    for c in split.values():
        assert not c["too_few"]
        assert c["brody"]["beta"] > mixed["brody"]["beta"] + 3 * c["brody"]["standard_error"]


def test_staircase_fit_and_errors():
    x = np.arange(200) + 0.3 * np.sin(np.arange(200))
    fitted = lgi.spectral_statistics(x, degree=1)
    given = lgi.spectral_statistics(x, unfolded=True)
    assert np.allclose(fitted["spacings"], given["spacings"], rtol=1e-9)
    assert np.array_equal(lgi.spectral_statistics([1.0, 3.0, 2.0, 5.0], unfolded=True)["spacings"], [0.75, 0.75, 1.5])
    with pytest.raises(ValueError, match="level 1 is not a finite number"):
        lgi.spectral_statistics([1.0, np.nan, 2.0], unfolded=True)
    with pytest.raises(ValueError, match="class labels"):
        lgi.spectral_statistics([1.0, 2.0, 3.0], classes=[0, 1])
    with pytest.raises(ValueError, match="too few"):
        lgi.spectral_statistics([1.0, 2.0])
    few = lgi.spectral_statistics(np.arange(10.0), classes=[0] * 9 + [1], degree=1)
    assert few[1]["too_few"] and few[1]["levels"] == 1 and not few[0]["too_few"]
