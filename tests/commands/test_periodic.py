"""`lgi periodic` as a user runs it (experiments/PERIODIC.md):
 - --from-equilibria on general_top_richter at l = 3: the contract's columns
   under /periodic with their shapes, the CSV beside it; every family's first
   period is 2*pi/omega to 1e-6; residuals <= 1e-10; four multipliers at 1
   to 1e-8 on first orbits, their product 1 to 1e-8; stability and event texts from the contract;
 - --seed-file: a seed from that file's last orbit is found again; continued in l
   (--continue-in l) its h is held and l steps down from 3;
 - --seeds-from-poincare: on a section of Richter's top at the h of an elliptic
   orbit, the centre of its island (the mean of one orbit's crossings around
   it) converges to that orbit: same period to 1e-8, elliptic, its point on
   the section, and its crossings (SciPy's DOP853, periodic_crossings.py) are
   the orbit's to 1e-7; a row of /events on the orbit converges to it too;
 - --continue-in l with --from-equilibria at l = 3: each family's first orbit
   at l = 3, one step of --h-step in h, then l steps down at that h;
 - --manifolds: the unstable and stable manifolds of a hyperbolic orbit of
   Richter's top at l = 3 past its fold, seeded from a section: N points a
   side and branch at crossing 0, s from eps|x0| to eps|x0||lambda|, the first
   return of the unstable branch's inner point |lambda| times as far from x0
   (to 3 %), the stable branch integrated backwards; and --shooting-points 3
   finds the same orbit (period to 1e-9);
 - bad input: one line on stderr naming the flag, exit 2."""
import math
import os
import sys

import h5py
import numpy as np
from lgi_cli import lgi, refused

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GENERAL = os.path.join(ROOT, "experiments", "scenes", "general_top_richter.toml")
sys.path.insert(0, os.path.join(ROOT, "scripts", "plots"))
import periodic_crossings as pc  # noqa: E402

COLUMNS = ["family", "index", "l", "h", "period", "angular_momentum", "gamma", "residual", "multipliers",
           "stability", "event", "degenerate"]


def test_families_of_a_general_top(tmp_path):
    out = str(tmp_path / "p.h5")
    lgi("periodic", "--scene", GENERAL, "--l", "3", "--from-equilibria", "--steps", "1", "--h-step", "0.02",
        "--out", out, "--quiet")
    assert os.path.exists(str(tmp_path / "p.csv"))
    with h5py.File(out, "r") as f:
        g = f["periodic"]
        for c in COLUMNS:
            assert c in g, c
        t = {k: g[k][()] for k in g}
    n = len(t["period"])
    assert n >= 2
    assert t["angular_momentum"].shape == (n, 3) and t["gamma"].shape == (n, 3)
    assert t["multipliers"].shape == (n, 12)
    assert np.all(t["residual"] <= 1e-10)
    assert np.all(t["l"] == 3.0)
    first = t["index"] == 0
    assert np.all(np.abs(t["period"][first] - 2 * math.pi / t["omega"][first]) <= 1e-6)
    mu = t["multipliers"].reshape(n, 6, 2)
    z = mu[:, :, 0] + 1j * mu[:, :, 1]
    assert np.all(np.abs(z[first, :4] - 1) <= 1e-8)  # further on: Jordan blocks split (PERIODIC.md)
    assert np.all(np.abs(z[:, :4] - 1) <= 2e-6)
    assert np.all(np.abs(np.prod(z, axis=1) - 1) <= 1e-8)
    stab = [s.decode() if isinstance(s, bytes) else s for s in t["stability"]]
    assert set(stab) <= {"elliptic", "hyperbolic", "inverse_hyperbolic", "complex"}
    assert all((e.decode() if isinstance(e, bytes) else e) == "none" for e in t["event"])
    assert np.all(t["degenerate"] == 0)

    # A seed from the last orbit, its period a little off: found again.
    seed = str(tmp_path / "seed.txt")
    x = np.concatenate([t["angular_momentum"][-1], t["gamma"][-1]])
    with open(seed, "w") as s:
        s.write("# Pi Gamma T\n" + " ".join(repr(float(v)) for v in x) + " %r\n" % (t["period"][-1] * 1.001))
    out2 = str(tmp_path / "s.h5")
    lgi("periodic", "--scene", GENERAL, "--l", "3", "--seed-file", seed, "--steps", "0", "--out", out2, "--quiet")
    with h5py.File(out2, "r") as f:
        assert abs(f["periodic/period"][0] - t["period"][-1]) <= 1e-8
        assert f["periodic/residual"][0] <= 1e-10

    # The same seed continued in l at fixed h: h held, l moving down from 3, the same records.
    out3 = str(tmp_path / "l.h5")
    lgi("periodic", "--scene", GENERAL, "--l", "3", "--seed-file", seed, "--continue-in", "l", "--l-step", "-0.01",
        "--steps", "2", "--no-events", "--out", out3, "--quiet")
    with h5py.File(out3, "r") as f:
        g = {k: f["periodic"][k][()] for k in f["periodic"]}
        assert f["parameters"].attrs["continue_in"] == "l"
    assert len(g["l"]) == 3 and np.all(g["h"] == g["h"][0]) and g["l"][0] == 3.0
    assert np.all(np.diff(g["l"]) < 0) and abs(g["l"][1] - 2.99) <= 1e-12
    assert np.all(g["residual"] <= 1e-10)
    assert abs(g["period"][0] - t["period"][-1]) <= 1e-8


def test_seeds_from_a_poincare_section(tmp_path):
    a = str(tmp_path / "a.h5")
    lgi("periodic", "--scene", GENERAL, "--l", "2.2", "--from-equilibria", "--steps", "1", "--h-step", "0.05",
        "--no-branch-switching", "--out", a, "--quiet")
    with h5py.File(a, "r") as f:
        t = {k: f["periodic"][k][()] for k in ("family", "index", "h", "period", "angular_momentum", "gamma")}
        J, w = pc.body_of(f["parameters"].attrs["scene_toml"])
    r = int(np.flatnonzero((t["family"] == 0) & (t["index"] == 1))[0])  # elliptic, T = 8.60, h = h_e + 0.05
    x0, T, h = np.concatenate([t["angular_momentum"][r], t["gamma"][r]]), float(t["period"][r]), float(t["h"][r])
    e = w / np.linalg.norm(w)
    crossings = pc.crossings(x0, T, J, w, e, True)
    phi, theta, sheet = crossings[0]
    # A section at the orbit's h: orbit 0 on the periodic orbit, orbit 1 around it in its island.
    seeds = str(tmp_path / "seeds.csv")
    with open(seeds, "w") as f:
        f.write("phi,theta,sheet\n%r,%r,%d\n%r,%r,%d\n" % (phi, theta, sheet, phi, theta + 0.03, sheet))
    s = str(tmp_path / "s.h5")
    lgi("poincare", "--scene", GENERAL, "--l", "2.2", "--h", repr(h), "--seeds", seeds, "--t-end", "300",
        "--out", s, "--quiet")
    with h5py.File(s, "r") as f:
        ev = {k: f["events"][k][()] for k in ("index", "phi", "theta", "sheet", "direction")}
    first = np.flatnonzero(ev["index"] == 0)[0]
    island = (ev["index"] == 1) & (ev["sheet"] == sheet)
    directions = np.unique(ev["direction"][island])
    island &= ev["direction"] == directions[0]
    centre = (float(np.mean(ev["phi"][island])), float(np.mean(ev["theta"][island])))
    assert 1e-3 < math.hypot(centre[0] - phi, centre[1] - theta) < 0.02  # a guess, not the orbit
    q = str(tmp_path / "q.h5")
    lgi("periodic", "--scene", GENERAL, "--seeds-from-poincare", s, "--poincare-point",
        "%r,%r,%d" % (centre[0], centre[1], sheet), "--poincare-rows", str(first), "--steps", "0", "--out", q,
        "--quiet")
    with h5py.File(q, "r") as f:
        p = {k: f["periodic"][k][()] for k in f["periodic"]}
        assert f["parameters"].attrs["seeds_from_poincare"] == s
    assert len(p["period"]) == 2
    assert np.all(p["residual"] <= 1e-10) and np.all(p["l"] == 2.2) and np.all(p["h"] == h)
    # The point: the island's orbit, elliptic, at the orbit's crossing.
    pt = {c: p[c][1] for c in p}  # the --poincare-point family comes after the rows'
    assert abs(pt["period"] - T) <= 1e-8
    assert (pt["stability"].decode() if isinstance(pt["stability"], bytes) else pt["stability"]) == "elliptic"
    assert abs(pt["section_phi"] - phi) <= 1e-7 and abs(pt["section_theta"] - theta) <= 1e-7
    assert pt["section_sheet"] == sheet
    mine = pc.crossings(np.concatenate([pt["angular_momentum"], pt["gamma"]]), pt["period"], J, w, e, True)
    assert len(mine) == len(crossings)
    for a_, b_ in zip(sorted(mine), sorted(crossings)):
        assert abs(a_[0] - b_[0]) <= 1e-7 and abs(a_[1] - b_[1]) <= 1e-7 and a_[2] == b_[2]
    # The row: a crossing of orbit 0, which lies on the periodic orbit, gives it again.
    assert abs(p["period"][0] - T) <= 1e-8


def test_families_from_equilibria_continued_in_l(tmp_path):
    out = str(tmp_path / "l.h5")
    lgi("periodic", "--scene", GENERAL, "--l", "3", "--from-equilibria", "--continue-in", "l", "--l-step", "-0.01",
        "--steps", "2", "--h-step", "0.02", "--no-events", "--out", out, "--quiet")
    with h5py.File(out, "r") as f:
        t = {k: f["periodic"][k][()] for k in ("family", "index", "l", "h", "residual")}
        assert f["parameters"].attrs["continue_in"] == "l"
    families = np.unique(t["family"])
    assert len(families) >= 2 and np.all(t["residual"] <= 1e-10)
    for fam in families:
        r = np.flatnonzero(t["family"] == fam)
        assert list(t["index"][r]) == [0, 1, 2]
        assert t["l"][r[0]] == 3.0 and t["l"][r[1]] == 3.0 and 2.98 < t["l"][r[2]] < 3.0
        assert abs(abs(t["h"][r[1]] - t["h"][r[0]]) - 0.02) <= 1e-12 and abs(t["h"][r[2]] - t["h"][r[1]]) <= 1e-10


# A hyperbolic orbit of Richter's top at l = 3 past the fold of test_periodic.cpp (tr P = 2.238).
HYPERBOLIC = ([2.737126154036692, 0.8488396292006605, -1.033127987220866, 0.8115814748784526, 0.4064375267217684,
               -0.4196951828487045], 4.535817543042772, 4.938876025487969)


def test_manifolds_of_a_hyperbolic_orbit(tmp_path):
    x0, T, h = np.array(HYPERBOLIC[0]), HYPERBOLIC[1], HYPERBOLIC[2]
    with open(GENERAL) as f:
        J, w = pc.body_of(f.read())
    phi, theta, sheet = pc.crossings(x0, T, J, w, w / np.linalg.norm(w), True)[0]
    seeds = str(tmp_path / "seeds.csv")
    with open(seeds, "w") as f:
        f.write("phi,theta,sheet\n%r,%r,%d\n" % (phi, theta, sheet))
    s = str(tmp_path / "s.h5")
    lgi("poincare", "--scene", GENERAL, "--l", "3", "--h", repr(h), "--seeds", seeds, "--t-end", "10",
        "--out", s, "--quiet")
    point = "%r,%r,%d" % (phi, theta, sheet)
    n, eps = 6, 1e-5
    q = str(tmp_path / "q.h5")
    lgi("periodic", "--scene", GENERAL, "--seeds-from-poincare", s, "--poincare-point", point, "--steps", "0",
        "--manifolds", str(n), "--manifold-periods", "2", "--manifold-epsilon", repr(eps), "--out", q, "--quiet")
    with h5py.File(q, "r") as f:
        p = {k: f["periodic"][k][()] for k in f["periodic"]}
        m = {k: f["manifolds"][k][()] for k in f["manifolds"]}
    assert len(p["period"]) == 1 and abs(p["period"][0] - T) <= 1e-8
    assert p["stability"][0].decode() == "hyperbolic"
    x = np.concatenate([p["angular_momentum"][0], p["gamma"][0]])
    mu = p["multipliers"][0].reshape(6, 2)[4:, 0]
    lam = float(mu[np.argmax(np.abs(mu))])
    assert abs(m["multiplier"][0] - lam) <= 1e-12 and lam > 1.5
    branch = np.array([b.decode() if isinstance(b, bytes) else b for b in m["branch"]])
    ret = int(m["returns"][0])
    state = np.concatenate([m["angular_momentum"], m["gamma"]], axis=1)
    for b in ("unstable", "stable"):
        for side in (1, -1):
            start = (branch == b) & (m["side"] == side) & (m["crossing"] == 0)
            assert sorted(m["point"][start]) == list(range(n))
            s_ = np.sort(m["s"][start])
            assert abs(s_[0] / (eps * np.linalg.norm(x)) - 1) <= 1e-12 and s_[-1] < s_[0] * lam
            later = (branch == b) & (m["side"] == side) & (m["crossing"] > 0)
            assert np.all(m["t"][later] > 0) if b == "unstable" else np.all(m["t"][later] < 0)
            # The inner point's m-th crossing: one return of the map, |lambda| times as far from x0.
            inner = (branch == b) & (m["side"] == side) & (m["point"] == 0)
            d0 = np.linalg.norm(state[inner & (m["crossing"] == 0)][0] - x)
            d1 = np.linalg.norm(state[inner & (m["crossing"] == ret)][0] - x)
            assert abs(d1 / d0 / lam - 1) <= 0.03, (b, side, d1 / d0, lam)
    # Multiple shooting finds the same orbit from the same section point.
    r = str(tmp_path / "r.h5")
    lgi("periodic", "--scene", GENERAL, "--seeds-from-poincare", s, "--poincare-point", point, "--steps", "0",
        "--shooting-points", "3", "--out", r, "--quiet")
    with h5py.File(r, "r") as f:
        assert abs(f["periodic"]["period"][0] - p["period"][0]) <= 1e-9
        assert f["parameters"].attrs["shooting_points"] == "3"
    # A point's own number of returns (PHI,THETA,SHEET,N) overrides --returns: with --returns 2 the point
    # alone would be guessed at about 2T; its own 1 finds the orbit of period T.
    own = str(tmp_path / "own.h5")
    lgi("periodic", "--scene", GENERAL, "--seeds-from-poincare", s, "--returns", "2", "--poincare-point",
        point + ",1", "--steps", "0", "--out", own, "--quiet")
    with h5py.File(own, "r") as f:
        assert abs(f["periodic"]["period"][0] - p["period"][0]) <= 1e-9
    for bad in (",0", ",1.5", ",1,2"):
        assert "--poincare-point" in refused("periodic", "--scene", GENERAL, "--seeds-from-poincare", s,
                                             "--poincare-point", point + bad, "--out", own + ".x")


def test_bad_input(tmp_path):
    out = str(tmp_path / "x.h5")
    assert "--l" in refused("periodic", "--scene", GENERAL, "--l", "nan", "--from-equilibria", "--out", out)
    assert "--seed-file" in refused("periodic", "--scene", GENERAL, "--l", "3", "--out", out)
    assert "--h-range" in refused("periodic", "--scene", GENERAL, "--l", "3", "--from-equilibria",
                                  "--h-range", "2:1", "--out", out)
    assert "--steps" in refused("periodic", "--scene", GENERAL, "--l", "3", "--from-equilibria", "--steps", "-1",
                                "--out", out)
    bad = str(tmp_path / "bad.txt")
    with open(bad, "w") as s:
        s.write("1 2 3\n")
    assert "--seed-file" in refused("periodic", "--scene", GENERAL, "--l", "3", "--seed-file", bad, "--out", out)
    assert "--continue-in" in refused("periodic", "--scene", GENERAL, "--l", "3", "--from-equilibria",
                                      "--continue-in", "x", "--out", out)
    assert "--shooting-points" in refused("periodic", "--scene", GENERAL, "--l", "3", "--from-equilibria",
                                          "--shooting-points", "0", "--out", out)
    assert "--switch-branches" in refused("periodic", "--scene", GENERAL, "--l", "3", "--from-equilibria",
                                          "--switch-branches", "--no-branch-switching", "--out", out)
    assert "--manifolds" in refused("periodic", "--scene", GENERAL, "--l", "3", "--from-equilibria",
                                    "--manifolds", "10", "--out", out)
    assert "--seeds-from-poincare" in refused("periodic", "--scene", GENERAL, "--seeds-from-poincare", bad,
                                              "--out", out)
    assert bad in refused("periodic", "--scene", GENERAL, "--seeds-from-poincare", bad, "--poincare-rows", "0",
                          "--out", out)
    assert not os.path.exists(out)
