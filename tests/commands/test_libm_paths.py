"""glibc's two code paths for sin, cos, exp, log, pow, ... (README, "Numerics
policy"; experiments/io/libm_code_path.hpp): every output file records which
one ran (GLIBC_TUNABLES included), and the adaptive pairs' runs are the same
bits on either, since their step-size controller calls none of them
(integrators/core/controller_math.hpp). GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA,-FMA4
makes this machine take the path of a CPU without FMA. With libm's exp and log
in the controller, the first run below ended 1.8e-5 apart in the attitude."""
import os
import platform
import subprocess

import h5py
import pytest
from test_sweep import LGI, SCENES, spec

NON_FMA = "glibc.cpu.hwcaps=-AVX2,-FMA,-FMA4"

pytestmark = pytest.mark.skipif(
    platform.machine() != "x86_64" or not hasattr(os, "confstr") or "glibc" not in (os.confstr("CS_GNU_LIBC_VERSION") or ""),
    reason="glibc's code paths are chosen on x86-64 only")


def environment(non_fma):
    env = dict(os.environ)
    env.pop("GLIBC_TUNABLES", None)
    if non_fma:
        env["GLIBC_TUNABLES"] = NON_FMA
    return env


def run(tmp_path, name, non_fma, *args):
    out = tmp_path / (name + ("_nonfma" if non_fma else "") + ".h5")
    r = subprocess.run([LGI, *args, "--out", str(out), "--force"], env=environment(non_fma),
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return out


def datasets(path):
    """Every dataset, as bytes, by path."""
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: out.__setitem__(name, obj[()].tobytes())
                     if isinstance(obj, h5py.Dataset) else None)
    return out


def cpu_flags():
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("flags"):
                return set(line.split(":", 1)[1].split())
    return set()


def test_every_output_file_records_the_code_path(tmp_path):
    glibc = "glibc " + os.confstr("CS_GNU_LIBC_VERSION").split()[-1]
    paths = {glibc + ", " + p for p in ("FMA code paths", "FMA4 code paths", "non-FMA code paths")}
    hlw = os.path.join(SCENES, "heavy_top_hlw.toml")
    recorded = {}
    for non_fma in (False, True):
        sim = run(tmp_path, "sim", non_fma, "simulate", "--scene", hlw, "--scheme", "rkmk4", "--dt", "0.1", "--t-end", "1")
        eq = run(tmp_path, "eq", non_fma, "equilibria", "--scene", hlw, "--l", "3", "--quiet")
        swept = run(tmp_path, "sweep", non_fma, "sweep", "--spec", spec(tmp_path, SWEEP), "--quiet")
        with h5py.File(sim, "r") as a, h5py.File(eq, "r") as b, h5py.File(swept, "r") as c:
            values = {a["parameters"].attrs["libm"], b["parameters"].attrs["libm"], c["provenance"].attrs["libm"]}
        assert len(values) == 1 and values <= paths, values
        recorded[non_fma] = values.pop()
    assert recorded[True] == glibc + ", non-FMA code paths"
    # glibc takes its FMA builds only where the CPU has FMA and AVX2 (the kernel lists what it has).
    if not {"fma", "avx2"} <= cpu_flags():
        assert recorded[False] != glibc + ", FMA code paths"


SWEEP = """
scene = "SCENES/heavy_top_hlw.toml"
scheme = "rkmk4"
dt = 0.1
t_end = 1.0
seed = 1
samples = 2
[[vary]]
key = "initial.angular_velocity"
uniform = [[-1.0, -1.0, 0.5], [1.0, 1.0, 1.5]]
"""


@pytest.mark.parametrize("scene,scheme,tol,t_end", [
    ("heavy_top_hlw", "rkmk-verner87", "1e-8", "3000"),
    ("kovalevskaya", "rkmk-dop853", "1e-10", "500"),
    ("magnetic_top", "rkmk-dp54", "1e-8", "500"),
])
def test_adaptive_pairs_take_the_same_steps_on_either_path(tmp_path, scene, scheme, tol, t_end):
    args = ("simulate", "--scene", os.path.join(SCENES, scene + ".toml"), "--scheme", scheme, "--tol", tol,
            "--t-end", t_end, "--save-every", "100")
    native, non_fma = (datasets(run(tmp_path, scheme, flag, *args)) for flag in (False, True))
    assert native.keys() == non_fma.keys()
    assert [k for k in native if native[k] != non_fma[k]] == []
