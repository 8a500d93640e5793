"""scripts/plots/poincare.py as a user runs it: `lgi poincare` on the
Kovalevskaya top (coloured by orbit) and on the general top with --megno
(coloured by MEGNO), then the figures (experiments/POINCARE.md)."""
import os
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LGI = Path(os.environ.get("LGI_EXECUTABLE", ROOT / "build" / "release" / "lgi"))
ENV = dict(os.environ, PYTHONDONTWRITEBYTECODE="1", MPLBACKEND="Agg")
SCRIPT = ROOT / "scripts" / "plots" / "poincare.py"


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
    assert r.returncode == 1 and "--megno" in r.stderr
