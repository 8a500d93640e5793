"""The hostile-input suite (issue 50, item 7): one row per bad input, each with the exit status
the README promises and a word the one-line message must contain. Every row runs under a
timeout (a hang fails it), a signal fails it, and a refusal (exit 2) must leave no output and
no .partial behind. The rows run concurrently (they are independent processes); each is a
refusal at parse time or a run of a few steps, so the whole table takes seconds.

Placeholders in the rows: {FREE} {HEAVY} {KOV} {CARDAN} scenes, {SPEC} a sweep spec, {OUT} a
fresh output path of the row, {FIFO} a FIFO, {DIR} a directory, {EMPTY} an empty file,
{BINARY} bytes that are not text, {BIG} a 17 MiB file, {MISSING} no file, {TEXT} a text file
that is neither TOML nor HDF5, {PLAIN} a regular file that is not HDF5, {LINK} a symbolic link
to {FIFO}, {DANGLING} a link to nothing, {TINY_DT_SPEC} a sweep spec whose dt cannot advance t,
{FIFO_SCENES} a folder with a scene and a FIFO named like one."""
import concurrent.futures
import os
import stat
import subprocess
import time

import pytest
from pacing import slowdown

LGI = os.environ.get("LGI_EXECUTABLE", "build/release/lgi")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
PLACES = {
    "FREE": os.path.join(SCENES, "free_body_hlw.toml"),
    "HEAVY": os.path.join(SCENES, "heavy_top_hlw.toml"),
    "KOV": os.path.join(SCENES, "kovalevskaya.toml"),
    "CARDAN": os.path.join(SCENES, "cardan_euler_tilted.toml"),
    "SPEC": os.path.join(ROOT, "experiments", "sweeps", "short_trajectories.toml"),
}
TIMEOUT = 10.0  # seconds per row (issue 50's bar), scaled by the build's speed

SIM = ["simulate", "--scene", "{FREE}", "--scheme", "rkmk4", "--dt", "0.1", "--t-end", "0.2"]
LT = ["long-time", "--scene", "{FREE}", "--scheme", "rkmk4", "--dt", "0.1", "--t-end", "0.2"]
WP = ["work-precision", "--scene", "{FREE}", "--schemes", "rkmk4", "--dt", "0.1", "--t-end", "0.2", "--repeat", "1"]
POIN = ["poincare", "--scene", "{KOV}", "--l", "1", "--h", "2", "--t-end", "0.5"]
CMAP = ["chaos-map", "--scene", "{KOV}", "--l-range", "1:1:1", "--h-range", "2:2:1", "--t-end", "0.5"]
EQ = ["equilibria", "--scene", "{HEAVY}"]
BIF = ["bifurcation", "--scene", "{HEAVY}"]
REG = ["region", "--scene", "{KOV}"]
ACT = ["actions", "--scene", "{KOV}"]
IND = ["indicators", "--scene", "{FREE}", "--t-end", "0.2", "--dt", "0.1"]
FREQ = ["frequencies", "--scene", "{FREE}", "--t-end", "2", "--dt", "0.1"]
PER = ["periodic", "--scene", "{HEAVY}", "--from-equilibria", "--l", "1", "--steps", "0"]
QUA = ["quantum", "--scene", "{HEAVY}", "--hbar", "0.1", "--jmax", "4"]
SWEEP = ["sweep", "--spec", "{SPEC}"]
OUT = ["--out", "{OUT}"]

# (id, argv without the program, expected exit status, a word the message contains)
CASES = [
    # ---- the command line itself
    ("no-subcommand", [], 2, "subcommand"),
    ("unknown-subcommand", ["frobnicate"], 2, "frobnicate"),
    ("unknown-subcommand-args", ["frobnicate", "--scene", "{FREE}"], 2, "frobnicate"),
    ("unknown-leading-option", ["--frob", "simulate", *SIM[1:], *OUT], 2, "--frob"),
    ("empty-subcommand", [""], 2, "subcommand"),
    ("unknown-option", [*SIM, "--frob", *OUT], 2, "--frob"),
    ("extra-positional", [*SIM, "stray", *OUT], 2, "stray"),
]


def without(base, flag):
    """base without `flag` and its value: the row gives its own."""
    if flag not in base:
        return list(base)
    i = base.index(flag)
    return base[:i] + base[i + 2:]


# Every subcommand that needs --scene refuses its absence, and a scene file that is not there, by name.
for name, base in (("simulate", SIM), ("work-precision", WP), ("long-time", LT), ("equilibria", EQ),
                   ("bifurcation", BIF), ("poincare", [*POIN, "--ics", "2"]), ("region", [*REG, "--l", "1", "--h", "2"]),
                   ("chaos-map", [*CMAP, "--ics", "2"]), ("actions", ACT), ("indicators", IND),
                   ("frequencies", FREQ)):
    CASES.append((f"{name}-no-scene", [name], 2, "--scene"))
    CASES.append((f"{name}-missing-scene-file", [*without(base, "--scene"), "--scene", "{MISSING}", *OUT], 2,
                  "no_such_file"))
CASES += [
    ("sweep-no-spec", ["sweep", *OUT], 2, "--spec"),
    ("sweep-no-out", ["sweep", "--spec", "{SPEC}"], 2, "--out"),
    ("singularity-no-out", ["singularity"], 2, "--out"),
    ("stress-no-out", ["stress"], 2, "--out"),
    ("simulate-no-scheme", ["simulate", "--scene", "{FREE}", *OUT], 2, "--scheme"),
    ("simulate-no-out", SIM, 2, "--out"),
    ("long-time-no-out", LT, 2, "--out"),
    ("work-precision-no-schemes", ["work-precision", "--scene", "{FREE}", *OUT], 2, "--schemes"),
    ("poincare-no-l", ["poincare", "--scene", "{KOV}", "--h", "2", "--t-end", "1", *OUT], 2, "--l"),
    ("poincare-no-t-end", ["poincare", "--scene", "{KOV}", "--l", "1", "--h", "2", *OUT], 2, "--t-end"),
    ("chaos-map-no-ics", [*CMAP, *OUT], 2, "--ics"),
    # --out is required everywhere (issue 50, item 8): no default file in the current folder
    ("poincare-no-out", [*POIN, "--ics", "2"], 2, "--out"),
    ("region-no-out", [*REG, "--l", "1", "--h", "2"], 2, "--out"),
    ("chaos-map-no-out", [*CMAP, "--ics", "2"], 2, "--out"),
    # a folder without the study's scenes: bad input, refused before <out>.partial exists (issue 50, item 9)
    ("singularity-scenes-dir-without-scenes", ["singularity", "--scenes-dir", "{DIR}", "--quick", *OUT], 2,
     "heavy_top_trindade_singular"),
]

# ---- numbers that are not numbers, or out of range
BAD_NUMBERS = [
    ("simulate", SIM, "--dt", ["abc", "nan", "inf", "-1", "0", "1e-300", "5e-324", "1e999", ""]),
    ("simulate", SIM, "--t-end", ["abc", "nan", "-1", "inf", ""]),
    ("simulate", SIM, "--save-every", ["0", "-1", "1.5", "abc", "99999999999999999999"]),
    ("long-time", LT, "--samples", ["0", "-3", "abc", "1000000000"]),
    ("long-time", LT, "--dt", ["0", "-0.1", "1e-300", "nan"]),
    ("long-time", LT, "--flush-seconds", ["0", "-1", "nan"]),
    ("work-precision", WP, "--repeat", ["0", "-1", "abc"]),
    ("poincare", [*POIN, "--ics", "2"], "--l", ["nan", "abc", "inf"]),
    ("poincare", [*POIN, "--ics", "2"], "--t-end", ["0", "-1", "nan"]),
    ("poincare", [*POIN, "--ics", "2"], "--max-events", ["0", "-1", "1000000000"]),
    ("poincare", [*POIN, "--ics", "2"], "--seed", ["-1", "abc", "18446744073709551615"]),
    ("poincare", [*POIN, "--ics", "2"], "--threads", ["0", "-1", "100000", "abc", "1.5"]),
    ("poincare", POIN, "--ics", ["0", "-5", "1000000000", "abc"]),
    ("chaos-map", [*CMAP, "--ics", "2"], "--l-range", ["1:0:2", "a:b:c", "1:2", "1:2:0", "0:1:1000000", ""]),
    ("chaos-map", [*CMAP, "--ics", "2"], "--threads", ["0", "100000", "-2"]),
    ("chaos-map", CMAP, "--ics", ["0", "10000000000"]),
    ("chaos-map", [*CMAP, "--ics", "2"], "--dt", ["0", "-1", "1e-300"]),
    ("equilibria", EQ, "--samples", ["2", "-1", "1000000000", "abc"]),
    ("equilibria", EQ, "--l", ["nan", "abc"]),
    ("bifurcation", BIF, "--samples", ["2", "1000000000"]),
    ("region", [*REG, "--l", "1", "--h", "2"], "--grid", ["7", "2001", "abc"]),
    ("region", [*REG, "--l", "1", "--h", "2"], "--samples", ["2", "1000000000"]),
    ("actions", [*ACT, "--h", "2", "--l", "1"], "--tori", ["0", "100000000"]),
    ("actions", ACT, "--grid", ["1", "2001"]),
    ("actions", ACT, "--crossings", ["15", "-1"]),
    ("actions", ACT, "--scheme", ["nosuch"]),
    ("sweep", SWEEP, "--threads", ["0", "-1", "100000", "abc"]),
    ("sweep", SWEEP, "--simd", ["bogus"]),
    ("indicators", IND, "--threads", ["0", "100000"]),
    ("indicators", IND, "--rtol", ["abc"]),
    ("frequencies", FREQ, "--t-end", ["0", "-1", "nan", "inf", "abc", "1", "1e12"]),
    ("frequencies", FREQ, "--terms", ["0", "101", "abc"]),
    ("frequencies", FREQ, "--window-order", ["-1", "9", "1.5"]),
    ("frequencies", FREQ, "--dt", ["0", "nan", "-0.1"]),
    ("frequencies", FREQ, "--output-dt", ["0", "0.15", "inf"]),
    ("frequencies", FREQ, "--observable", ["energy", "gamma_4", "", "gamma_1+i"]),
    ("frequencies", FREQ, "--threads", ["0", "100000"]),
    # a step that cannot advance time is refused up front in every command (item 1), not a failed row
    ("work-precision", WP, "--dt", ["1e-300", "5e-324"]),
    ("poincare", [*POIN, "--ics", "2"], "--dt", ["1e-300", "0"]),
    ("indicators", IND, "--dt", ["1e-300"]),
    ("singularity", ["singularity", "--quick"], "--dt", ["1e-300"]),
    ("actions", ACT, "--dt", ["1e-300", "1e-9", "0"]),
    ("periodic", PER, "--dt", ["1e-300", "1e-9", "0", "nan", "2"]),
    ("periodic", PER, "--steps", ["-1", "1000000000"]),
    ("periodic", PER, "--returns", ["0", "1000000000"]),
    ("periodic", PER, "--manifold-periods", ["0", "1e12"]),
    ("periodic", PER, "--l", ["nan", "abc"]),
    ("periodic", PER, "--h-step", ["0", "nan"]),
    ("periodic", PER, "--amplitude", ["0", "1"]),
    ("quantum", QUA, "--hbar", ["0", "-1", "nan", "abc"]),
    ("quantum", QUA, "--jmax", ["100000", "-1"]),
    ("quantum", QUA, "--jmax-step", ["0", "1000"]),
    ("quantum", QUA, "--tol", ["nan", "0", "-1"]),
]
for name, base, flag, values in BAD_NUMBERS:
    for v in values:
        CASES.append((f"{name}{flag}={v or 'empty'}", [*without(base, flag), flag, v, *OUT], 2, flag))

CASES += [
    # ---- absurd work (issue 50, items 2 and 6): refused up front, within the timeout
    ("region-cells-1e10", [*REG, "--cells", "--l-range", "0:1:100000", "--h-range", "0:1:100000", *OUT], 2, "--cells"),
    ("region-cells-1e9", [*REG, "--cells", "--l-range", "0:1:100000", "--h-range", "0:1:10000", *OUT], 2, "--cells"),
    ("chaos-map-cells-1e10", ["chaos-map", "--scene", "{KOV}", "--l-range", "0:1:100000", "--h-range", "0:1:100000",
                              "--ics", "1", "--t-end", "1", *OUT], 2, "--l-range"),
    ("chaos-map-orbits", ["chaos-map", "--scene", "{KOV}", "--l-range", "0:1:1000", "--h-range", "1:2:1000", "--ics",
                          "1000", "--t-end", "1", *OUT], 2, "orbits"),
    ("actions-tori-l-list", [*ACT, "--h", "2", "--l", "0.1,0.2,0.3", "--tori", "50000", *OUT], 2, "--tori"),
    ("poincare-ics-1e9", [*POIN, "--ics", "1000000000", *OUT], 2, "--ics"),
    ("long-time-samples-1e9", [*LT, "--samples", "1000000000", *OUT], 2, "--samples"),
    ("sweep-spec-dt-no-progress", ["sweep", "--spec", "{TINY_DT_SPEC}", *OUT], 2, "dt: the step 1e-300"),
    ("poincare-cardan-dt-no-progress", ["poincare", "--scene", "{CARDAN}", "--l", "0", "--h", "1", "--t-end", "1",
                                        "--ics", "2", "--dt", "1e-300", *OUT], 2, "--dt"),
    ("indicators-cardan-dt-no-progress", ["indicators", "--scene", "{CARDAN}", "--t-end", "1", "--dt", "1e-300", *OUT],
     2, "--dt"),
    ("quantum-m-above-jmax", [*QUA, "--m", "1000000000", *OUT], 2, "--jmax"),
    ("quantum-bad-energy-window", [*QUA, "--statistics", "--energy-window", "a:b", *OUT], 2, "--energy-window"),
    ("simulate-dt-no-progress", ["simulate", "--scene", "{FREE}", "--scheme", "lgvi", "--dt", "1e-17", "--t-end",
                                 "1e3", *OUT], 2, "--dt"),
    # ---- empty values and list elements (item 10)
    ("work-precision-empty-scheme", ["work-precision", "--scene", "{FREE}", "--schemes", "rkmk4,,cf4", "--dt", "0.1",
                                     *OUT], 2, "--schemes"),
    ("work-precision-trailing-comma", ["work-precision", "--scene", "{FREE}", "--schemes", "rkmk4,", "--dt", "0.1",
                                       *OUT], 2, "--schemes"),
    ("work-precision-empty-dt", ["work-precision", "--scene", "{FREE}", "--schemes", "rkmk4", "--dt", "0.1,,0.2",
                                 *OUT], 2, "--dt"),
    ("actions-empty-l", [*ACT, "--h", "2", "--l", "1,,2", *OUT], 2, "--l"),
    ("actions-leading-comma", [*ACT, "--h", "2", "--l", ",1", *OUT], 2, "--l"),
    ("bifurcation-empty-appelrot", [*BIF, "--appelrot", "1,,2", *OUT], 2, "--appelrot"),
    ("stress-empty-scheme", ["stress", "--schemes", "rkmk4,,cf4", "--quick", *OUT], 2, "--schemes"),
    ("simulate-empty-out", [*SIM, "--out", ""], 2, "--out"),
    ("simulate-empty-out-eq", [*SIM, "--out="], 2, "--out"),
    ("long-time-empty-out", [*LT, "--out", ""], 2, "--out"),
    ("sweep-empty-out", [*SWEEP, "--out", ""], 2, "--out"),
    ("poincare-empty-out", [*POIN, "--ics", "2", "--out", ""], 2, "--out"),
    ("simulate-empty-scene", ["simulate", "--scene", "", "--scheme", "rkmk4", *OUT], 2, "--scene"),
    ("simulate-empty-scheme", ["simulate", "--scene", "{FREE}", "--scheme", "", *OUT], 2, "--scheme"),
    ("simulate-empty-tol", [*SIM, "--tol", "", *OUT], 2, "--tol"),
    ("simulate-tol-1e50", ["simulate", "--scene", "{FREE}", "--scheme", "rkmk-dp54", "--t-end", "1", "--tol", "1e50",
                           *OUT], 2, "--tol: must be below 1"),
    ("simulate-tol-1e300", ["simulate", "--scene", "{FREE}", "--scheme", "rkmk-dp54", "--t-end", "1", "--tol", "1e300",
                            *OUT], 2, "--tol: must be below 1"),
    ("simulate-empty-dt", [*without(SIM, "--dt"), "--dt", "", *OUT], 2, "--dt: an empty value"),
    ("simulate-empty-t-end", [*without(SIM, "--t-end"), "--t-end", "", *OUT], 2, "--t-end: an empty value"),
    ("simulate-empty-dt-eq", [*without(SIM, "--dt"), "--dt=", *OUT], 2, "--dt"),
    # ---- schemes that do not exist or do not apply
    ("simulate-unknown-scheme", ["simulate", "--scene", "{FREE}", "--scheme", "nosuch", *OUT], 2, "nosuch"),
    ("simulate-cardan-scheme-on-so3", ["simulate", "--scene", "{FREE}", "--scheme", "cardan-dp54", "--dt", "0.1",
                                       "--t-end", "0.2", *OUT], 2, "cardan-dp54"),
    ("simulate-so3-scheme-on-cardan", ["simulate", "--scene", "{CARDAN}", "--scheme", "rkmk4", "--dt", "0.1",
                                       "--t-end", "0.2", *OUT], 2, "rkmk4"),
    ("long-time-unknown-scheme", ["long-time", "--scene", "{FREE}", "--scheme", "nosuch", *OUT], 2, "nosuch"),
    ("work-precision-unknown-scheme", ["work-precision", "--scene", "{FREE}", "--schemes", "nosuch", *OUT], 2,
     "nosuch"),
    ("stress-unknown-scheme", ["stress", "--schemes", "nosuch", "--quick", *OUT], 2, "nosuch"),
    ("poincare-adaptive-scheme", [*POIN, "--ics", "2", "--scheme", "rkmk45", *OUT], 2, "--scheme"),
    ("poincare-bad-section", [*POIN, "--ics", "2", "--section", "bogus", *OUT], 2, "--section"),
    ("poincare-bad-measure", [*POIN, "--ics", "2", "--measure", "bogus", *OUT], 2, "--measure"),
    ("poincare-ics-and-seeds", [*POIN, "--ics", "2", "--seeds", "{TEXT}", *OUT], 2, "--ics"),
    ("poincare-empty-level", ["poincare", "--scene", "{KOV}", "--l", "1", "--h", "-50", "--t-end", "1", "--ics", "2",
                              *OUT], 2, "--h"),
    ("region-cells-and-l", [*REG, "--cells", "--l", "1", "--l-range", "0:1:2", "--h-range", "0:1:2", *OUT], 2, "--l"),
    ("region-no-h", [*REG, "--l", "1", *OUT], 2, "--h"),
    ("region-range-without-cells", [*REG, "--l", "1", "--h", "2", "--l-range", "0:1:2", *OUT], 2, "--l-range"),
    ("actions-l-without-h", [*ACT, "--l", "1", *OUT], 2, "--l"),
    ("chaos-map-bad-measure", [*CMAP, "--ics", "2", "--measure", "bogus", *OUT], 2, "--measure"),
    ("chaos-map-cardan", ["chaos-map", "--scene", "{CARDAN}", "--l-range", "1:1:1", "--h-range", "2:2:1", "--ics", "2",
                          "--t-end", "0.5", *OUT], 2, "--vary KEY=a:b:n"),
    ("indicators-bad-scheme", [*IND, "--scheme", "cf4", *OUT], 2, "--scheme"),
    ("sweep-resume-nothing", [*SWEEP, "--resume", *OUT], 2, "--resume"),
    ("long-time-resume-nothing", [*LT, "--resume", *OUT], 2, "--resume"),
    # ---- inputs that are not what they claim (item 3)
    ("scene-dev-zero", ["simulate", "--scene", "/dev/zero", "--scheme", "rkmk4", *OUT], 2, "16 MiB"),
    ("scene-dev-urandom", ["simulate", "--scene", "/dev/urandom", "--scheme", "rkmk4", *OUT], 2, "16 MiB"),
    ("scene-dev-null", ["simulate", "--scene", "/dev/null", "--scheme", "rkmk4", *OUT], 2, "/dev/null"),
    ("scene-directory", ["simulate", "--scene", "{DIR}", "--scheme", "rkmk4", *OUT], 2, "directory"),
    ("scene-big", ["simulate", "--scene", "{BIG}", "--scheme", "rkmk4", *OUT], 2, "16 MiB"),
    ("scene-binary", ["simulate", "--scene", "{BINARY}", "--scheme", "rkmk4", *OUT], 2, "binary"),
    ("scene-empty", ["simulate", "--scene", "{EMPTY}", "--scheme", "rkmk4", *OUT], 2, "empty"),
    ("scene-not-toml", ["simulate", "--scene", "{TEXT}", "--scheme", "rkmk4", *OUT], 2, "text.txt"),
    ("scene-missing", ["simulate", "--scene", "{MISSING}", "--scheme", "rkmk4", *OUT], 2, "No such file"),
    ("equilibria-scene-dev-zero", ["equilibria", "--scene", "/dev/zero", *OUT], 2, "16 MiB"),
    ("poincare-scene-directory", ["poincare", "--scene", "{DIR}", "--l", "1", "--h", "2", "--t-end", "1", "--ics",
                                  "2", *OUT], 2, "directory"),
    ("spec-dev-zero", ["sweep", "--spec", "/dev/zero", *OUT], 2, "16 MiB"),
    ("spec-dev-urandom", ["sweep", "--spec", "/dev/urandom", *OUT], 2, "16 MiB"),
    ("spec-directory", ["sweep", "--spec", "{DIR}", *OUT], 2, "directory"),
    ("spec-big", ["sweep", "--spec", "{BIG}", *OUT], 2, "16 MiB"),
    ("spec-empty", ["sweep", "--spec", "{EMPTY}", *OUT], 2, "empty.toml"),
    ("spec-missing", ["sweep", "--spec", "{MISSING}", *OUT], 2, "No such file"),
    ("spec-is-a-scene", ["sweep", "--spec", "{FREE}", *OUT], 2, "free_body_hlw.toml"),
    ("seeds-dev-zero", [*POIN, "--seeds", "/dev/zero", *OUT], 2, "--seeds"),
    ("seeds-directory", [*POIN, "--seeds", "{DIR}", *OUT], 2, "directory"),
    ("seeds-missing", [*POIN, "--seeds", "{MISSING}", *OUT], 2, "--seeds"),
    ("seeds-empty", [*POIN, "--seeds", "{EMPTY}", *OUT], 2, "--seeds"),
    ("seeds-not-csv", [*POIN, "--seeds", "{TEXT}", *OUT], 2, "--seeds"),
    ("state-file-dev-zero", [*IND, "--state-file", "/dev/zero", *OUT], 2, "16 MiB"),
    ("state-file-directory", [*IND, "--state-file", "{DIR}", *OUT], 2, "directory"),
    ("state-file-dev-null", [*IND, "--state-file", "/dev/null", *OUT], 2, "/dev/null"),
    ("state-file-missing", [*IND, "--state-file", "{MISSING}", *OUT], 2, "No such file"),
    ("state-file-not-csv", [*IND, "--state-file", "{TEXT}", *OUT], 2, "text.txt"),
    ("state-file-binary", [*IND, "--state-file", "{BINARY}", *OUT], 2, "binary.bin"),
    ("periodic-no-scene", ["periodic", "--from-equilibria", "--l", "1", *OUT], 2, "--scene"),
    ("periodic-no-out", PER, 2, "--out"),
    ("periodic-no-start", ["periodic", "--scene", "{HEAVY}", "--l", "1", *OUT], 2, "--from-equilibria"),
    ("periodic-scene-directory", [*without(PER, "--scene"), "--scene", "{DIR}", *OUT], 2, "directory"),
    ("periodic-seed-file-dev-zero", ["periodic", "--scene", "{HEAVY}", "--l", "1", "--seed-file", "/dev/zero", *OUT],
     2, "16 MiB"),
    ("periodic-seed-file-directory", ["periodic", "--scene", "{HEAVY}", "--l", "1", "--seed-file", "{DIR}", *OUT], 2,
     "directory"),
    ("periodic-seed-file-missing", ["periodic", "--scene", "{HEAVY}", "--l", "1", "--seed-file", "{MISSING}", *OUT],
     2, "--seed-file"),
    ("periodic-seed-file-empty", ["periodic", "--scene", "{HEAVY}", "--l", "1", "--seed-file", "{EMPTY}", *OUT], 2,
     "no seed"),
    ("periodic-seed-file-not-seeds", ["periodic", "--scene", "{HEAVY}", "--l", "1", "--seed-file", "{TEXT}", *OUT], 2,
     "line 1"),
    ("periodic-poincare-fifo", ["periodic", "--scene", "{HEAVY}", "--seeds-from-poincare", "{FIFO}",
                                "--poincare-rows", "0", *OUT], 2, "FIFO"),
    ("periodic-poincare-not-hdf5", ["periodic", "--scene", "{HEAVY}", "--seeds-from-poincare", "{PLAIN}",
                                    "--poincare-rows", "0", *OUT], 2, "HDF5 signature"),
    ("periodic-poincare-directory", ["periodic", "--scene", "{HEAVY}", "--seeds-from-poincare", "{DIR}",
                                     "--poincare-rows", "0", *OUT], 2, "directory"),
    ("periodic-poincare-without-rows", ["periodic", "--scene", "{HEAVY}", "--seeds-from-poincare", "{PLAIN}", *OUT],
     2, "--poincare-rows"),
    ("quantum-no-scene", ["quantum", "--hbar", "0.1", *OUT], 2, "--scene"),
    ("quantum-no-hbar", ["quantum", "--scene", "{HEAVY}", *OUT], 2, "--hbar"),
    ("quantum-no-out", QUA, 2, "--out"),
    ("quantum-scene-directory", [*without(QUA, "--scene"), "--scene", "{DIR}", *OUT], 2, "directory"),
    ("scenes-not-a-folder", ["scenes", "/dev/zero"], 2, "not a folder"),
    ("scenes-fifo-named-like-a-scene", ["scenes", "{FIFO_SCENES}"], 2, "FIFO"),
    ("schemes-scene-directory", ["schemes", "--scene", "{DIR}"], 2, "directory"),
    ("schemes-unknown-family", ["schemes", "--family", "nosuch"], 2, "nosuch"),
    # ---- outputs that must never be replaced (item 4); device nodes: the test below, on a private one
    ("simulate-force-fifo", [*SIM, "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("simulate-fifo", [*SIM, "--out", "{FIFO}"], 2, "FIFO"),
    ("simulate-force-dir", [*SIM, "--out", "{DIR}", "--force"], 2, "directory"),
    ("simulate-force-link-to-fifo", [*SIM, "--out", "{LINK}", "--force"], 2, "FIFO"),
    ("simulate-force-dangling", [*SIM, "--out", "{DANGLING}", "--force"], 2, "link"),
    ("long-time-force-fifo", [*LT, "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("work-precision-force-fifo", [*WP, "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("sweep-force-fifo", [*SWEEP, "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("poincare-force-fifo", [*POIN, "--ics", "2", "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("chaos-map-force-fifo", [*CMAP, "--ics", "1", "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("equilibria-force-fifo", [*EQ, "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("bifurcation-force-dir", [*BIF, "--out", "{DIR}", "--force"], 2, "directory"),
    ("region-force-fifo", [*REG, "--l", "1", "--h", "2", "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("actions-force-fifo", [*ACT, "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("indicators-force-fifo", [*IND, "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("singularity-force-fifo", ["singularity", "--quick", "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("stress-force-fifo", ["stress", "--quick", "--schemes", "rkmk4", "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("periodic-force-fifo", [*PER, "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("periodic-force-dir", [*PER, "--out", "{DIR}", "--force"], 2, "directory"),
    ("periodic-empty-out", [*PER, "--out", ""], 2, "--out"),
    ("quantum-force-fifo", [*QUA, "--out", "{FIFO}", "--force"], 2, "FIFO"),
    ("quantum-empty-out", [*QUA, "--out", ""], 2, "--out"),
    ("simulate-exists", [*SIM, "--out", "{PLAIN}"], 2, "--force"),
    ("simulate-out-in-missing-dir", [*SIM, "--out", "{MISSING}/x.h5"], 2, "x.h5"),
    ("simulate-out-under-a-file", [*SIM, "--out", "{PLAIN}/x.h5"], 2, "x.h5"),
    # ---- resume files that are not resume files
    ("long-time-resume-fifo", [*LT, "--resume", "--out", "{FIFO_STEM}"], 2, "FIFO"),
    ("long-time-resume-not-hdf5", [*LT, "--resume", "--out", "{PLAIN_STEM}"], 2, "HDF5"),
    ("sweep-resume-not-hdf5", [*SWEEP, "--resume", "--out", "{PLAIN_STEM}"], 2, "without --resume"),
    ("sweep-resume-fifo", [*SWEEP, "--resume", "--out", "{FIFO_STEM}"], 2, "FIFO"),
]


def make_places(d):
    p = dict(PLACES)
    p["DIR"] = os.path.join(d, "a_directory")
    os.mkdir(p["DIR"])
    p["FIFO"] = os.path.join(d, "fifo")
    os.mkfifo(p["FIFO"])
    p["LINK"] = os.path.join(d, "link_to_fifo")
    os.symlink(p["FIFO"], p["LINK"])
    p["DANGLING"] = os.path.join(d, "dangling")
    os.symlink(os.path.join(d, "nothing_here"), p["DANGLING"])
    p["EMPTY"] = os.path.join(d, "empty.toml")
    open(p["EMPTY"], "w").close()
    p["BINARY"] = os.path.join(d, "binary.bin")
    with open(p["BINARY"], "wb") as f:
        f.write(bytes(range(256)) * 16)
    p["BIG"] = os.path.join(d, "big.toml")
    with open(p["BIG"], "wb") as f:
        f.truncate(17 << 20)  # sparse: 17 MiB of zeros without writing them
    p["TEXT"] = os.path.join(d, "text.txt")
    with open(p["TEXT"], "w") as f:
        f.write("this is not a scene = [\n")
    p["PLAIN"] = os.path.join(d, "plain.h5")
    with open(p["PLAIN"], "w") as f:
        f.write("a previous output\n")
    p["MISSING"] = os.path.join(d, "no_such_file")
    p["TINY_DT_SPEC"] = os.path.join(d, "tiny_dt.toml")
    with open(p["TINY_DT_SPEC"], "w") as f:
        f.write(f'scene = "{PLACES["FREE"]}"\nscheme = "rkmk4"\ndt = 1e-300\nt_end = 1.0\nsamples = 2\n'
                '[[vary]]\nkey = "initial.angular_momentum"\nuniform = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]\n')
    p["FIFO_SCENES"] = os.path.join(d, "scenes_with_a_fifo")
    os.mkdir(p["FIFO_SCENES"])
    os.mkfifo(os.path.join(p["FIFO_SCENES"], "a_fifo.toml"))
    with open(PLACES["FREE"]) as f, open(os.path.join(p["FIFO_SCENES"], "free.toml"), "w") as g:
        g.write(f.read())
    # Resume paths: <stem>.partial is the FIFO, or a plain text file.
    p["FIFO_STEM"] = os.path.join(d, "fstem.h5")
    os.mkfifo(p["FIFO_STEM"] + ".partial")
    p["PLAIN_STEM"] = os.path.join(d, "pstem.h5")
    with open(p["PLAIN_STEM"] + ".partial", "w") as f:
        f.write("not HDF5\n")
    return p


def snapshot(p):
    """What the rows must not change: the kind and contents of every prepared file."""
    out = {}
    for key, path in p.items():
        if os.path.lexists(path) and not path.startswith(os.path.join(ROOT, "experiments")):
            st = os.lstat(path)
            content = None
            if stat.S_ISREG(st.st_mode) and st.st_size < 1 << 20:
                content = open(path, "rb").read()
            out[key] = (stat.S_IFMT(st.st_mode), st.st_size, content)
    return out


def run_case(case, places, outdir, timeout):
    name, argv, status, word = case
    fill = dict(places, OUT=os.path.join(outdir, name.replace("/", "_") + ".h5"))
    args = [a.format(**fill) for a in argv]
    start = time.monotonic()
    try:
        r = subprocess.run([LGI, *args], capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL)
    except subprocess.TimeoutExpired:
        return name, None, "", time.monotonic() - start, fill["OUT"]
    return name, r.returncode, r.stderr, time.monotonic() - start, fill["OUT"]


@pytest.fixture(scope="module")
def results(tmp_path_factory):
    d = str(tmp_path_factory.mktemp("hostile"))
    places = make_places(d)
    before = snapshot(places)
    outdir = os.path.join(d, "out")
    os.mkdir(outdir)
    timeout = TIMEOUT * slowdown(LGI)
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        done = list(pool.map(lambda c: run_case(c, places, outdir, timeout), CASES))
    return {name: rest for name, *rest in done}, before, snapshot(places), outdir


def test_the_table_is_large_and_its_names_unique():
    assert len(CASES) >= 150
    assert len({c[0] for c in CASES}) == len(CASES)


@pytest.mark.parametrize("case", CASES, ids=[c[0] for c in CASES])
def test_hostile_input(results, case):
    name, argv, status, word = case
    table, _, _, _ = results
    code, err, seconds, out = table[name]
    assert code is not None, f"hung: no exit within the timeout ({seconds:.1f} s)"
    assert code >= 0, f"killed by signal {-code}: {err}"
    assert code == status, (code, err)
    assert err.endswith("\n") and err.count("\n") == 1, f"not one line: {err!r}"
    assert word in err, f"{word!r} not in {err!r}"
    assert "required but received" not in err, "the row gives a flag twice"
    if status == 2:
        assert not os.path.lexists(out) and not os.path.lexists(out + ".partial"), "a refusal left a file"


def test_no_prepared_file_was_changed(results):
    _, before, after, _ = results
    assert before == after


def test_force_onto_a_private_device_node_is_refused_and_the_node_unchanged(tmp_path):
    """Issue 50's bar: --force onto a device node (made here, never a system one) is refused with
    exit 2, and the node keeps its kind, numbers and mode."""
    if os.geteuid() != 0:
        pytest.skip("making a device node needs root")
    node = str(tmp_path / "null_clone")
    try:
        os.mknod(node, 0o600 | stat.S_IFCHR, os.makedev(1, 3))  # the numbers of /dev/null
    except PermissionError:
        pytest.skip("this container may not make device nodes")
    before = os.lstat(node)
    for args in (SIM, LT, SWEEP):
        argv = [a.format(**PLACES) for a in args]
        r = subprocess.run([LGI, *argv, "--out", node, "--force"], capture_output=True, text=True, timeout=60)
        assert r.returncode == 2, r.stderr
        assert "--out" in r.stderr and "device" in r.stderr and r.stderr.count("\n") == 1, r.stderr
        after = os.lstat(node)
        assert stat.S_ISCHR(after.st_mode) and after.st_rdev == before.st_rdev
        assert after.st_mode == before.st_mode and after.st_ino == before.st_ino
        assert not os.path.exists(node + ".partial")


def test_long_time_resume_onto_another_commands_file_is_refused_and_the_file_kept(tmp_path):
    """Issue 50's bar: `long-time --resume` whose <out>.partial is a sweep's file (here a finished
    sweep's, which has the same groups as its .partial: /sweep, no /series, no checkpoint) exits 2
    and leaves the file byte-identical; it used to start again from step 0 over it."""
    spec = tmp_path / "s.toml"
    spec.write_text(f'name = "small"\nscene = "{PLACES["FREE"]}"\nscheme = "rkmk4"\ndt = 0.01\nt_end = 0.1\n'
                    'seed = 1\nsamples = 4\n[[vary]]\nkey = "initial.angular_momentum"\n'
                    'uniform = [[-1.0, -1.0, -1.0], [1.0, 1.0, 1.0]]\n')
    sweep_file = str(tmp_path / "s.h5")
    r = subprocess.run([LGI, "sweep", "--spec", str(spec), "--out", sweep_file, "--threads", "1", "--quiet"],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    out = str(tmp_path / "x.h5")
    os.rename(sweep_file, out + ".partial")
    before = open(out + ".partial", "rb").read()
    argv = [a.format(**PLACES) for a in LT]
    r = subprocess.run([LGI, *argv, "--resume", "--out", out], capture_output=True, text=True, timeout=60)
    assert r.returncode == 2, r.stderr
    assert "--resume" in r.stderr and "not a partial lgi long-time file" in r.stderr and r.stderr.count("\n") == 1
    assert open(out + ".partial", "rb").read() == before
    assert not os.path.exists(out) and not os.path.exists(str(tmp_path / "x.csv"))
