"""scripts/plots/quantum_compare.py and quantum_levels.py as a user runs them
(experiments/QUANTUM.md "Measured"): two tops at l = 1 over h in [1, 2], each
with `lgi quantum --statistics --energy-window` and a small `lgi chaos-map`,
make the comparison figure, its Markdown table and its LaTeX tabular; three
runs of Richter's top at m = 0 make the levels-against-hbar figure; and
quantum.py draws the Euler top's EBK panel from free-body /ebk files."""
import subprocess
from script_env import ENV, PLOTS, SCENES, lgi


def script(name, *args):
    return subprocess.run(["/usr/bin/python3", str(PLOTS / name), *map(str, args)], env=ENV, capture_output=True,
                          text=True)


def test_quantum_compare(tmp_path):
    cases = []
    for label, stem, extra in (("Lagrange", "lagrange_top_cigar", ["--levels", 60]),
                               ("Richter", "general_top_richter", ["--levels", 60])):
        q, k = tmp_path / f"q_{stem}.h5", tmp_path / f"c_{stem}.h5"
        lgi("quantum", "--scene", SCENES / f"{stem}.toml", "--hbar", 0.25, "--m", 4, "--jmax", 20, *extra,
            "--statistics", "--energy-window", "1:2", "--out", q)
        lgi("chaos-map", "--scene", SCENES / f"{stem}.toml", "--l-range", "1:1:1", "--h-range", "1:2:2", "--ics", 6,
            "--t-end", 60, "--out", k)
        cases += ["--case", label, q, k]
    out = tmp_path / "fig"
    r = script("quantum_compare.py", "--out", out, "--tex", tmp_path / "t.tex", "--markdown", tmp_path / "t.md",
               *cases)
    assert r.returncode == 0, r.stderr
    assert all((out / f"quantum_compare.{ext}").stat().st_size > 1000 for ext in ("pdf", "png"))
    md = (tmp_path / "t.md").read_text().splitlines()
    assert len(md) == 4 and md[2].startswith("| Lagrange | 1..2 | 0.25, 4 |") and "| GUE |" in md[3]
    tex = (tmp_path / "t.tex").read_text()
    assert tex.startswith("\\begin{tabular}") and tex.count("\\\\\n") == 4 and "$\\pm$" in tex
    # A chaos-map file where a quantum file belongs is refused with a line naming it.
    bad = script("quantum_compare.py", "--out", out, "--case", "x", cases[3], cases[3])
    assert bad.returncode != 0 and "statistics" in bad.stderr


def test_quantum_levels_and_euler_ebk(tmp_path):
    files = []
    for hbar, jmax in ((0.2, 16), (0.1, 24), (0.07, 30)):
        files.append(tmp_path / f"r_{hbar}.h5")
        lgi("quantum", "--scene", SCENES / "general_top_richter.toml", "--hbar", hbar, "--jmax", jmax, "--levels", 6,
            "--out", files[-1])
    r = script("quantum_levels.py", "--out", tmp_path / "lv", "--levels", 6, *files)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "lv" / "quantum_levels.png").stat().st_size > 1000
    assert script("quantum_levels.py", "--out", tmp_path / "x", files[0]).returncode != 0
    euler = []
    for j in (10, 20):
        euler.append(tmp_path / f"e_{j}.h5")
        lgi("quantum", "--scene", SCENES / "free_body_hlw.toml", "--hbar", 1 / (j + 0.5), "--m", j, "--jmax", j,
            "--ebk", "--out", euler[-1])
    r = script("quantum.py", "--out", tmp_path / "eb", *euler)
    assert r.returncode == 0, r.stderr
    assert (tmp_path / "eb" / "quantum.png").stat().st_size > 1000
