#!/usr/bin/env bash
# Table 1 of Trindade & Sampaio (2001) (seed 001, docs/sources.md) measured on this machine:
# CPU milliseconds of each stepper in Euler angles, rotation vector and
# quaternion coordinates, and of Lie-group schemes, on Trindade cases 1-4
# (scenes heavy_top_trindade_{1,2,3,4}.toml; columns "case N (ms)", the paper's
# "Ex. N") at tolerance 1e-6 (the fixed-step rk4 at dt = 1e-3), t_end as in the scenes.
#
#   scripts/table1.sh [--lgi PATH] [--repeat N] [--tol TOL] [--dt H] [--cases 1,2,3,4] [--out DIR]
#
# Every cell is one `lgi simulate` run repeated N times (default 3); the cell
# is the smallest /diagnostics cpu_seconds of the N, in milliseconds (the
# stepper loop's CPU clock, no file output in between: --save-every is huge),
# or "fail" when the run stops (exit 1; the reason is printed below the
# table). Writes
# DIR/table1.md and DIR/table1.csv (default DIR: build/table1) and prints the
# Markdown table; progress ("table1: case 2 (2/4) quat/rk4, run 41/68") goes to stderr.
# Needs /usr/bin/python3 with h5py (the python3 first on PATH may lack it).
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
lgi="${here}/build/release/lgi"
repeat=3
tol=1e-6
dt=1e-3
out="${here}/build/table1"
cases=1,2,3,4
while [[ $# -gt 0 ]]; do
  case "$1" in
    --lgi) lgi="$2"; shift 2 ;;
    --repeat) repeat="$2"; shift 2 ;;
    --tol) tol="$2"; shift 2 ;;
    --dt) dt="$2"; shift 2 ;;
    --out) out="$2"; shift 2 ;;
    --cases) cases="$2"; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "table1.sh: unknown argument $1" >&2; exit 2 ;;
  esac
done
[[ -x "$lgi" ]] || { echo "table1.sh: no lgi executable at $lgi (use --lgi)" >&2; exit 2; }
mkdir -p "$out"

exec /usr/bin/python3 - "$lgi" "$repeat" "$tol" "$dt" "$out" "${here}/experiments/scenes" "$cases" <<'PY'
import csv, os, subprocess, sys
import h5py

lgi, repeat, tol, dt, out, scenes = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5], sys.argv[6]
cases = [int(x) for x in sys.argv[7].split(",") if x]
if not cases or any(k not in (1, 2, 3, 4) for k in cases):
    sys.exit("table1.sh: --cases takes a comma-separated subset of 1,2,3,4")
coords = [("euler-zxz", "Euler angles"), ("rotvec", "Rotation vector"), ("quat", "Quaternion")]
steppers = ["dopri5", "rkf78", "bs", "rosenbrock4", "rk4"]
lie = [("rkmk-dp54", "tol"), ("rkmk4", "dt")]
tmp = os.path.join(out, "run.h5")
failures = []
total = len(steppers) * len(coords) * len(cases) + len(lie) * len(cases)
done = 0

def run(scheme, case, adaptive):
    global done
    done += 1
    sys.stderr.write("table1: case %d (%d/%d) %s, run %d/%d\n"
                     % (case, cases.index(case) + 1, len(cases), scheme, done, total))
    sys.stderr.flush()
    scene = os.path.join(scenes, "heavy_top_trindade_%d.toml" % case)
    flag = ["--tol", tol] if adaptive else ["--dt", dt]
    best, steps = None, None
    for _ in range(repeat):
        p = subprocess.run([lgi, "simulate", "--scene", scene, "--scheme", scheme, *flag, "--save-every",
                            "1000000000000", "--quiet", "--force", "--out", tmp], capture_output=True, text=True)
        path = tmp if p.returncode == 0 else tmp + ".partial"
        with h5py.File(path, "r") as f:
            d = f["diagnostics"].attrs
            cpu, status, steps = float(d["cpu_seconds"]), d["status"], int(d["steps"])
        for leftover in (tmp, tmp + ".partial"):
            if os.path.exists(leftover):
                os.remove(leftover)
        if isinstance(status, bytes):
            status = status.decode()
        if p.returncode != 0:
            failures.append("%s, case %d: %s" % (scheme, case, status))
            return None, steps
        best = cpu if best is None else min(best, cpu)
    return best, steps

def cell(v):
    return "fail" if v is None else "%.3g" % (1e3 * v)

rows = []
for st in steppers:
    adaptive = st != "rk4"
    label = st + (" (tol %s)" % tol if adaptive else " (dt %s)" % dt)
    row = {"method": label}
    for c, _ in coords:
        for case in cases:
            v, n = run(c + "/" + st, case, adaptive)
            row["%s case %d" % (c, case)] = cell(v)
            row["%s case %d steps" % (c, case)] = n
    rows.append(row)
lie_rows = []
for scheme, kind in lie:
    adaptive = kind == "tol"
    label = "%s (%s %s)" % (scheme, kind, tol if adaptive else dt)
    row = {"method": label}
    for case in cases:
        v, n = run(scheme, case, adaptive)
        row["case %d" % case] = cell(v)
        row["case %d steps" % case] = n
    lie_rows.append(row)

lines = []
head = ["Stepper"] + ["%s, case %d (ms)" % (name, k) for _, name in coords for k in cases]
lines.append("| " + " | ".join(head) + " |")
lines.append("|" + "---|" * len(head))
for r in rows:
    lines.append("| " + " | ".join([r["method"]] + [r["%s case %d" % (c, k)] for c, _ in coords for k in cases]) + " |")
lines.append("")
lines.append("| " + " | ".join(["Lie-group scheme (SO(3) x R^3)"] + ["case %d (ms)" % k for k in cases]) + " |")
lines.append("|" + "---|" * (1 + len(cases)))
for r in lie_rows:
    lines.append("| " + " | ".join([r["method"]] + [r["case %d" % k] for k in cases]) + " |")
lines.append("")
lines.append("CPU milliseconds (ms: /diagnostics cpu_seconds x 1000), the smallest of %d runs of lgi simulate; "
             "case N = scene heavy_top_trindade_N.toml (Trindade & Sampaio's Ex. N); t_end as in the scenes." % repeat)
if failures:
    lines.append("")
    lines.append("Failed runs:")
    lines += ["- " + f for f in failures]
text = "\n".join(lines) + "\n"
with open(os.path.join(out, "table1.md"), "w") as f:
    f.write(text)
with open(os.path.join(out, "table1.csv"), "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["method", "coordinates", "case", "cpu_milliseconds_min", "steps"])
    for st, r in zip(steppers, rows):
        for c, _ in coords:
            for k in cases:
                w.writerow([r["method"], c, k, r["%s case %d" % (c, k)], r["%s case %d steps" % (c, k)]])
    for r in lie_rows:
        for k in cases:
            w.writerow([r["method"], "lie-group", k, r["case %d" % k], r["case %d steps" % k]])
sys.stdout.write(text)
PY
