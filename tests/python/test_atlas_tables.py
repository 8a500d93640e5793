"""scripts/plots/atlas_tables.py, the tables of the paper's section "The global
dynamics of tops": every equilibrium of the files in the table, MEGNO medians
and chaotic fractions that tell the integrable top from the general one."""
import os
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LGI = Path(os.environ.get("LGI_EXECUTABLE", ROOT / "build" / "release" / "lgi"))
ENV = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
SCRIPT = ROOT / "scripts" / "plots" / "atlas_tables.py"
SCENES = ROOT / "experiments" / "scenes"


def lgi(*args):
    subprocess.run([str(LGI), *args, "--quiet"], check=True)


def test_atlas_tables(tmp_path):
    lgi("equilibria", "--scene", str(SCENES / "general_top_richter.toml"), "--l", "3", "--out", str(tmp_path / "e.h5"))
    for stem in ("kovalevskaya", "general_top_richter"):
        lgi("poincare", "--scene", str(SCENES / f"{stem}.toml"), "--l", "1", "--h", "2", "--ics", "6",
            "--t-end", "150", "--megno", "--out", str(tmp_path / f"{stem}.h5"))
    (tmp_path / "cmds.txt").write_text("lgi equilibria --l 3\n")
    subprocess.run(["/usr/bin/python3", str(SCRIPT), "--out", str(tmp_path / "gen"), "--equilibria",
                    str(tmp_path / "e.h5"), "--sections", str(tmp_path / "kovalevskaya.h5"),
                    str(tmp_path / "general_top_richter.h5"), "--commands", str(tmp_path / "cmds.txt")],
                   check=True, env=ENV)
    eq = (tmp_path / "gen" / "atlas_equilibria.tex").read_text()
    # l = 3 has six permanent rotations (lgi equilibria --l 3), one row each
    assert sum(1 for ln in eq.splitlines() if ln.startswith("3 & ")) == 6
    rows = [ln for ln in (tmp_path / "gen" / "atlas_megno.tex").read_text().splitlines() if " & 6 & " in ln]
    assert len(rows) == 2
    kov, gen = (float(r.split("&")[4]) for r in rows)
    # regular orbits approach 2, from below near stable periodic orbits (docs/atlas.md §7): 6 orbits
    # of the Liouville draw at t = 150 have the median 1.56; the general top's are chaotic
    assert 1.0 < kov < 2.5 and gen > 3.0
    # the measure, and the chaotic fraction k/6 with its 95 % Wilson interval (0/6: [0.00, 0.39])
    assert all(r.split("&")[1].strip() == "liouville" for r in rows)
    for r in rows:
        k = round(6 * float(r.split("&")[5].split()[0]))
        assert r.split("&")[5].strip().startswith(
            {0: "0.00 [0.00, 0.39]", 3: "0.50 [0.19, 0.81]", 6: "1.00 [0.61, 1.00]"}.get(k, f"{k / 6:.2f} ["))
    assert "lgi equilibria --l 3" in (tmp_path / "gen" / "atlas_commands.tex").read_text()
    # a file that is not lgi equilibria output: one line, exit 1
    r = subprocess.run(["/usr/bin/python3", str(SCRIPT), "--out", str(tmp_path / "gen2"), "--equilibria",
                        str(tmp_path / "kovalevskaya.h5"), "--sections", str(tmp_path / "kovalevskaya.h5")],
                       env=ENV, capture_output=True, text=True)
    assert r.returncode == 2 and "no /equilibria" in r.stderr


def test_long_commands_are_wrapped_for_the_page():
    """The paper's verbatim block of atlas commands: no line over the width a
    footnotesize line of the text width holds, continued with a backslash, broken
    before an option, and the same command once the continuations are joined."""
    import sys
    sys.path.insert(0, str(SCRIPT.parent))
    from atlas_tables import COMMAND_WIDTH, wrapped_command
    line = ("lgi poincare --scene experiments/scenes/cardan_general_asymmetric_up.toml --l 1.6814407530796442 "
            "--h 2.2145076834471573 --ics 3 --t-end 100 --dt 0.005 --megno --lyapunov "
            "--out cardan/megno_cardan_general_asymmetric_up.h5")
    parts = wrapped_command(line)
    assert len(parts) > 1 and all(len(p) <= COMMAND_WIDTH for p in parts)
    assert all(p.endswith(" \\") for p in parts[:-1]) and not parts[-1].endswith("\\")
    assert all(p.startswith("    --") for p in parts[1:])  # each continuation starts at an option
    assert " ".join(p.removesuffix(" \\").strip() for p in parts) == line
    assert wrapped_command("lgi equilibria --l 3") == ["lgi equilibria --l 3"]
    # a negative value stays with its option
    ranged = ("lgi region --scene experiments/scenes/lagrange_top_oblate.toml --cells --l-range 0:3:41 "
              "--h-range -1.2:3:41 --out region/lagrange_top_oblate.h5")
    assert any(p.strip().startswith("--h-range -1.2:3:41") for p in wrapped_command(ranged))
