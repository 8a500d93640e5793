"""The tops-atlas figure scripts as a user runs them: `lgi bifurcation` on a
general top, a Lagrange top and a free body, then scripts/plots/bifurcation.py
draws each (l, h) diagram (experiments/EQUILIBRIA.md)."""
import os
import subprocess
from pathlib import Path

import h5py
import numpy as np

ROOT = Path(__file__).resolve().parents[2]
LGI = Path(os.environ.get("LGI_EXECUTABLE", ROOT / "build" / "release" / "lgi"))
ENV = dict(os.environ, PYTHONDONTWRITEBYTECODE="1", MPLBACKEND="Agg")


def test_bifurcation_diagrams(tmp_path):
    files = []
    for scene in ("general_top_richter", "gyroscope", "free_body_hlw"):
        out = tmp_path / f"{scene}.h5"
        subprocess.run([str(LGI), "bifurcation", "--scene", str(ROOT / "experiments" / "scenes" / f"{scene}.toml"),
                        "--out", str(out), "--quiet"], check=True)
        with h5py.File(out, "r") as f:
            t = f["equilibria"]
            assert len(t["l"]) > 100
            # dh/dl = omega along a branch (docs/atlas.md §2), away from folds and poles.
            sel = (t["branch"][()] == t["branch"][0]) & (t["fold"][()] == 0)
            l, h, w = t["l"][()][sel], t["h"][()][sel], t["omega"][()][sel]
            mid = slice(len(l) // 4, 3 * len(l) // 4)
            slope = np.gradient(h[mid], l[mid])
            assert np.median(np.abs(slope - w[mid]) / np.abs(w[mid])) < 1e-2
        files.append(out)
    subprocess.run(["/usr/bin/python3", str(ROOT / "scripts" / "plots" / "bifurcation.py"), "--out",
                    str(tmp_path / "fig"), *map(str, files)], check=True, env=ENV, capture_output=True)
    for scene in ("general_top_richter", "gyroscope", "free_body_hlw"):
        for ext in ("pdf", "png"):
            assert (tmp_path / "fig" / f"bifurcation_{scene}.{ext}").stat().st_size > 1000
