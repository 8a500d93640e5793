"""scripts/unseen_tops.py: random general heavy tops, each from its own seed, their scene
files as the built lgi reads them, and the cost-at-equal-error ratios it prints."""
import json
import os
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SCRIPT = ROOT / "scripts" / "unseen_tops.py"
PY = "/usr/bin/python3"
LGI = Path(os.environ.get("LGI_EXECUTABLE", ROOT / "build" / "release" / "lgi"))
ENV = dict(os.environ, PYTHONDONTWRITEBYTECODE="1", MPLBACKEND="Agg")

sys.path.insert(0, str(ROOT / "scripts"))
import unseen_tops  # noqa: E402


def test_tops_are_general_and_seeded_per_item():
    tops = [unseen_tops.draw_top(1, k) for k in range(20)]
    assert unseen_tops.draw_top(1, 7) == tops[7]  # the k-th top does not depend on the ones before it
    assert unseen_tops.draw_top(2, 7) != tops[7]
    for top in tops:
        a, b, c = top["inertia"]
        assert a + b > c and a + c > b and b + c > a  # a body's moments about a point
        for x, y in ((a, b), (a, c), (b, c)):
            assert abs(x - y) >= 0.05 * max(x, y) * (1 - 1e-12)  # no near-symmetric top
        chi = sum(v * v for v in top["center_of_mass"]) ** 0.5
        assert 0.2 <= chi <= 1.0 and min(abs(v) for v in top["center_of_mass"]) > 0.0
        omega = sum(v * v for v in top["angular_velocity"]) ** 0.5
        assert 1.0 <= omega <= 4.0


def test_scene_file_round_trips():
    top = unseen_tops.draw_top(3, 0)
    scene = tomllib.loads(unseen_tops.scene_toml(top, 3, 0))
    assert scene["body"]["inertia"] == top["inertia"]  # repr() keeps every bit
    assert scene["body"]["center_of_mass"] == top["center_of_mass"]
    assert scene["initial"]["angular_velocity"] == top["angular_velocity"]
    assert scene["gravity"]["g"] == 1.0 and scene["run"]["t_end"] == 10.0


def test_summary_counts_tops_at_the_bar():
    per_top = [[("a", 1.0, "q", 2.0), ("a", 1.0, "q", 4.0)], [("a", 3.0, "q", 4.0), None]]
    assert unseen_tops.summary(per_top, [1e-6, 1e-8], 0.5) == [
        "# at error 1e-06: median 0.625, largest 0.750, 1 of 2 tops at or below 0.5",
        "# at error 1e-08: median 0.250, largest 0.250, 1 of 1 tops at or below 0.5"]


def test_runs_lgi_on_each_top(tmp_path):
    if not LGI.exists():
        pytest.skip(f"no lgi at {LGI}")
    out = tmp_path / "ratios.json"
    p = subprocess.run([PY, SCRIPT, "--count", "2", "--seed", "5", "--lgi", LGI, "--repeat", "1",
                        "--tolerances", "1e-5,1e-6,1e-7,1e-8", "--dts", "0.1", "--lie", "rkmk-dp54,rkmk-cayley-dp54",
                        "--baselines", "quat/dopri5", "--targets", "1e-6", "--keep", tmp_path / "files",
                        "--json", out], capture_output=True, text=True, env=ENV, timeout=120)
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert [l.split(":")[0] for l in lines] == ["# top 0", "# top 1", "# at error 1e-06"], p.stdout
    assert "/ quat/dopri5" in lines[0] and "tops at or below 0.5" in lines[2]
    assert "lgi work-precision on top 1" in p.stderr
    assert (tmp_path / "files" / "top_5_1.toml").is_file() and (tmp_path / "files" / "top_5_1.h5").is_file()
    data = json.loads(out.read_text())
    assert data["seed"] == 5 and len(data["tops"]) == 2 and data["complete"] is True
    assert data["tops"][0]["inertia"] == unseen_tops.draw_top(5, 0)["inertia"]
    r = data["tops"][0]["ratios"][0]
    assert r["baseline"] == "quat/dopri5" and r["ratio"] == pytest.approx(r["lie_group_s"] / r["baseline_s"])


def test_a_failed_top_keeps_the_tops_before_it(tmp_path):
    """A stand-in lgi that runs the real one but fails on top 1: exit 1, top 0 printed,
    summarised and written to the JSON, which says the run is not complete."""
    if not LGI.exists():
        pytest.skip(f"no lgi at {LGI}")
    fake = tmp_path / "lgi"
    fake.write_text(f"""#!/bin/sh
case "$*" in *top_5_1.toml*) echo "lgi: stand-in failure" >&2; exit 1;; esac
exec {LGI} "$@"
""")
    fake.chmod(0o755)
    out = tmp_path / "ratios.json"
    p = subprocess.run([PY, SCRIPT, "--count", "3", "--seed", "5", "--lgi", fake, "--repeat", "1",
                        "--tolerances", "1e-5,1e-6,1e-7,1e-8", "--dts", "0.1", "--lie", "rkmk-dp54",
                        "--baselines", "quat/dopri5", "--targets", "1e-6", "--json", out],
                       capture_output=True, text=True, env=ENV, timeout=120)
    assert p.returncode == 1, p.stderr
    assert [l.split(":")[0] for l in p.stdout.splitlines()] == ["# top 0", "# at error 1e-06"], p.stdout
    assert "failed on top 1 (exit 1)" in p.stderr.splitlines()[-1]
    data = json.loads(out.read_text())
    assert data["complete"] is False and [t["top"] for t in data["tops"]] == [0]


def test_rounds_merge_to_the_least_time_of_each_row():
    row = {"scheme": "a", "dt": "", "tol": "1e-08", "steps": "10", "rejected_steps": "0", "rhs_evaluations": "130",
           "error": "1e-09", "status": "ok", "cpu_seconds_min": "3e-05"}
    failed = dict(row, scheme="b", status="failed: x", cpu_seconds_min="")
    merged = unseen_tops.merge_rounds([[row, failed], [dict(row, cpu_seconds_min="2e-05"), failed],
                                       [dict(row, cpu_seconds_min="4e-05"), failed]])
    assert float(merged[0]["cpu_seconds_min"]) == 2e-05 and merged[1] == failed
    assert float(row["cpu_seconds_min"]) == 3e-05  # the rounds' rows are not changed
    with pytest.raises(ValueError, match="rhs_evaluations is 130 in one round and 131"):
        unseen_tops.merge_rounds([[row], [dict(row, rhs_evaluations="131")]])
    with pytest.raises(ValueError, match="rows"):
        unseen_tops.merge_rounds([[row], [row, row]])


def test_rounds_run_each_top_in_turn_and_a_failure_keeps_every_round(tmp_path):
    """--rounds 2 over 2 tops with a stand-in lgi that fails on its 4th call (top 1's second round):
    top 0 is printed with 2 rounds, top 1 with its 1, the files of every round are kept, exit 1."""
    if not LGI.exists():
        pytest.skip(f"no lgi at {LGI}")
    fake, calls = tmp_path / "lgi", tmp_path / "calls"
    fake.write_text(f"""#!/bin/sh
echo "$*" >> {calls}
[ "$(wc -l < {calls})" -eq 4 ] && {{ echo "lgi: stand-in failure" >&2; exit 1; }}
exec {LGI} "$@"
""")
    fake.chmod(0o755)
    out, files = tmp_path / "ratios.json", tmp_path / "files"
    p = subprocess.run([PY, SCRIPT, "--count", "2", "--seed", "5", "--lgi", fake, "--repeat", "1", "--rounds", "2",
                        "--tolerances", "1e-5,1e-6,1e-7,1e-8", "--dts", "0.1", "--lie", "rkmk-dp54",
                        "--baselines", "quat/dopri5", "--targets", "1e-6", "--keep", files, "--json", out],
                       capture_output=True, text=True, env=ENV, timeout=120)
    assert p.returncode == 1, p.stderr
    assert [c.split("top_5_")[1].split(".toml")[0] for c in calls.read_text().splitlines()] == ["0", "1", "0", "1"]
    assert "on top 1 (round 2 of 2)" in p.stderr and "failed on top 1 (exit 1)" in p.stderr.splitlines()[-1]
    assert [l.split(":")[0] for l in p.stdout.splitlines()] == ["# top 0", "# top 1", "# at error 1e-06"], p.stdout
    assert sorted(f.name for f in files.glob("*.h5")) == ["top_5_0_round1.h5", "top_5_0_round2.h5",
                                                         "top_5_1_round1.h5"]
    data = json.loads(out.read_text())
    assert data["complete"] is False and [(t["top"], t["rounds"]) for t in data["tops"]] == [(0, 2), (1, 1)]


@pytest.mark.parametrize("args, flag", [(["--count", "0"], "--count"), (["--targets", "1e-6,x"], "--targets"),
                                        (["--lgi", "/nonexistent/lgi"], "--lgi"),
                                        (["--rounds", "0"], "--rounds")])
def test_bad_arguments_exit_2_naming_the_flag(args, flag):
    p = subprocess.run([PY, SCRIPT, *args], capture_output=True, text=True, env=ENV, timeout=60)
    assert p.returncode == 2
    assert flag in p.stderr.splitlines()[-1]


def test_a_scheme_lgi_refuses_exits_2():
    if not LGI.exists():
        pytest.skip(f"no lgi at {LGI}")
    p = subprocess.run([PY, SCRIPT, "--count", "1", "--lgi", LGI, "--repeat", "1", "--lie", "no-such-scheme"],
                       capture_output=True, text=True, env=ENV, timeout=60)
    assert p.returncode == 2 and p.stdout == ""
    assert "unknown scheme 'no-such-scheme'" in p.stderr and "failed on top 0 (exit 2)" in p.stderr
