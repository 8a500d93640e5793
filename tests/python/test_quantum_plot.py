"""scripts/plots/quantum.py as a user runs it (experiments/QUANTUM.md): EBK
against exact levels of the Lagrange top from `lgi quantum --ebk` files at two
hbar, and the spacing histogram from a `lgi quantum --statistics` file; a file
with neither group is refused."""
import subprocess
from script_env import ENV, ROOT, SCENES, lgi


def plot(out, *files):
    return subprocess.run(["/usr/bin/python3", str(ROOT / "scripts" / "plots" / "quantum.py"), "--out", str(out),
                           *map(str, files)], env=ENV, capture_output=True, text=True)


def test_quantum_figure(tmp_path):
    files = []
    for hbar, jmax in ((0.1, 30), (0.05, 40)):
        files.append(tmp_path / f"ebk_{hbar}.h5")
        lgi("quantum", "--scene", SCENES / "lagrange_top_cigar.toml", "--hbar", hbar, "--m", 1, "--jmax", jmax,
            "--levels", 10, "--ebk", "--out", files[-1])
    files.append(tmp_path / "stat.h5")
    lgi("quantum", "--scene", SCENES / "lagrange_top_cigar.toml", "--hbar", 0.1, "--m", 1, "--jmax", 40,
        "--levels", 100, "--statistics", "--out", files[-1])
    out = tmp_path / "fig"
    r = plot(out, *files)
    assert r.returncode == 0, r.stderr
    assert all((out / f"quantum.{ext}").stat().st_size > 1000 for ext in ("pdf", "png"))
    plain = tmp_path / "plain.h5"
    lgi("quantum", "--scene", SCENES / "free_body_hlw.toml", "--hbar", 1, "--jmax", 3, "--out", plain)
    assert plot(tmp_path / "x", plain).returncode != 0
