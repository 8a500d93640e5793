"""lgi long-time --resume (issue 15; RESULTS.md, "long-time --resume"): a run
killed with SIGKILL (or stopped by SIGINT) at moments drawn from a fixed-seed
generator, then resumed with the same arguments and --resume, ends with the
files of an uninterrupted run: every /series value bit for bit, the CSV twin
byte for byte, and the same /diagnostics counters. The cases cover a
fixed-step scheme without memory (rkmk4), an adaptive one that carries its
FSAL stage and controller state (rkmk-dp54), one whose start() sets up
from the initial state (split-exact) and one that carries compensated sums
and the history of its Newton predictor (dmv-pre10), and on a Cardan scene
(state on T^3 x R^3) a fixed-step scheme (cardan-rk4) and the adaptive
cardan-dp54 with its controller's memory; one run is killed twice. A scheme that
cannot be resumed, a missing partial file and changed arguments are refused
with exit 2 and one line."""
import os
import random
import signal
import subprocess
import time

import h5py
import pytest

LGI = os.environ.get("LGI_EXECUTABLE", "build/release/lgi")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
FREE = os.path.join(SCENES, "free_body_hlw.toml")
TOP = os.path.join(SCENES, "heavy_top_trindade_1.toml")
CARDAN = os.path.join(SCENES, "cardan_euler_tilted.toml")  # state on T^3 x R^3 (docs/cardan.md section 7)
FLUSH = ["--flush-seconds", "0.1"]  # checkpoints every 0.1 s (and every 4096 steps at most)

CASES = {
    "rkmk4": ["--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-4", "--t-end", "200", "--samples", "40"],
    "rkmk-dp54": ["--scene", TOP, "--scheme", "rkmk-dp54", "--tol", "1e-12", "--t-end", "300", "--samples", "40"],
    "split-exact": ["--scene", TOP, "--scheme", "split-exact", "--dt", "1e-3", "--t-end", "150"],
    "dmv-pre10": ["--scene", FREE, "--scheme", "dmv-pre10", "--dt", "1e-4", "--t-end", "1000", "--samples", "40"],
    "cardan-rk4": ["--scene", CARDAN, "--scheme", "cardan-rk4", "--dt", "1e-3", "--t-end", "400", "--samples", "40"],
    "cardan-dp54": ["--scene", CARDAN, "--scheme", "cardan-dp54", "--tol", "1e-12", "--t-end", "2000",
                    "--samples", "40"],
}
RNG = random.Random(1515)  # fixed seed: the same moments on every run
# (case, signals, fractions of the uninterrupted run's wall time at which they are sent)
RUNS = [("rkmk4", [signal.SIGKILL], [RNG.uniform(0.25, 0.7)]) for _ in range(3)]
RUNS += [("rkmk-dp54", [signal.SIGKILL], [RNG.uniform(0.25, 0.7)]),
         ("split-exact", [signal.SIGKILL], [RNG.uniform(0.25, 0.7)]),
         ("rkmk4", [signal.SIGKILL, signal.SIGKILL], [RNG.uniform(0.2, 0.4), RNG.uniform(0.2, 0.4)]),
         ("rkmk-dp54", [signal.SIGINT], [RNG.uniform(0.25, 0.7)]),
         ("dmv-pre10", [signal.SIGKILL], [RNG.uniform(0.25, 0.7)])]
# Cardan scenes, the same loop on T^3 x R^3: a fixed step, and the adaptive pair with its controller's memory.
RUNS += [("cardan-rk4", [signal.SIGKILL], [RNG.uniform(0.25, 0.7)]),
         ("cardan-dp54", [signal.SIGKILL], [RNG.uniform(0.25, 0.7)])]
COUNTERS = ["steps", "rejected_steps", "rhs_evaluations", "newton_iterations_max", "newton_failures", "samples",
            "t_final", "status"]


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def lgi(*args):
    return subprocess.run([LGI, "long-time", *args], capture_output=True, text=True, timeout=600)


@pytest.fixture(scope="module")
def references(tmp_path_factory):
    """Each case run once, uninterrupted: its files and its wall time."""
    d = tmp_path_factory.mktemp("uninterrupted")
    out = {}
    for name, args in CASES.items():
        path = str(d / f"{name}.h5")
        start = time.monotonic()
        r = lgi(*args, *FLUSH, "--out", path, "--quiet")
        assert r.returncode == 0, r.stderr
        out[name] = (path, time.monotonic() - start)
    return out


def cut(args, out, sig, seconds, resume):
    """Starts the run (resumed or not) and sends `sig` `seconds` after it started writing.
    Returns False if the run finished first."""
    p = subprocess.Popen([LGI, "long-time", *args, *FLUSH, "--out", out, "--quiet", *(["--resume"] if resume else [])],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        end = time.monotonic() + 120
        while not os.path.exists(out + ".partial") and p.poll() is None and time.monotonic() < end:
            time.sleep(0.005)
        time.sleep(seconds)
        if p.poll() is not None:
            assert p.returncode == 0
            return False
        p.send_signal(sig)
    finally:
        if p.poll() is None and sig != signal.SIGINT:
            p.kill()
        p.wait(timeout=120)
    if p.returncode == 0:  # it finished between the poll and the signal: a signal to a zombie does nothing
        return False
    if p.returncode == -signal.SIGINT and published(out):  # it came after the results were published
        return False
    assert p.returncode == (-signal.SIGKILL if sig == signal.SIGKILL else 130), p.returncode
    return True


def published(out):
    """The results are in <out> and nothing is left under .partial."""
    return os.path.exists(out) and not os.path.exists(out + ".partial")


def assert_same_files(out, ref):
    with h5py.File(out, "r") as f, h5py.File(ref, "r") as g:
        assert sorted(f["series"]) == sorted(g["series"])
        for k in g["series"]:
            assert f["series"][k][()].tobytes() == g["series"][k][()].tobytes(), k
        for k in COUNTERS:
            assert text(f["diagnostics"].attrs[k]) == text(g["diagnostics"].attrs[k]), k
    csv, ref_csv = out[:-3] + ".csv", ref[:-3] + ".csv"
    with open(csv, "rb") as a, open(ref_csv, "rb") as b:
        assert a.read() == b.read()


@pytest.mark.parametrize("k", range(len(RUNS)))
def test_resume_matches_uninterrupted(tmp_path, references, k):
    name, signals, fractions = RUNS[k]
    ref, wall = references[name]
    out = str(tmp_path / "run.h5")
    resumed_from = []
    for i, (sig, fraction) in enumerate(zip(signals, fractions)):
        if not cut(CASES[name], out, sig, fraction * wall, resume=i > 0):
            break  # a fast machine: the run finished before the signal
    if os.path.exists(out + ".partial"):
        r = lgi(*CASES[name], *FLUSH, "--out", out, "--resume")
        assert r.returncode == 0, r.stderr
        assert "resuming" in r.stderr, r.stderr
        resumed_from = r.stderr
    assert not os.path.exists(out + ".partial")
    assert_same_files(out, ref)
    if resumed_from and fractions[0] * wall > 0.5:
        assert "from step 0" not in resumed_from, "no checkpoint after 0.5 s of a run that checkpoints every 0.1 s"


def one_line(err):
    assert err.endswith("\n") and err.count("\n") == 1, repr(err)
    return err


def test_resume_refusals(tmp_path):
    out = str(tmp_path / "r.h5")
    short = ["--scene", FREE, "--dt", "1e-3", "--t-end", "1"]
    r = lgi(*short, "--scheme", "rkmk4", "--out", out, "--resume")
    assert r.returncode == 2 and "there is no" in one_line(r.stderr)
    # A baseline keeps its chart's coordinates between steps and does not save them.
    r = lgi(*short, "--scheme", "quat/rk4", "--out", out, "--resume")
    assert r.returncode == 2 and "--resume" in one_line(r.stderr)
    # A partial file of another run (another step) is refused, and left as it was.
    assert cut(["--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-4", "--t-end", "1e4"], out, signal.SIGKILL, 0.3,
               resume=False)
    before = open(out + ".partial", "rb").read()
    r = lgi("--scene", FREE, "--scheme", "rkmk4", "--dt", "2e-4", "--t-end", "1e4", "--out", out, "--resume")
    assert r.returncode == 2 and "another" in one_line(r.stderr)
    assert open(out + ".partial", "rb").read() == before


def test_signal_at_any_moment_of_a_short_run(tmp_path):
    """SIGINT at random moments of a run whose steps take a fraction of the
    time it spends creating and finishing its files: the command either
    stops with 130 and a .partial that --resume completes, or finishes with
    0 (a signal after the last step only lets the files be finished). It
    never dies half-way between <out>.partial and <out>; a signal after the
    results are published, as the process exits, may still end it, with the
    files complete."""
    args = ["--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-3", "--t-end", "5", "--samples", "10"]
    ref = str(tmp_path / "ref.h5")
    r = lgi(*args, "--out", ref, "--quiet")
    assert r.returncode == 0, r.stderr
    rng = random.Random(4242)
    window = 0.0  # the longest time seen from .partial's creation to the exit
    outcomes = {}
    for k in range(16):
        out = str(tmp_path / f"run{k}.h5")
        p = subprocess.Popen([LGI, "long-time", *args, "--out", out, "--quiet"],
                             stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        end = time.monotonic() + 60
        while not os.path.exists(out + ".partial") and p.poll() is None and time.monotonic() < end:
            time.sleep(0.0002)
        started = time.monotonic()
        if k >= 2:  # the first two runs measure the window
            time.sleep(rng.uniform(0.0, 1.5 * window))
            if p.poll() is None:
                p.send_signal(signal.SIGINT)
        p.wait(timeout=60)
        window = max(window, time.monotonic() - started)
        outcomes[p.returncode] = outcomes.get(p.returncode, 0) + 1
        if p.returncode == 130:
            assert os.path.exists(out + ".partial") and not os.path.exists(out)
            r = lgi(*args, "--out", out, "--resume", "--quiet")
            assert r.returncode == 0, r.stderr
        else:
            assert p.returncode in (0, -signal.SIGINT), outcomes
        assert published(out), (k, p.returncode)
        assert_same_files(out, ref)
    assert outcomes.get(130, 0) > 0, outcomes  # the moments reached the run itself


def test_finish_interrupted_between_its_renames(tmp_path, references):
    """A finish publishes the CSV, then the HDF5 file; a run killed between the two renames leaves
    <out>.csv beside <out>.partial. --resume takes the CSV back and ends with the uninterrupted files."""
    ref, wall = references["rkmk4"]
    out = str(tmp_path / "run.h5")
    if not cut(CASES["rkmk4"], out, signal.SIGKILL, 0.5 * wall, resume=False):
        pytest.skip("the run finished before the signal")
    csv = out[:-3] + ".csv"
    os.rename(csv + ".partial", csv)  # the state a kill between the two renames leaves
    r = lgi(*CASES["rkmk4"], *FLUSH, "--out", out, "--resume")
    assert r.returncode == 0, r.stderr
    assert "taken back" in r.stderr and not os.path.exists(out + ".partial")
    assert_same_files(out, ref)
