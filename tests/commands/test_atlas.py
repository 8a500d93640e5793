"""The tops-atlas commands as a user runs them: `lgi region` (experiments/REGION.md),
`lgi bifurcation --appelrot` (experiments/EQUILIBRIA.md) and `lgi chaos-map`
(experiments/CHAOS_MAP.md):
 - region: the critical points are `lgi equilibria --l` at the same l, the
   components' labels cover exactly {U_l <= h} on the grid, the topology is
   the seed's (2S3 / S1xS2 / RP3 for the free body); --cells labels a raster;
   an empty level is refused with exit 2 and poincare's message;
 - appelrot: the equilibria's (h, k) on the Appelrot curves (formulas of
   docs/atlas.md §9 evaluated here, independently), the range of k bounded by them;
 - chaos-map: integrable tops (Lagrange, Kovalevskaya) have no chaotic orbit
   on a small grid, the general top has chaotic ones at (l, h) = (1, 1) and
   (1, 1.5); each cell equals `lgi poincare --megno --lyapunov` at that (l, h)
   bit for bit; 1 and 2 threads agree bit for bit; empty cells are marked."""
import os

import h5py
import numpy as np
from lgi_cli import SCENES, lgi

GENERAL = os.path.join(SCENES, "general_top_richter.toml")
KOVALEVSKAYA = os.path.join(SCENES, "kovalevskaya.toml")
LAGRANGE = os.path.join(SCENES, "lagrange_top_disk.toml")
BOOK = os.path.join(SCENES, "dzhanibekov_book_axis2.toml")


def group(path, name):
    with h5py.File(path, "r") as f:
        return {k: f[name][k][()] for k in f[name]}, dict(f[name].attrs)


def test_region_critical_points_are_the_equilibria(tmp_path):
    reg, eq = str(tmp_path / "r.h5"), str(tmp_path / "eq.h5")
    lgi("region", "--scene", GENERAL, "--l", "2", "--h", "2.2", "--grid", "60", "--out", reg, "--quiet")
    lgi("equilibria", "--scene", GENERAL, "--l", "2", "--out", eq, "--quiet")
    cp, _ = group(reg, "critical_points")
    e, _ = group(eq, "equilibria")
    assert len(cp["value"]) == len(e["h"]) in (2, 4, 6)
    assert np.abs(cp["gamma"] - e["gamma"]).max() == 0.0
    assert np.abs(cp["value"] - e["h"]).max() < 1e-13 * (1 + np.abs(e["h"]).max())
    assert np.all((cp["index"] == 0) == (e["nonlinearly_stable"] == 1))
    assert np.sum(np.where(cp["index"] == 1, -1, 1)) == 2  # Morse: chi(S^2)
    pot, _ = group(reg, "potential")
    inside = pot["component"] >= 0
    assert np.array_equal(inside, pot["U"] <= 2.2)
    comps, attrs = group(reg, "components")
    with h5py.File(reg, "r") as f:
        par = dict(f["parameters"].attrs)
    names = attrs["topology"].split("\n")
    assert len(names) == len(comps["id"]) and par["resolved"] == "yes"
    assert np.array_equal(comps["boundaries"], 2 - comps["euler"])
    assert np.array_equal(comps["euler"], comps["euler_morse"])


def test_region_free_body_topologies_and_empty_level(tmp_path):
    A = np.array([0.01203, 0.0074, 0.0048])  # the book about its centre (seed 000)
    l = 0.1
    energies = l * l / (2 * A)  # e1 < e2 < e3
    expected = {0.5 * (energies[0] + energies[1]): "2S3", 0.5 * (energies[1] + energies[2]): "S1xS2",
                1.1 * energies[2]: "RP3"}
    for k, (h, name) in enumerate(expected.items()):
        out = str(tmp_path / f"b{k}.h5")
        r = lgi("region", "--scene", BOOK, "--l", str(l), "--h", repr(h), "--grid", "48", "--out", out)
        assert f"energy surface {name};" in r.stdout
    r = lgi("region", "--scene", BOOK, "--l", str(l), "--h", repr(0.9 * energies[0]), "--out",
            str(tmp_path / "e.h5"), check=False)
    assert r.returncode == 2
    assert "h is below the minimum energy at this l" in r.stderr and r.stderr.count("\n") == 1
    assert not (tmp_path / "e.h5").exists()
    r = lgi("region", "--scene", BOOK, "--l", "1", "--out", str(tmp_path / "x.h5"), check=False)
    assert r.returncode == 2 and "--h" in r.stderr


def test_region_cells(tmp_path):
    out = str(tmp_path / "cells.h5")
    lgi("region", "--scene", LAGRANGE, "--cells", "--l-range", "0:3:13", "--h-range", "-1.2:3:22", "--grid", "60",
        "--out", out, "--quiet")
    cells, attrs = group(out, "cells")
    names = attrs["topology_names"].split("\n")
    assert cells["topology"].shape == (13, 22)
    found = {names[k] for k in np.unique(cells["topology"])}
    assert {"empty", "S3", "2S3", "RP3"} <= found  # the seed's Lagrange topologies for the disk
    empty = names.index("empty")
    below = cells["h"][None, :] < cells["h_min"][:, None]
    assert np.array_equal(cells["topology"] == empty, below)
    assert cells["resolved"].mean() > 0.9
    eq, _ = group(out, "equilibria")
    assert len(eq["l"]) > 100


def appelrot_curves_k(l_scaled, h):
    """k of every Appelrot family at (l, h) (docs/atlas.md §9), from the formulas alone."""
    G = l_scaled ** 2 / 2
    out = [0.0, (h - G) ** 2]
    if G == 0:
        out += [1.0] + ([1 + h * h] if h > 0 else [])
    else:
        for s in np.roots([2.0, -2.0 * h, 0.0, G]):
            if abs(s.imag) < 1e-9 * max(1, abs(s)) and s.real != 0:
                s = s.real
                out.append(1 - G / s + G * G / (4 * s ** 4))
    return np.array(out)


def test_appelrot_diagram(tmp_path):
    out = str(tmp_path / "k.h5")
    lgi("bifurcation", "--scene", KOVALEVSKAYA, "--appelrot", "0,1,2", "--appelrot-h", "-1:4:51", "--out", out,
        "--quiet")
    eq, _ = group(out, "appelrot_equilibria")
    assert len(eq["k"]) >= 8
    for l, h, k in zip(eq["l_scaled"], eq["h_scaled"], eq["k"]):
        assert np.min(np.abs(appelrot_curves_k(l, h) - k)) < 1e-9 * (1 + k), (l, h, k)
    rng, _ = group(out, "appelrot_range")
    assert len(rng["k_min"]) > 20
    for l, h, lo, hi in zip(rng["l_scaled"], rng["h_scaled"], rng["k_min"], rng["k_max"]):
        fam = appelrot_curves_k(l, h)
        assert np.min(np.abs(fam - lo)) < 1e-6 * (1 + lo), (l, h, lo)
        assert np.min(np.abs(fam - hi)) < 1e-6 * (1 + hi), (l, h, hi)
    cur, _ = group(out, "appelrot")
    assert set(np.unique(cur["family"])) == {0, 1, 2, 3}
    # Realised arcs at l = 0 (docs/atlas.md section 9): k = 0 only for h > 0; k = h^2 for -1 < h < 0.
    at0 = cur["l"] == 0
    k0 = at0 & (cur["family"] == 0)
    assert np.all(cur["realised"][k0 & (cur["h_scaled"] > 0.2)] == 1)
    assert np.all(cur["realised"][k0 & (cur["h_scaled"] < -0.2)] == 0)
    k1 = at0 & (cur["family"] == 1) & (cur["h_scaled"] > -0.8) & (cur["h_scaled"] < -0.2)
    assert k1.any() and np.all(cur["realised"][k1] == 1)
    crit, _ = group(out, "appelrot_critical")  # every critical value found lies on a family, at rank < 4
    assert len(crit["k"]) > 50 and np.all(crit["family"] >= 0) and np.all(crit["rank_gap"] < 1e-7)
    for l, h, k in zip(crit["l_scaled"], crit["h_scaled"], crit["k"]):
        assert np.min(np.abs(appelrot_curves_k(l, h) - k)) < 1e-6 * (1 + k), (l, h, k)
    regions, _ = group(out, "appelrot_regions")
    assert len(regions["tori"]) > 20 and set(np.unique(regions["tori"])) <= {-1, 1, 2, 3, 4}
    main, _ = group(out, "equilibria")  # the (l, h) branches are still there
    assert len(main["l"]) > 100
    r = lgi("bifurcation", "--scene", GENERAL, "--appelrot", "1", "--out", str(tmp_path / "g.h5"), check=False)
    assert r.returncode == 2 and "--appelrot" in r.stderr and "Kovalevskaya" in r.stderr


def chaos_map(out, scene, l_range, h_range, *extra):
    lgi("chaos-map", "--scene", scene, "--l-range", l_range, "--h-range", h_range, "--ics", "4", "--t-end", "150",
        "--out", out, "--quiet", *extra)
    return group(out, "chaos_map")[0]


def test_chaos_map_integrable_tops_are_regular(tmp_path):
    for name, scene in (("kov", KOVALEVSKAYA), ("lag", LAGRANGE)):
        m = chaos_map(str(tmp_path / f"{name}.h5"), scene, "0.5:1.5:2", "0.5:2:2")
        ok = m["status"] == 0
        assert ok.sum() >= 3
        assert np.all(m["chaotic_fraction"][ok] == 0.0), (name, m["chaotic_fraction"], m["megno_median"])
        assert np.all(m["lyapunov_max"][ok] < 0.05)


def test_chaos_map_general_top_and_poincare_agree(tmp_path):
    out = str(tmp_path / "g.h5")
    m = chaos_map(out, GENERAL, "1:1:1", "-0.7:1.5:3", "--threads", "2")
    assert m["status"].tolist() == [[1, 0, 0]]  # h = -0.7 is below min H at l = 1
    assert np.isnan(m["chaotic_fraction"][0, 0])
    assert m["chaotic_fraction"][0, 1] > 0 or m["chaotic_fraction"][0, 2] > 0
    assert np.nanmax(m["lyapunov_max"]) > 0.05
    orbits, _ = group(out, "orbits")
    pc = str(tmp_path / "pc.h5")
    lgi("poincare", "--scene", GENERAL, "--l", "1", "--h", "1.5", "--ics", "4", "--t-end", "150", "--megno",
        "--lyapunov", "--out", pc, "--quiet")
    sw, _ = group(pc, "sweep")
    cell = orbits["h"] == 1.5
    assert orbits["megno"][cell].tobytes() == sw["megno"].tobytes()
    assert orbits["lyapunov"][cell].tobytes() == sw["lyapunov"].tobytes()
    one = str(tmp_path / "g1.h5")
    chaos_map(one, GENERAL, "1:1:1", "-0.7:1.5:3", "--threads", "1")
    assert group(one, "orbits")[0]["megno"].tobytes() == orbits["megno"].tobytes()
