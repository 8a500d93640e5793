"""`lgi periodic` as a user runs it (experiments/PERIODIC.md):
 - --from-equilibria on general_top_richter at l = 3: the contract's columns
   under /periodic with their shapes, the CSV beside it; every family's first
   period is 2*pi/omega to 1e-6; residuals <= 1e-10; four multipliers at 1
   to 1e-8 on first orbits, their product 1 to 1e-8; stability and event texts from the contract;
 - --seed-file: a seed from that file's last orbit is found again;
 - bad input: one line on stderr naming the flag, exit 2."""
import math
import os

import h5py
import numpy as np
from lgi_cli import lgi, refused

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GENERAL = os.path.join(ROOT, "experiments", "scenes", "general_top_richter.toml")
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
    assert not os.path.exists(out)
