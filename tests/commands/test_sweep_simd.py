"""`lgi sweep --simd` (docs/ensemble.md): the ensemble path gives the rows of
one-trajectory-at-a-time stepping bit for bit, whatever the instruction set,
the thread count and the chunking (batches never cross a chunk), with
crossings, thinned trajectories, varied body keys (a batch per scene) and
blow-ups inside a batch, for rkmk4 and for dmv-pre10 (whose lanes may fall
back to the scalar scheme); a bad --simd is refused with exit 2."""
import subprocess

import h5py
import pytest
from test_sweep import LGI, columns, spec, sweep

ISAS = ("sse2", "avx2", "avx512")

# Level-set draws on the Kovalevskaya top with crossings and a thinned trajectory.
LEVEL_SET = """
scene = "SCENES/kovalevskaya.toml"
scheme = "rkmk4"
dt = 0.01
t_end = 4.0
seed = 3
samples = 37
chunk = 13
trajectory_every = 70
[level_set]
h = 2.0
l = 1.0
[[event]]
quantity = "gamma"
component = 3
direction = "rising"
[[event]]
quantity = "angular_momentum"
component = 1
"""

# Two scenes (a body key on a grid: a batch never mixes them), random attitudes.
TWO_SCENES = """
scene = "SCENES/heavy_top_trindade_1.toml"
scheme = "rkmk4"
dt = 0.005
t_end = 1.0
seed = 5
samples = 11
monitor_every = 3
[[vary]]
key = "body.mass"
values = [0.5, 2.0]
[[vary]]
key = "initial.gamma"
uniform = [[-1.0, -1.0, 0.2], [1.0, 1.0, 1.0]]
[[event]]
quantity = "gamma"
component = 1
"""

# Blow-ups (|Pi| = 1e200: Pi x Omega overflows in the first step) among ordinary lanes.
BLOW_UP = """
scene = "SCENES/free_body_hlw.toml"
scheme = "rkmk4"
dt = 0.01
t_end = 2.0
[[vary]]
key = "initial.angular_momentum"
values = [[0.1, 0.2, 0.3], [1e200, 1e200, 1e200], [0.5, -0.2, 0.1], [0.3, 0.3, 0.3], [1e200, 0.0, 1e200],
          [-0.4, 0.1, 0.2], [0.2, 0.9, -0.1], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.2, 0.2, -0.7]]
[[event]]
quantity = "angular_velocity"
component = 2
"""

# The preprocessed DMV (a kernel with a scalar scheme behind each lane): the
# same bodies, with lanes the scheme refuses (|h Ω| > π) among ordinary ones,
# crossings and thinned trajectories.
DMV = BLOW_UP.replace('scheme = "rkmk4"', 'scheme = "dmv-pre10"').replace("t_end = 2.0", "t_end = 2.0\ntrajectory_every = 30")


def available(tmp_path, isa):
    s = spec(tmp_path, BLOW_UP, "probe.toml")
    r = sweep("--spec", s, "--out", str(tmp_path / f"probe_{isa}.h5"), "--simd", isa, "--quiet", check=False)
    if r.returncode == 2 and "not available" in r.stderr:
        return False
    assert r.returncode == 0, r.stderr
    return True


@pytest.mark.parametrize("text", [LEVEL_SET, TWO_SCENES, BLOW_UP, DMV], ids=["level_set", "two_scenes", "blow_up", "dmv"])
def test_ensemble_rows_are_the_scalar_rows(tmp_path, text):
    s = spec(tmp_path, text)
    off = str(tmp_path / "off.h5")
    sweep("--spec", s, "--out", off, "--simd", "off", "--threads", "1", "--quiet")
    reference = columns(off)
    runs = [(isa, "1") for isa in ISAS if available(tmp_path, isa)] + [("auto", "2")]
    assert len(runs) >= 2
    for isa, threads in runs:
        out = str(tmp_path / f"{isa}_{threads}.h5")
        sweep("--spec", s, "--out", out, "--simd", isa, "--threads", threads, "--quiet")
        assert columns(out) == reference, (isa, threads)
        with h5py.File(out, "r") as f:
            used = f["provenance"].attrs["simd"]
            used = used.decode() if isinstance(used, bytes) else used
            assert isa == "auto" or used.startswith(isa), used
    with h5py.File(off, "r") as f:
        status = list(f["sweep/status"][()])
        used = f["provenance"].attrs["simd"]
        assert (used.decode() if isinstance(used, bytes) else used) == "off"
    if text is BLOW_UP or text is DMV:
        assert status == [0, 1, 0, 0, 1, 0, 0, 0, 0, 0]
    else:
        assert set(status) == {0}


def test_bad_simd_is_refused(tmp_path):
    s = spec(tmp_path, BLOW_UP)
    r = sweep("--spec", s, "--out", str(tmp_path / "bad.h5"), "--simd", "avx3", check=False)
    assert r.returncode == 2
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and "--simd" in lines[0] and "avx3" in lines[0], r.stderr
    assert not (tmp_path / "bad.h5").exists()


def test_provenance_says_when_the_ensemble_was_not_used(tmp_path):
    # dmv-pre10 has a kernel for the free body only: on a top it runs one trajectory at a time, and says why.
    top = LEVEL_SET.replace('scheme = "rkmk4"', 'scheme = "dmv-pre10"').replace("t_end = 4.0", "t_end = 0.5")
    for text, expected in ((top, "not used: no ensemble kernel for dmv-pre10 with torques"), (DMV, None)):
        out = str(tmp_path / "p.h5")
        sweep("--spec", spec(tmp_path, text), "--out", out, "--simd", "sse2", "--force", "--quiet")
        with h5py.File(out, "r") as f:
            used = f["provenance"].attrs["simd"]
            used = used.decode() if isinstance(used, bytes) else used
        if expected:
            assert used.startswith("sse2") and expected in used, used
        else:
            assert "not used" not in used, used
