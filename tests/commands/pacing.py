"""Pacing of the tests that cut a run short (signals, kills, faults): how much
slower the lgi under test runs than a release build (a sanitizer build: about
5x), measured once per session on a fixed simulate, by which they scale their
waits so that the run has reached the same point whatever the build; and the
long sweep they cut."""
import functools
import os
import resource
import subprocess
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
RELEASE_SECONDS = 0.10  # the same simulate in a release build on one core


@functools.lru_cache(maxsize=None)
def slowdown(lgi):
    scene = os.path.join(ROOT, "experiments", "scenes", "free_body_hlw.toml")
    with tempfile.TemporaryDirectory() as d:
        start = time.monotonic()
        subprocess.run([lgi, "simulate", "--scene", scene, "--scheme", "rkmk4", "--dt", "1e-4", "--t-end", "20",
                        "--save-every", "100000", "--out", os.path.join(d, "pace.h5"), "--quiet"], check=True)
        wall = time.monotonic() - start
    return max(1.0, wall / RELEASE_SECONDS)


@functools.lru_cache(maxsize=None)
def cpu_slowdown(lgi):
    """As slowdown, in CPU time (utime + stime): the build's own factor, whatever the machine's load."""
    scene = os.path.join(ROOT, "experiments", "scenes", "free_body_hlw.toml")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryDirectory() as d:
        subprocess.run([lgi, "simulate", "--scene", scene, "--scheme", "rkmk4", "--dt", "1e-4", "--t-end", "20",
                        "--save-every", "100000", "--out", os.path.join(d, "pace.h5"), "--quiet"], check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    return max(1.0, cpu / RELEASE_SECONDS)


def cpu_seconds(pid):
    """utime + stime of a running process (all its threads) in s, from /proc/PID/stat; None once it has ended."""
    try:
        with open(f"/proc/{pid}/stat") as f:
            fields = f.read().rsplit(")", 1)[1].split()
    except OSError:
        return None
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def signal_after_cpu(lgi, args, sig, after):
    """Starts lgi with `args` (one OpenMP thread), sends `sig` once it has used `after` s of CPU time (scaled
    to the build's speed) and returns (exit status, stderr, CPU seconds it used from the signal to its exit).
    CPU time, not wall time: on a loaded machine the run gets the same work done before and after the
    signal, however slowly (scripts/audit_stop_polling.py measures the same way)."""
    with tempfile.TemporaryFile("w+") as err:
        p = subprocess.Popen([lgi, *args], stdout=subprocess.DEVNULL, stderr=err, text=True,
                             env=dict(os.environ, OMP_NUM_THREADS="1"))
        while True:
            used = cpu_seconds(p.pid)
            assert used is not None and p.poll() is None, "the command ended before it could be interrupted"
            if used >= after * cpu_slowdown(lgi):
                break
            time.sleep(0.01)
        p.send_signal(sig)
        _, status, usage = os.wait4(p.pid, 0)
        p.returncode = os.waitstatus_to_exitcode(status)
        err.seek(0)
        return p.returncode, err.read(), usage.ru_utime + usage.ru_stime - used


def wait_part_way(p, partial):
    """Waits until process p has created `partial` and then run 0.8 s more (scaled to the build's
    speed), so that it is part-way through the long sweep; fails if it has ended by then."""
    while not os.path.exists(partial):
        assert p.poll() is None, "the sweep ended before its .partial appeared"
        time.sleep(0.01)
    time.sleep(0.8 * slowdown(p.args[0]))  # the same moment of the run in a slower (sanitizer) build
    assert p.poll() is None, "the sweep ended before it could be killed"


# A sweep long enough to be cut in the middle (about 4.5 s on one core, in
# the ensemble's 16 AVX-512 lanes; longer on narrower vectors); SCENES stands
# for the shipped scenes' folder.
LONG_SWEEP = """
scene = "SCENES/kovalevskaya.toml"
scheme = "rkmk4"
dt = 0.01
t_end = 200.0
seed = 3
samples = 2000
chunk = 20
[level_set]
h = 2.0
l = 1.0
"""


def signal_and_time(lgi, args, sig, after):
    """Starts lgi with `args`, sends `sig` `after` s (scaled to the build's speed) into the run and
    returns (exit status, stderr, seconds from the signal to the exit)."""
    p = subprocess.Popen([lgi, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    time.sleep(after * slowdown(lgi))
    assert p.poll() is None, "the command ended before it could be interrupted"
    p.send_signal(sig)
    sent = time.monotonic()
    _, err = p.communicate(timeout=60)
    return p.returncode, err, time.monotonic() - sent
