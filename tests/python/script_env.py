"""What the script tests (tests/python) share: the repository's folders, the lgi under test,
the environment a plot script runs in (no bytecode, a headless matplotlib), and lgi run quietly."""
import os
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LGI = Path(os.environ.get("LGI_EXECUTABLE", ROOT / "build" / "release" / "lgi"))
ENV = dict(os.environ, PYTHONDONTWRITEBYTECODE="1", MPLBACKEND="Agg")
SCENES = ROOT / "experiments" / "scenes"
PLOTS = ROOT / "scripts" / "plots"


def lgi(*args):
    subprocess.run([str(LGI), *map(str, args), "--quiet"], check=True)
