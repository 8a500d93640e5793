"""The command tests' way to run lgi (tests/commands): run it, read a table of its
output file, and check a refusal (exit 2 and one line on stderr, README "Using lgi")."""
import os
import subprocess

import h5py

LGI = os.environ.get("LGI_EXECUTABLE", "build/release/lgi")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")


def lgi(*args, check=True):
    r = subprocess.run([LGI, *args], capture_output=True, text=True, timeout=600)
    if check:
        assert r.returncode == 0, r.stderr
    return r


def columns(path, name):
    """The columns of group /name."""
    with h5py.File(path, "r") as f:
        return {k: f[name][k][()] for k in f[name]}


def table(path, name):
    """The columns of group /name and the /parameters attributes."""
    with h5py.File(path, "r") as f:
        return {k: f[name][k][()] for k in f[name]}, dict(f["parameters"].attrs)


def refused(*args):
    """Runs lgi, expects exit 2 and one line "lgi: ..." on stderr, and returns that line."""
    r = lgi(*args, check=False)
    assert r.returncode == 2, (r.returncode, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("lgi: "), r.stderr
    return lines[0]
