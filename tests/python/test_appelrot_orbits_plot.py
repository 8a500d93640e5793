"""bifurcation.py --periodic (scripts/plots/appelrot_orbits.py; experiments/PERIODIC.md,
"Kovalevskaya's top: critical orbits"): the orbits of /periodic tables drawn into
the (h, k) diagram at each panel's l only, h divided by J3 c, NaN k (another top)
skipped; the figure written over an `lgi bifurcation --appelrot` file, and a
/periodic file without the k column refused with one line naming it (exit 1)."""
import subprocess
import sys

import h5py
import matplotlib
import numpy as np
from script_env import ENV, PLOTS, SCENES, lgi

matplotlib.use("Agg")
sys.path.insert(0, str(PLOTS))
import appelrot_orbits  # noqa: E402
import lgi_plot_common as c  # noqa: E402


def table(k=True):
    t = {"family": np.array([0, 0, 0, 1, 1, 2]), "l": np.array([1.0, 1.0, 1.0, 1.0, 1.0, 0.5]),
         "h": np.array([2.0, 2.2, 2.4, 3.0, 3.2, 1.0]),
         "stability": np.array(["elliptic", "elliptic", "hyperbolic", "inverse_hyperbolic", "elliptic", "elliptic"],
                               dtype=object)}
    t["k"] = np.array([0.0, 0.0, 0.0, 1.0, 1.1, 0.3]) if k else np.full(6, np.nan)
    return t


def test_draw_selects_the_panel_and_scales_h():
    fig, ax = c.plt.subplots()
    assert appelrot_orbits.draw(ax, 1.0, 2.0, [table()]) == 5
    xs = np.concatenate([line.get_xdata() for line in ax.lines])
    assert np.isclose(xs.min(), 1.0) and np.isclose(xs.max(), 1.6)  # h / (J3 c), l = 0.5 left out
    assert appelrot_orbits.draw(ax, 1.0, 1.0, [table(k=False)]) == 0
    assert len(appelrot_orbits.legend_entries([table()])) == 3
    c.plt.close(fig)


def test_bifurcation_figure_with_orbits(tmp_path):
    kov = tmp_path / "kov.h5"
    lgi("bifurcation", "--scene", SCENES / "kovalevskaya.toml", "--samples", "60", "--appelrot", "0,1",
        "--appelrot-h", "-1:3:9", "--out", kov)
    good, bad = tmp_path / "p.h5", tmp_path / "old.h5"
    for path, with_k in ((good, True), (bad, False)):
        with h5py.File(path, "w") as f:
            for name, v in table().items():
                if name == "k" and not with_k:
                    continue
                f.create_dataset(f"periodic/{name}", data=v.astype("S") if v.dtype == object else v)
    out = tmp_path / "fig"
    r = subprocess.run(["/usr/bin/python3", str(PLOTS / "bifurcation.py"), "--out", str(out), "--periodic", str(good),
                        str(kov)], env=ENV, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert all((out / f"appelrot_kov.{e}").stat().st_size > 1000 for e in ("pdf", "png"))
    r = subprocess.run(["/usr/bin/python3", str(PLOTS / "bifurcation.py"), "--out", str(out), "--periodic", str(bad),
                        str(kov)], env=ENV, capture_output=True, text=True)
    assert r.returncode == 2 and str(bad) in r.stderr and "column k" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1
