"""The atlas figure scripts as a user runs them: scripts/plots/region.py on
`lgi region` files (single levels, combined into the seed's panel figure, and
--cells), scripts/plots/bifurcation.py on `lgi bifurcation --appelrot` (the
Kovalevskaya (h, k) diagram) and scripts/plots/chaos_map.py on `lgi chaos-map`
(experiments/REGION.md, EQUILIBRIA.md, CHAOS_MAP.md)."""
import subprocess
from script_env import ENV, PLOTS, ROOT, SCENES, lgi


def plot(script, out, *args):
    r = subprocess.run(["/usr/bin/python3", str(PLOTS / script), "--out", str(out), *map(str, args)], env=ENV,
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    return r


def written(out, name):
    return all((out / f"{name}.{ext}").stat().st_size > 1000 for ext in ("pdf", "png"))


def test_region_figures(tmp_path):
    scene = SCENES / "lagrange_top_oblate.toml"
    singles = []
    for k, (l, h) in enumerate(((2.5, 2.3), (2.5, 2.9), (1.0, 0.0), (2.5, 3.5))):
        singles.append(tmp_path / f"r{k}.h5")
        lgi("region", "--scene", scene, "--l", l, "--h", h, "--grid", "40", "--out", singles[-1])
    cells = tmp_path / "cells.h5"
    lgi("region", "--scene", scene, "--cells", "--l-range", "0:3:7", "--h-range", "-1.2:3:9", "--grid", "40",
        "--samples", "60", "--out", cells)
    out = tmp_path / "fig"
    plot("region.py", out, singles[0], cells)
    assert written(out, "region_r0") and written(out, "region_cells_cells")
    plot("region.py", out, "--combine", "lagrange_potentials", *singles)
    assert written(out, "lagrange_potentials")
    r = subprocess.run(["/usr/bin/python3", str(PLOTS / "region.py"), "--out", str(out / "x"),
                        str(ROOT / "experiments" / "scenes" / "kovalevskaya.toml")], env=ENV, capture_output=True)
    assert r.returncode != 0


def test_appelrot_and_chaos_map_figures(tmp_path):
    kov = tmp_path / "kov.h5"
    lgi("bifurcation", "--scene", SCENES / "kovalevskaya.toml", "--samples", "60", "--appelrot", "0,1",
        "--appelrot-h", "-1:3:9", "--out", kov)
    out = tmp_path / "fig"
    plot("bifurcation.py", out, kov)
    assert written(out, "appelrot_kov") and written(out, "bifurcation_kov")
    cm = tmp_path / "cm.h5"
    lgi("chaos-map", "--scene", SCENES / "general_top_richter.toml", "--l-range", "0.5:1.5:2", "--h-range",
        "-0.5:1.5:3", "--ics", "2", "--t-end", "20", "--out", cm)
    branches = tmp_path / "g.h5"
    lgi("bifurcation", "--scene", SCENES / "general_top_richter.toml", "--samples", "60", "--out", branches)
    plot("chaos_map.py", out, "--branches", branches, cm)
    assert written(out, "chaos_map_cm")


def test_cardan_chaos_map_figure(tmp_path):
    """A Cardan map (--vary): the varied key on the horizontal axis; --branches refused."""
    cm = tmp_path / "tilt.h5"
    lgi("chaos-map", "--scene", SCENES / "cardan_general_asymmetric_up.toml", "--vary",
        "suspension.tilt=0:1.5707963267948966:3", "--h-range", "-0.95:1:3", "--ics", "2", "--t-end", "5",
        "--dt", "0.01", "--out", cm)
    out = tmp_path / "fig"
    plot("chaos_map.py", out, cm)
    assert written(out, "chaos_map_tilt")
    r = subprocess.run(["/usr/bin/python3", str(PLOTS / "chaos_map.py"), "--out", str(out), "--branches", str(cm),
                        str(cm)], env=ENV, capture_output=True, text=True)
    assert r.returncode != 0
