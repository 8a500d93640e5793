#!/usr/bin/python3
"""Valgrind memcheck over short `lgi simulate` runs (issue 15): no invalid
read or write, no use of an uninitialised value, no definite leak.

Usage: memcheck_simulate.py LGI [--quick]
  --quick   one scheme (rkmk4), a few steps: a check of the run's machinery
            (scene reading, the registry, the loop, the H5MD writer) in seconds
  default   one scheme of every family that `lgi schemes --json` lists (the
            first that applies to the scene, on the free body; on a heavy top
            for families whose schemes need torques to differ, and for the
            Euler-angle charts, whose singular set holds the free body's start), about 20 steps each

Each run is `valgrind --tool=memcheck --error-exitcode=99 --leak-check=full
--errors-for-leak-kinds=definite lgi simulate ...`; a run fails on exit status
99 (memcheck's errors) or any other non-zero status. Suppressions: none.
Prints one line per run with its time; exits 1 if any failed."""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
FREE = os.path.join(SCENES, "free_body_hlw.toml")
TOP = os.path.join(SCENES, "heavy_top_trindade_1.toml")
VALGRIND = ["valgrind", "--tool=memcheck", "--error-exitcode=99", "--leak-check=full",
            "--errors-for-leak-kinds=definite", "--quiet"]


def schemes_by_family(lgi):
    """The first scheme of each family, with the scene it runs on (from the facts of `lgi schemes --json`)."""
    out = {}
    for scene in (FREE, TOP):
        listed = json.loads(subprocess.run([lgi, "schemes", "--json", "--scene", scene], capture_output=True,
                                           text=True, check=True).stdout)
        for s in listed:
            # The free body starts at the identity, on the Euler-angle chart's singular set (theta = 0),
            # where euler-zxz/* refuse to start: the charts run on the heavy top, which starts off it.
            if scene == FREE and s["family"] == "baseline euler-zxz":
                continue
            # One baseline in all (their families are one per chart), one scheme of every other family.
            out.setdefault("baseline" if s["kind"] == "baseline" else s["family"], (s, scene))
    return out


def run(lgi, scheme, scene, folder):
    args = [lgi, "simulate", "--scene", scene, "--scheme", scheme["name"], "--t-end", "0.02", "--force", "--quiet",
            "--out", os.path.join(folder, "memcheck.h5")]
    args += ["--tol", "1e-6"] if scheme.get("adaptive") else ["--dt", "1e-3"]
    start = time.monotonic()
    r = subprocess.run(VALGRIND + args, capture_output=True, text=True, timeout=900)
    ok = r.returncode == 0
    print(f"memcheck {scheme['name']:<28} {os.path.basename(scene):<28} {time.monotonic() - start:6.1f} s  "
          f"{'ok' if ok else 'FAILED (exit %d)' % r.returncode}", flush=True)
    if not ok:
        print(r.stderr[-4000:], file=sys.stderr)
    return ok


def main():
    if len(sys.argv) < 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(sys.argv) > 1 else 2
    lgi = os.path.abspath(sys.argv[1])
    quick = "--quick" in sys.argv[2:]
    if shutil.which("valgrind") is None:
        print("memcheck_simulate: valgrind not found (scripts/install-deps.sh installs it)", file=sys.stderr)
        return 1
    if quick:
        cases = [({"name": "rkmk4", "adaptive": False}, FREE)]
    else:
        cases = [(s, scene) for s, scene in schemes_by_family(lgi).values()]
    with tempfile.TemporaryDirectory(prefix="lgi-memcheck-") as folder:
        failed = [s["name"] for s, scene in cases if not run(lgi, s, scene, folder)]
    if failed:
        print("memcheck_simulate: errors in " + ", ".join(failed), file=sys.stderr)
        return 1
    print(f"memcheck_simulate: {len(cases)} runs, 0 errors")
    return 0


if __name__ == "__main__":
    sys.exit(main())
