"""scripts/plots/poincare.py as a user runs it: `lgi poincare` on the
Kovalevskaya top (coloured by orbit) and on the general top with --megno
(coloured by MEGNO), then the figures (experiments/POINCARE.md); --periodic on
a Cardan top's section: the marks where lgi periodic finds the orbits, the
manifolds in their pieces, the refusals."""
import subprocess
import sys

import h5py
import numpy as np
from script_env import ENV, LGI, PLOTS, SCENES, lgi

ROOT = PLOTS.parents[1]
SCRIPT = PLOTS / "poincare.py"


def test_poincare_figures(tmp_path):
    runs = {"kov": ("kovalevskaya", "2", []), "gen": ("general_top_richter", "2.5", ["--megno"])}
    for stem, (scene, h, flags) in runs.items():
        subprocess.run([str(LGI), "poincare", "--scene", str(ROOT / "experiments" / "scenes" / f"{scene}.toml"),
                        "--l", "1", "--h", h, "--ics", "6", "--t-end", "60", "--quiet", "--out",
                        str(tmp_path / f"{stem}.h5"), *flags], check=True)
    subprocess.run(["/usr/bin/python3", str(SCRIPT), "--out", str(tmp_path / "fig"), str(tmp_path / "kov.h5")],
                   check=True, env=ENV, capture_output=True)
    subprocess.run(["/usr/bin/python3", str(SCRIPT), "--out", str(tmp_path / "fig"), "--colour", "megno",
                    str(tmp_path / "gen.h5")], check=True, env=ENV, capture_output=True)
    for stem in ("kov", "gen"):
        for ext in ("pdf", "png"):
            assert (tmp_path / "fig" / f"poincare_{stem}.{ext}").stat().st_size > 1000
    # --colour megno on a file without MEGNO: one line, exit 1
    r = subprocess.run(["/usr/bin/python3", str(SCRIPT), "--out", str(tmp_path / "fig2"), "--colour", "megno",
                        str(tmp_path / "kov.h5")], env=ENV, capture_output=True, text=True)
    assert r.returncode == 2 and "--megno" in r.stderr


# --periodic on a Cardan section (experiments/POINCARE.md, "A top in a Cardan suspension"; PERIODIC.md,
# "Cardan tops"): the orbit of period 5.745 of cardan_general_asymmetric_up at l = 1 (row 3 of
# `lgi periodic --from-equilibria --steps 1 --h-step 0.02`) on its own level's section.
UP = SCENES / "cardan_general_asymmetric_up.toml"


def plot(*args, code=0):
    r = subprocess.run(["/usr/bin/python3", str(SCRIPT), *map(str, args)], env=ENV, capture_output=True, text=True)
    assert r.returncode == code, r.stderr
    return r


def marks(csv):
    """poincare.py's list of the marks it drew: [(family, index, stability, panel, x, y)]."""
    rows = [line.split(",") for line in csv.read_text().splitlines()[1:]]
    return [(int(f), int(i), s, int(p), float(x), float(y)) for f, i, _, _, _, s, p, x, y in rows]


def test_cardan_periodic_marks(tmp_path):
    """The crossings poincare.py marks for an orbit of --from-equilibria (integrated from its point) are
    where lgi itself finds that orbit on the section: lgi periodic --seeds-from-poincare from each mark
    converges to the same period and to the mark (its section_phi, section_theta, section_sheet); the
    orbit it finds, which carries its crossing, is marked there exactly and at the same other crossings."""
    base = tmp_path / "a.h5"
    lgi("periodic", "--scene", UP, "--l", "1", "--from-equilibria", "--steps", "1", "--h-step", "0.02", "--out", base)
    with h5py.File(base) as f:
        h, T, fam = (f["periodic"][k][3] for k in ("h", "period", "family"))
    assert abs(T - 5.745) < 0.01
    sec = tmp_path / "s.h5"
    lgi("poincare", "--scene", UP, "--l", "1", "--h", repr(float(h)), "--ics", "2", "--t-end", "5", "--out", sec)
    r = plot("--out", tmp_path / "fig", "--periodic", base, "--periodic-h-tol", "1e-9", sec)
    assert (tmp_path / "fig" / "poincare_s.png").stat().st_size > 1000
    mine = [m for m in marks(tmp_path / "fig" / "poincare_s_periodic.csv") if m[0] == fam]
    assert "crossing(s) marked" in r.stderr and len(mine) >= 2, r.stderr
    assert all(m[2] == "elliptic" for m in mine)
    torus = [m for m in mine if m[3] in (1, -1)]
    assert {m[3] for m in torus} == {1, -1}  # dq2/dt = 0 with dq3/dt of either sign, once each per period
    points = [f"{m[4]!r},{m[5]!r},{m[3]}" for m in torus]
    seeded = tmp_path / "b.h5"
    lgi("periodic", "--scene", UP, "--seeds-from-poincare", sec, *[a for p in points for a in ("--poincare-point", p)],
        "--steps", "0", "--out", seeded)
    with h5py.File(seeded) as f:
        s = {k: f["periodic"][k][()] for k in ("period", "section_phi", "section_theta", "section_sheet", "family")}
    assert len(s["period"]) == len(torus)
    for k, m in enumerate(torus):
        assert abs(s["period"][k] - T) < 1e-8
        assert s["section_sheet"][k] == m[3]
        assert abs(s["section_phi"][k] - m[4]) < 1e-7 and abs(s["section_theta"][k] - m[5]) < 1e-7, (k, m)
    plot("--out", tmp_path / "fig2", "--periodic", seeded, "--periodic-h-tol", "1e-9", sec)
    theirs = marks(tmp_path / "fig2" / "poincare_s_periodic.csv")
    for k in range(len(torus)):
        own = [m for m in theirs if m[0] == s["family"][k]]
        assert (s["section_sheet"][k], s["section_phi"][k], s["section_theta"][k]) in [m[3:] for m in own]
        assert sorted(m[3] for m in own) == sorted(m[3] for m in mine)
        for m in own:  # the other crossings as the first orbit's
            assert min(abs(m[4] - n[4]) + abs(m[5] - n[5]) for n in mine if n[3] == m[3]) < 1e-6


def test_cardan_manifolds_and_marks_in_their_panels(tmp_path):
    """A /manifolds group (lgi periodic --manifolds: phi, theta, sheet hold x, y, piece on a Cardan top):
    each point of the orbits drawn is in the panel of its piece, in its branch's colour, another orbit's
    are not; and each crossing marked is in the panel of its piece, with its class's marker."""
    sys.path.insert(0, str(PLOTS))
    import poincare
    path = tmp_path / "m.h5"
    with h5py.File(path, "w") as f:
        g = f.create_group("manifolds")
        g["family"], g["index"] = np.array([0, 0, 0, 0, 1]), np.array([2, 2, 2, 2, 2])
        g["branch"] = np.array(["unstable", "unstable", "stable", "unstable", "stable"], dtype=h5py.string_dtype())
        g["phi"], g["theta"] = np.array([1.0, 2.0, 3.0, 4.0, 5.0]), np.array([0.5, 1.5, -2.5, 2.0, 1.0])
        g["sheet"] = np.array([1, -1, 2, 1, 3])
    table = {"family": np.array([0, 1]), "index": np.array([2, 3])}
    fig, axes = poincare.c.plt.subplots(2, 2)
    panels = dict(zip(poincare.PANEL_PIECES, axes.flat))
    m = poincare.read_manifolds(path, table, [0, 1])
    assert sorted(m["branch"]) == ["stable", "unstable", "unstable", "unstable"]
    poincare.draw_manifolds(panels, m, False)
    drawn = {(piece, tuple(np.round(col.get_facecolor()[0], 3)), tuple(xy)) for piece, ax in panels.items()
             for col in ax.collections for xy in col.get_offsets()}
    red, blue = (tuple(np.round(poincare.c.matplotlib.colors.to_rgba(k), 3)) for k in ("tab:red", "tab:blue"))
    assert drawn == {(1, red, (1.0, 0.5)), (-1, red, (2.0, 1.5)), (2, blue, (3.0, -2.5)), (1, red, (4.0, 2.0))}
    assert poincare.read_manifolds(path, table, [1]) is None  # family 1's index 3 has none
    poincare.draw_marks(panels, [(0, "elliptic", -1, 1.5, 2.5), (1, "hyperbolic", 3, 0.5, -1.0),
                                 (1, "elliptic", -1, 0.2, 0.3)])
    lines = {(piece, line.get_marker(), tuple(xy)) for piece, ax in panels.items() for line in ax.lines
             for xy in line.get_xydata()}
    assert lines == {(-1, "o", (1.5, 2.5)), (-1, "o", (0.2, 0.3)), (3, "X", (0.5, -1.0))}
    poincare.c.plt.close(fig)


# A hyperbolic orbit of the same top at l = 1 (family 0 of `lgi periodic --from-equilibria --steps 25
# --h-step 0.02 --h-range=-1:1`, index 13, between its folds at h = -0.0245 and -0.0756; tr P = 3.11,
# T = 14.244): its h and the point where it crosses the torus copy dq3/dt > 0, by lgi periodic
# --seeds-from-poincare --returns 3, to 17 digits.
HYPERBOLIC_H, HYPERBOLIC_POINT = "-0.05003916166763288", "2.60946322381019,3.81115459130907,1"


def test_cardan_manifolds_of_a_hyperbolic_orbit(tmp_path):
    """lgi periodic --manifolds on the hyperbolic orbit, drawn: all its /manifolds points counted on
    stderr, the orbit's six crossings marked as hyperbolic (its own point exactly), and each mark with
    manifold points near it in its panel (the manifolds leave the orbit's crossings)."""
    sec, orbit = tmp_path / "s.h5", tmp_path / "o.h5"
    lgi("poincare", "--scene", UP, "--l", "1", "--h", HYPERBOLIC_H, "--ics", "1", "--t-end", "1", "--out", sec)
    lgi("periodic", "--scene", UP, "--seeds-from-poincare", sec, "--poincare-point", HYPERBOLIC_POINT, "--returns",
        "3", "--steps", "0", "--manifolds", "4", "--manifold-periods", "2", "--manifold-epsilon", "1e-3",
        "--out", orbit)
    with h5py.File(orbit) as f:
        assert f["periodic"]["stability"][0] in (b"hyperbolic", "hyperbolic")
        m = {k: f["manifolds"][k][()] for k in ("branch", "phi", "theta", "sheet")}
    unstable = sum(b in (b"unstable", "unstable") for b in m["branch"])
    r = plot("--out", tmp_path / "fig", "--periodic", orbit, "--periodic-h-tol", "1e-9", sec)
    assert f"{unstable} unstable and {len(m['branch']) - unstable} stable manifold point(s)" in r.stderr, r.stderr
    drawn = marks(tmp_path / "fig" / "poincare_s_periodic.csv")
    assert len(drawn) == 6 and all(d[2] == "hyperbolic" for d in drawn)
    x, y, piece = (float(v) for v in HYPERBOLIC_POINT.split(","))
    assert (int(piece), x, y) in [d[3:] for d in drawn]
    for d in drawn:
        near = (m["sheet"] == d[3]) & (np.hypot(m["phi"] - d[4], m["theta"] - d[5]) < 0.05)
        assert near.sum() >= 4, d


def test_cardan_periodic_refusals(tmp_path):
    """--periodic refuses, with one line naming it and exit 1: a heavy top's periodic file on a Cardan
    section, a Cardan top's on a heavy top's section, and a periodic file of another Cardan top."""
    sec, heavy_sec = tmp_path / "s.h5", tmp_path / "hs.h5"
    lgi("poincare", "--scene", UP, "--l", "1", "--h", "-0.6", "--ics", "1", "--t-end", "1", "--out", sec)
    lgi("poincare", "--scene", SCENES / "general_top_richter.toml", "--l", "1", "--h", "2", "--ics", "1",
        "--t-end", "1", "--out", heavy_sec)
    cols = {"family": [0], "index": [0], "l": [1.0], "h": [-0.5], "period": [5.0], "angular_momentum": [[0, 0, 1.0]],
            "gamma": [[0, 0, 1.0]], "stability": ["elliptic"], "cardan_angles": [[0, 1.0, 0.5]],
            "cardan_momenta": [[1.0, 0.1, 0.2]]}

    def periodic_file(name, scene_text):
        with h5py.File(tmp_path / name, "w") as f:
            for k, v in cols.items():
                f[f"periodic/{k}"] = np.array(v, dtype=h5py.string_dtype()) if isinstance(v[0], str) else np.array(v)
            f.create_group("parameters").attrs["scene_toml"] = scene_text
        return tmp_path / name

    up = UP.read_text()
    heavy = periodic_file("heavy.h5", (SCENES / "general_top_richter.toml").read_text())
    other = periodic_file("other.h5", up.replace("outer_inertia = 0.3", "outer_inertia = 0.31"))
    same = periodic_file("same.h5", up)
    for p, s, words in ((heavy, sec, ("heavy top", "section of a Cardan top")),
                        (same, heavy_sec, ("Cardan top", "section of a heavy top")),
                        (other, sec, ("another top", "rings differ"))):
        r = plot("--out", tmp_path / "x", "--periodic", p, s, code=2)
        assert len(r.stderr.strip().splitlines()) == 1 and "--periodic" in r.stderr, r.stderr
        assert all(w in r.stderr for w in words), r.stderr
    assert not list((tmp_path / "x").glob("*.png"))
    plot("--out", tmp_path / "y", "--periodic", same, sec)  # the same top is drawn (no orbit within 0.01 of h)
