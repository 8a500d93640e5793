"""`lgi indicators` as a user runs it (experiments/INDICATORS.md):
 - with --state-file from an `lgi equilibria` file of general_top_richter:
   one row per equilibrium, the contract's columns and the CSV beside it;
   every singly unstable equilibrium's lyapunov_last_half is Grammel's rate
   sqrt(z+) from the file's g1, g2 to 1e-3; the spectrum sums to 0;
 - the CSV beside the equilibria file gives the same numbers bit for bit;
 - the scene's initial state, set with [initial] gamma;
 - bad input: one line on stderr and exit 2."""
import os

import numpy as np
from lgi_cli import lgi, refused, table

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
GENERAL = os.path.join(ROOT, "experiments", "scenes", "general_top_richter.toml")
COLUMNS = ["index", "lyapunov", "lyapunov_last_half", "megno", "t_end", "converged"]


def test_equilibria_state_file(tmp_path):
    eq, out = str(tmp_path / "eq.h5"), str(tmp_path / "ind.h5")
    lgi("equilibria", "--scene", GENERAL, "--l", "3", "--out", eq, "--quiet")
    r = lgi("indicators", "--scene", GENERAL, "--state-file", eq, "--t-end", "40", "--dt", "0.005", "--spectrum",
            "--out", out)
    assert "lyapunov_last_half=" in r.stdout and "wrote" in r.stdout
    e, _ = table(eq, "equilibria")
    d, p = table(out, "indicators")
    n = len(e["h"])
    for c in COLUMNS:
        assert d[c].shape == (n,), c
    assert d["spectrum"].shape == (n, 6)
    assert d["index"].dtype == np.int64 and list(d["index"]) == list(range(n))
    assert set(d["converged"]) <= {0, 1} and np.all(d["t_end"] == 40.0)
    assert np.abs(d["gamma"] - e["gamma"]).max() < 1e-15
    assert np.array_equal(d["angular_momentum"], e["angular_momentum"])
    assert p["subcommand"] == "indicators" and "--state-file" in p["command_line"] and p["scheme"] == "rkmk4"
    unstable = np.flatnonzero(e["stability"] == 1)
    assert len(unstable) >= 2
    for i in unstable:
        rate = np.sqrt(0.5 * (-e["g1"][i] + np.sqrt(e["g1"][i] ** 2 - 4 * e["g2"][i])))
        assert abs(d["lyapunov_last_half"][i] - rate) <= 1e-3, (i, d["lyapunov_last_half"][i], rate)
    assert np.abs(d["spectrum"].sum(axis=1)).max() < 1e-8
    with open(str(tmp_path / "ind.csv")) as f:
        header = f.readline().strip().split(",")
    assert header[:6] == COLUMNS and "spectrum_6" in header and "gamma_3" in header
    # The CSV beside the equilibria file: the same states to the bit, the same numbers.
    out_csv = str(tmp_path / "ind_csv.h5")
    lgi("indicators", "--scene", GENERAL, "--state-file", str(tmp_path / "eq.csv"), "--t-end", "40", "--dt", "0.005",
        "--spectrum", "--out", out_csv, "--quiet")
    c, _ = table(out_csv, "indicators")
    for k in COLUMNS + ["spectrum", "gamma", "angular_momentum"]:
        assert np.array_equal(c[k], d[k]), k


def test_scene_initial_state_with_gamma(tmp_path):
    scene = tmp_path / "top.toml"
    with open(GENERAL) as f:
        text = f.read()
    body = text[: text.index("[initial]")]
    scene.write_text(body + "[initial]\ngamma = [0.0, 0.6, 0.8]\nangular_velocity = [1.0, 0.5, 0.5]\n"
                     "[run]\nt_end = 20\ndt = 0.01\n")
    out = str(tmp_path / "one.h5")
    lgi("indicators", "--scene", str(scene), "--out", out, "--quiet")
    d, p = table(out, "indicators")
    assert d["index"].tolist() == [0] and d["t_end"][0] == 20.0 and p["dt"] == "0.01"
    assert np.abs(d["gamma"][0] - [0.0, 0.6, 0.8]).max() < 1e-15
    assert np.isfinite(d["lyapunov"][0]) and np.isfinite(d["megno"][0])
    assert "spectrum" not in d


def test_bad_input(tmp_path):
    out = str(tmp_path / "x.h5")
    assert "--scheme" in refused("indicators", "--scene", GENERAL, "--scheme", "rk4", "--out", out)
    missing = str(tmp_path / "none.h5")
    assert missing in refused("indicators", "--scene", GENERAL, "--state-file", missing, "--out", out)
    bad_csv = tmp_path / "bad.csv"
    bad_csv.write_text("gamma_1,gamma_2,gamma_3\n0,0,1\n")
    assert "angular_momentum_1" in refused("indicators", "--scene", GENERAL, "--state-file", str(bad_csv), "--out", out)
    zero = tmp_path / "zero.toml"
    with open(GENERAL) as f:
        text = f.read()
    zero.write_text(text[: text.index("[initial]")] + "[initial]\ngamma = [0, 0, 0]\n")
    assert "[initial] gamma" in refused("indicators", "--scene", str(zero), "--out", out)
    assert "--t-end" in refused("indicators", "--scene", GENERAL, "--t-end", "-1", "--out", out)
    lgi("indicators", "--scene", GENERAL, "--t-end", "1", "--out", out, "--quiet")
    assert "exists" in refused("indicators", "--scene", GENERAL, "--t-end", "1", "--out", out)
