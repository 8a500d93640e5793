"""scripts/plots/periodic.py and poincare.py --periodic (experiments/PERIODIC.md,
"Figures"; experiments/POINCARE.md): the figures from small synthetic /periodic
and /equilibria files made here with h5py (lgi periodic itself takes a minute),
the refusals, and the crossings of a periodic orbit of Richter's top at
l = 2.2 (found by lgi periodic, copied here to 17 digits) against those lgi
poincare finds on the same orbit; a /manifolds group drawn in a --zoom window, and a
bad --zoom refused."""
import os
import subprocess
import sys
from pathlib import Path

import h5py
import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]
PLOTS = ROOT / "scripts" / "plots"
LGI = Path(os.environ.get("LGI_EXECUTABLE", ROOT / "build" / "release" / "lgi"))
ENV = dict(os.environ, PYTHONDONTWRITEBYTECODE="1", MPLBACKEND="Agg")
SCENE = ROOT / "experiments" / "scenes" / "general_top_richter.toml"
sys.path.insert(0, str(PLOTS))
import periodic  # noqa: E402
import periodic_crossings as pc  # noqa: E402

# family 1 of `lgi periodic --scene general_top_richter.toml --l 2.2 --from-equilibria --steps 16
# --h-step 0.02` at h = 1.507 (inverse hyperbolic, doubled from family 0) and family 2 at h = 1.5153
# (elliptic): (h, T, Pi, Gamma)
ORBITS = [(1.5070002744548436, 21.77145127952004, [-1.3527066539729664, -1.820144042296441, -0.7895049387592321],
           [-0.36288400149992495, -0.9316813434008692, -0.016884188288712944], "inverse_hyperbolic"),
          (1.5153161610328627, 3.841061563943097, [-0.548348626521471, -0.3664104245820286, -2.4574406659473857],
           [0.26715913611212566, -0.3287759732679072, -0.9058324102137012], "elliptic")]


def run(script, *args, code=0):
    r = subprocess.run(["/usr/bin/python3", str(PLOTS / script), *map(str, args)], env=ENV, capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == code, f"{script} {args}: exit {r.returncode}\n{r.stderr}"
    return r


def refused(capsys, monkeypatch, *args):
    """periodic.py's main in this process (a refusal needs no figure): its stderr, after exit 2."""
    monkeypatch.setattr(sys, "argv", ["periodic.py", *map(str, args)])
    with pytest.raises(SystemExit) as e:
        periodic.main()
    assert e.value.code == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1, err
    return err


def write_table(path, group, cols, attrs):
    with h5py.File(path, "w") as f:
        g = f.create_group(group)
        for k, v in cols.items():
            g.create_dataset(k, data=np.array(v, dtype=h5py.string_dtype()) if isinstance(v[0], str) else v)
        p = f.create_group("parameters")
        for k, v in attrs.items():
            p.attrs[k] = v


def periodic_file(path, orbits=None):
    """Two families at l = 2.2: 0 elliptic -> period doubling -> inverse hyperbolic, with a fold
    and a class change; 1 doubled from 0. Or the given (h, T, Pi, Gamma, class) orbits."""
    if orbits is None:
        h = np.concatenate([np.linspace(0.7, 1.6, 10), [1.6, 1.55], np.linspace(1.2, 1.4, 5)])
        T = np.concatenate([np.linspace(8, 11, 10), [11.1, 11.2], np.linspace(22, 21.5, 5)])
        st = ["elliptic"] * 5 + ["inverse_hyperbolic"] * 5 + ["hyperbolic"] * 2 + ["elliptic"] * 3 + ["hyperbolic"] * 2
        ev = ["none"] * 4 + ["period_doubling"] + ["none"] * 4 + ["fold", "class_change", "none"] + ["none"] * 5
        fam, par = [0] * 12 + [1] * 5, [-1] * 12 + [0] * 5
        tr = np.concatenate([np.linspace(1.9, -1.9, 5), np.linspace(-2.5, -40, 5), [2.5, 2.0], np.linspace(1.5, 3, 5)])
        P, G = np.tile([0, 0, 2.2], (17, 1)), np.tile([0, 0, 1.0], (17, 1))
    else:
        h, T, P, G, st = (list(x) for x in zip(*orbits))
        n = len(h)
        ev, fam, par, tr = ["none"] * n, list(range(n)), [-1] * n, [0.0] * n
    n = len(h)
    cols = {"family": fam, "index": list(range(n)), "l": [2.2] * n, "h": h, "period": T,
            "angular_momentum": np.asarray(P, dtype=float), "gamma": np.asarray(G, dtype=float),
            "stability": st, "event": ev, "degenerate": [0] * n, "equilibrium": [0] * n, "parent": par,
            "reduced_trace": tr}
    write_table(path, "periodic", cols, {"scene_toml": SCENE.read_text(), "scene_file": str(SCENE), "l": "2.2"})


def bifurcation_file(path):
    l = np.linspace(-3, 3, 61)
    cols = {"branch": np.repeat([0, 1], 61), "l": np.concatenate([l, l]),
            "h": np.concatenate([l * l / 4 - 1, l * l / 3 + 1]), "stability": np.repeat([0, 1], 61),
            "fold": np.zeros(122, dtype=int), "class_change": np.zeros(122, dtype=int)}
    write_table(path, "equilibria", cols, {"scene_toml": SCENE.read_text(), "branch_labels": "0: hanging\n1: upright"})


def test_periodic_figures(tmp_path):
    periodic_file(tmp_path / "p.h5")
    bifurcation_file(tmp_path / "b.h5")
    run("periodic.py", "--out", tmp_path / "fig", "--branches", tmp_path / "b.h5", tmp_path / "p.h5")
    run("periodic.py", "--out", tmp_path / "bare", tmp_path / "p.h5")
    for out in ("fig", "bare"):
        for name in ("periodic_plane_p", "periodic_period_p", "periodic_trace_p"):
            for ext in ("pdf", "png"):
                assert (tmp_path / out / f"{name}.{ext}").stat().st_size > 1000, (out, name, ext)


def test_periodic_refusals(tmp_path, capsys, monkeypatch):
    periodic_file(tmp_path / "p.h5")
    bifurcation_file(tmp_path / "b.h5")
    x = tmp_path / "x"
    assert "b.h5: no /periodic group" in refused(capsys, monkeypatch, "--out", x, tmp_path / "b.h5")
    err = refused(capsys, monkeypatch, "--out", x, "--branches", tmp_path / "p.h5", tmp_path / "p.h5")
    assert "--branches" in err and "no /equilibria" in err
    (tmp_path / "junk.h5").write_text("not hdf5")
    assert "junk.h5: cannot read" in refused(capsys, monkeypatch, "--out", x, tmp_path / "junk.h5")
    with h5py.File(tmp_path / "p.h5", "a") as f:
        f["periodic/stability"][0] = "unstable"
    assert "/periodic/stability holds 'unstable'" in refused(capsys, monkeypatch, "--out", x, tmp_path / "p.h5")
    assert "give at least one file" in refused(capsys, monkeypatch, "--out", x)
    assert not any(x.glob("*.png"))


def test_crossings_agree_with_lgi_poincare(tmp_path):
    """The crossings periodic_crossings.py computes (DOP853) are lgi poincare's, orbit by orbit."""
    h, T, P, G, _ = ORBITS[0]
    seeds = tmp_path / "seed.csv"
    seeds.write_text("gamma_1,gamma_2,gamma_3,angular_momentum_1,angular_momentum_2,angular_momentum_3\n"
                     + ",".join(repr(v) for v in G + P) + "\n")
    subprocess.run([str(LGI), "poincare", "--scene", str(SCENE), "--l", "2.2", "--h", repr(h), "--seeds", str(seeds),
                    "--t-end", repr(T), "--dt", "1e-3", "--quiet", "--out", str(tmp_path / "s.h5")], check=True)
    with h5py.File(tmp_path / "s.h5") as f:
        e = np.array([float(f["parameters"].attrs[f"axis_{k}"]) for k in (1, 2, 3)])
        theirs = np.column_stack([f["events"][k][()] for k in ("phi", "theta", "sheet")])
    J, w = pc.body_of(SCENE.read_text())
    mine = np.array(pc.crossings(np.array(P + G), T, J, w, e / np.linalg.norm(e), True))
    assert len(mine) == len(theirs) == 12
    assert np.max(np.abs(mine - theirs)) < 1e-8  # measured 2e-11
    # the figure: both orbits at h (the elliptic one 0.008 away), one line on stderr saying so
    periodic_file(tmp_path / "p.h5", ORBITS)
    subprocess.run([str(LGI), "poincare", "--scene", str(SCENE), "--l", "2.2", "--h", repr(h), "--ics", "4",
                    "--t-end", "40", "--quiet", "--out", str(tmp_path / "sec.h5")], check=True)
    r = run("poincare.py", "--out", tmp_path / "fig", "--periodic", tmp_path / "p.h5", tmp_path / "sec.h5")
    assert "2 periodic orbit(s)" in r.stderr
    assert (tmp_path / "fig" / "poincare_sec.png").stat().st_size > 1000
    # the marks drawn (listed beside the figure) of the first orbit are its crossings, on the torus angle
    listed = np.genfromtxt(tmp_path / "fig" / "poincare_sec_periodic.csv", delimiter=",", names=True, dtype=None,
                           encoding=None)
    first = listed[listed["family"] == 0]
    drawn = np.column_stack([mine[:, 0], np.where(mine[:, 2] > 0, mine[:, 1], 2 * np.pi - mine[:, 1])])
    assert (first["panel"] == 0).all() and (first["stability"] == "inverse_hyperbolic").all()
    assert (first["mark"] == "hyperbolic").all() and len(first) == 12
    assert np.array_equal(np.column_stack([first["x"], first["y"]]), drawn)
    # /manifolds of the first orbit (as lgi periodic --manifolds writes it) drawn, in a --zoom window
    with h5py.File(tmp_path / "p.h5", "a") as f:
        g = f.create_group("manifolds")
        g["family"], g["index"] = np.zeros(4, dtype=np.int64), np.zeros(4, dtype=np.int64)
        g["branch"] = np.array(["unstable", "unstable", "stable", "stable"], dtype=h5py.string_dtype())
        g["phi"], g["theta"], g["sheet"] = np.array([1.0, 1.1, 1.2, 1.3]), np.full(4, 2.0), np.array([1, 1, -1, -1])
    r = run("poincare.py", "--out", tmp_path / "fig4", "--periodic", tmp_path / "p.h5", "--zoom", "0.5:2:1:5.5",
            tmp_path / "sec.h5")
    assert (tmp_path / "fig4" / "poincare_sec.png").stat().st_size > 1000
    r = run("poincare.py", "--out", tmp_path / "fig5", "--zoom", "2:1:0:1", tmp_path / "sec.h5", code=2)
    assert "--zoom" in r.stderr
    table = {"l": np.array([2.2, 2.2, 2.2]), "h": np.array([h, h + 0.008, h + 0.0005]),
             "family": np.array([0, 1, 1]), "event": np.array(["none"] * 3, dtype=object)}
    assert pc.orbits_at(table, 2.2, h, 1e-3) == [0, 2]  # of each family the nearest, within the tolerance
    assert pc.orbits_at(table, 2.2, h, 1e-2) == [0, 2] and pc.orbits_at(table, 2.3, h, 1e-2) == []
    r = run("poincare.py", "--out", tmp_path / "fig3", "--periodic", tmp_path / "sec.h5", tmp_path / "sec.h5", code=2)
    assert "--periodic" in r.stderr and "not a file written by lgi periodic" in r.stderr
