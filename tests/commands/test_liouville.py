"""The measure of the level-set draws (docs/atlas.md §6, experiments/SWEEPS.md
"Level set"): the Liouville draw is invariant under the flow, the uniform one
is not; `measure` in a spec and `--measure` in `lgi poincare` and
`lgi chaos-map` (default liouville); the uniform draw is lgi's earlier draw;
the chaotic fraction with its 95 % Wilson interval in the files and on stdout."""
import os

import h5py
import numpy as np
from lgi_cli import SCENES, lgi

GENERAL = os.path.join(SCENES, "general_top_richter.toml")
KOVALEVSKAYA = os.path.join(SCENES, "kovalevskaya.toml")
CARDAN = os.path.join(SCENES, "cardan_euler_tilted.toml")
Z = 1.959963984540054  # the 0.975 quantile of the normal law


def sweep_spec(tmp_path, measure, samples, t_end, scene=GENERAL, l=2.2, h=2.0, seed=1, name="s"):
    text = (f'scene = "{scene}"\nscheme = "split-exact@yoshida4"\ndt = 0.05\nt_end = {t_end}\n'
            f"seed = {seed}\nsamples = {samples}\nmonitor_every = 100000\n[level_set]\nh = {h}\nl = {l}\n")
    if measure:
        text += f'measure = "{measure}"\n'
    path = tmp_path / f"{name}.toml"
    path.write_text(text)
    return str(path)


def sweep_rows(path):
    with h5py.File(path, "r") as f:
        return {k: f["sweep"][k][()] for k in f["sweep"]}


def two_sample_chi_square(a, b, bins=10):
    """Pearson's chi-square of two equal-size samples over `bins` bins of equal pooled count (bins - 1 dof)."""
    edges = np.quantile(np.concatenate([a, b]), np.linspace(0, 1, bins + 1))
    edges[0], edges[-1] = -np.inf, np.inf
    ca, cb = np.histogram(a, edges)[0], np.histogram(b, edges)[0]
    return float(np.sum((ca - cb) ** 2 / (ca + cb)))


def wilson(k, n):
    p = k / n
    c = (p + Z * Z / (2 * n)) / (1 + Z * Z / n)
    w = Z / (1 + Z * Z / n) * np.sqrt(p * (1 - p) / n + Z * Z / (4 * n * n))
    return c - w, c + w


def flowed_histograms(tmp_path, scene, l, h, measure, samples, t_end):
    """Chi-square of t = 0 against t = t_end for Gamma_1, Gamma_3 and Pi_1 of `samples` orbits."""
    out = str(tmp_path / f"{measure}.h5")
    lgi("sweep", "--spec", sweep_spec(tmp_path, measure, samples, t_end, scene=scene, l=l, h=h, name=measure),
        "--out", out, "--quiet")
    r = sweep_rows(out)
    assert np.all(r["status"] == 0)
    return [two_sample_chi_square(r["initial.gamma"][:, 0], r["gamma"][:, 0]),
            two_sample_chi_square(r["initial.gamma"][:, 2], r["gamma"][:, 2]),
            two_sample_chi_square(r["initial.angular_momentum"][:, 0], r["angular_momentum"][:, 0])]


# 27.9 is the 0.999 quantile of chi-square with 9 degrees of freedom. The two
# samples are the same orbits at two times (positively correlated), so the
# test is conservative for an invariant draw.
CHI2_999 = 27.9


def test_liouville_draw_is_invariant_on_richters_top(tmp_path):
    """Richter's top at (l, h) = (2.2, 2): 3000 orbits to t = 40; the histograms
    of Gamma_1, Gamma_3 and Pi_1 at t = 0 and t = 40 agree."""
    chi2 = flowed_histograms(tmp_path, GENERAL, 2.2, 2.0, "liouville", 3000, 40)
    assert max(chi2) < CHI2_999, chi2


def test_uniform_draw_is_not_invariant(tmp_path):
    """A top of very unequal moments, J = (1, 4, 4.5) (the uniform draw's density
    is off by up to sqrt(4.5)), at (l, h) = (1, 1.5), 6000 orbits to t = 30: the
    Liouville draw's histograms of Gamma_1 agree at t = 0 and 30, the uniform
    draw's differ far beyond the sampling error (it drifts towards the Liouville
    density: Gamma along the axis of the least moment gains weight)."""
    scene = tmp_path / "unequal.toml"
    scene.write_text(open(GENERAL).read().replace("inertia = [1.0, 1.5, 2.0]", "inertia = [1.0, 4.0, 4.5]"))
    liouville = flowed_histograms(tmp_path, str(scene), 1.0, 1.5, "liouville", 6000, 30)
    uniform = flowed_histograms(tmp_path, str(scene), 1.0, 1.5, "uniform", 6000, 30)
    assert max(liouville) < CHI2_999, liouville
    assert uniform[0] > 2 * CHI2_999, uniform


def test_default_measure_threads_and_refusals(tmp_path):
    default, liouville, uniform = (str(tmp_path / f"{n}.h5") for n in ("default", "liouville", "uniform"))
    lgi("sweep", "--spec", sweep_spec(tmp_path, None, 40, 1, name="d"), "--out", default, "--quiet", "--threads", "1")
    lgi("sweep", "--spec", sweep_spec(tmp_path, "liouville", 40, 1, name="l"), "--out", liouville, "--quiet",
        "--threads", "2")
    lgi("sweep", "--spec", sweep_spec(tmp_path, "uniform", 40, 1, name="u"), "--out", uniform, "--quiet")
    d, li, u = sweep_rows(default), sweep_rows(liouville), sweep_rows(uniform)
    for k in ("initial.gamma", "initial.angular_momentum", "gamma", "angular_momentum"):
        assert d[k].tobytes() == li[k].tobytes(), k
    assert not np.array_equal(d["initial.gamma"], u["initial.gamma"])
    bad = sweep_spec(tmp_path, "microcanonical", 4, 1, name="bad")
    r = lgi("sweep", "--spec", bad, "--out", str(tmp_path / "bad.h5"), check=False)
    assert r.returncode == 2 and len(r.stderr.strip().splitlines()) == 1
    assert "[level_set] measure" in r.stderr and "liouville or uniform" in r.stderr
    r = lgi("poincare", "--scene", GENERAL, "--l", "1", "--h", "2", "--ics", "2", "--t-end", "1", "--measure", "box",
            "--out", str(tmp_path / "p.h5"), check=False)
    assert r.returncode == 2 and "--measure" in r.stderr
    r = lgi("chaos-map", "--scene", GENERAL, "--l-range", "1:1:1", "--h-range", "2:2:1", "--ics", "2", "--t-end", "1",
            "--measure", "box", "--out", str(tmp_path / "c.h5"), check=False)
    assert r.returncode == 2 and "--measure" in r.stderr
    r = lgi("poincare", "--scene", CARDAN, "--l", "2.85", "--h", "6.96", "--ics", "2", "--t-end", "1",
            "--measure", "liouville", "--out", str(tmp_path / "cardan.h5"), check=False)
    assert r.returncode == 2 and "--measure" in r.stderr


def test_uniform_measure_is_the_earlier_draw(tmp_path):
    """measure = "uniform" reproduces the draws of lgi before the measure was
    chosen (the values below are that version's /sweep initial columns)."""
    out = str(tmp_path / "u.h5")
    lgi("sweep", "--spec", sweep_spec(tmp_path, "uniform", 3, 0.05, scene=KOVALEVSKAYA, l=1.0, h=2.0, seed=2026),
        "--out", out, "--quiet")
    r = sweep_rows(out)
    np.testing.assert_allclose(r["initial.gamma"], EARLIER_GAMMA, rtol=0, atol=1e-13)
    np.testing.assert_allclose(r["initial.angular_momentum"], EARLIER_PI, rtol=0, atol=1e-13)


# lgi sweep at commit 3271f04 (before `measure` existed) with this spec, /sweep rows 0-2.
EARLIER_GAMMA = [[-0.30014810043815937, 0.9536499060241972, 0.021516843249053563],
                 [-0.8761194001502166, -0.4270772667820833, 0.2236510784198682],
                 [0.8929372796208733, -0.4501733507523357, 0.0026398741804773973]]
EARLIER_PI = [[2.099588770628818, 1.7308041035783763, -0.9477965369841412],
              [-1.3499247377477108, 1.4476997701919418, 1.9476070161102625],
              [0.8120750926548244, -0.6029304918425638, 1.3048486018333025]]


def test_chaotic_fraction_with_wilson_interval(tmp_path):
    pc, cm = str(tmp_path / "p.h5"), str(tmp_path / "c.h5")
    r = lgi("poincare", "--scene", GENERAL, "--l", "1", "--h", "1.5", "--ics", "12", "--t-end", "150", "--megno",
            "--out", pc)
    with h5py.File(pc, "r") as f:
        megno = f["sweep"]["megno"][()]
        chaos = {k: f["chaos"][k][()] for k in f["chaos"]}
        assert f["parameters"].attrs["measure"] == "liouville"
        assert 'measure = "liouville"' in f["parameters"].attrs["spec_toml"]
    n, k = int(np.sum(np.isfinite(megno))), int(np.sum(megno > 3.0))
    assert chaos["orbits"][0] == n and chaos["chaotic"][0] == k and chaos["threshold"][0] == 3.0
    lo, hi = wilson(k, n)
    assert abs(chaos["chaotic_fraction"][0] - k / n) < 1e-15
    assert abs(chaos["chaotic_fraction_low"][0] - lo) < 1e-12 and abs(chaos["chaotic_fraction_high"][0] - hi) < 1e-12
    assert f"chaotic (MEGNO > 3): {k}/{n} = {k / n:.3f} [{lo:.3f}, {hi:.3f}]" in r.stdout
    r = lgi("chaos-map", "--scene", GENERAL, "--l-range", "1:1:1", "--h-range", "1.5:1.5:1", "--ics", "12",
            "--t-end", "150", "--threads", "2", "--out", cm)
    with h5py.File(cm, "r") as f:
        m = {k: np.ravel(f["chaos_map"][k][()]) for k in f["chaos_map"]}
        assert f["chaos_map"].attrs["measure"] == "liouville" and f["parameters"].attrs["measure"] == "liouville"
    # The cell's orbits are poincare's (same draw, same indicators).
    assert m["orbits"][0] == n and m["chaotic"][0] == k
    assert abs(m["chaotic_fraction_low"][0] - lo) < 1e-12 and abs(m["chaotic_fraction_high"][0] - hi) < 1e-12
    assert f"l = 1, h = 1.5: chaotic {k}/{n} = {k / n:.3f} [{lo:.3f}, {hi:.3f}]" in r.stdout
