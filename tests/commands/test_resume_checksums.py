"""Resumes that verify what they continue (issue 50, item 5): every finished row of a sweep's
and of a long-time run's .partial carries an FNV-1a checksum, and --resume checks each one
before it goes on. A bit flipped in a finished row, in its status, or a status set by hand on
a row that was never computed is refused with exit 2, one line naming the row, and the files
left byte for byte as they were (experiments/SWEEPS.md, "Resuming"; RESULTS.md, "long-time
--resume"). The bits are flipped in the file's bytes (h5py only locates them), as a disk would."""
import os
import signal
import struct
import subprocess
import time

import h5py
import numpy as np
from pacing import LONG_SWEEP, slowdown, wait_part_way

LGI = os.environ.get("LGI_EXECUTABLE", "build/release/lgi")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
FREE = os.path.join(SCENES, "free_body_hlw.toml")


def read(path):
    with open(path, "rb") as f:
        return f.read()


def flip(path, offset, mask=1):
    with open(path, "r+b") as f:
        f.seek(offset)
        b = f.read(1)[0]
        f.seek(offset)
        f.write(bytes([b ^ mask]))


def put(path, offset, data):
    with open(path, "r+b") as f:
        f.seek(offset)
        f.write(data)


def element_offset(dset, index):
    """Byte offset in the file of element `index` (first axis) of a dataset, contiguous or chunked."""
    row = dset.dtype.itemsize * int(np.prod(dset.shape[1:], dtype=np.int64))
    if dset.chunks is None:
        return dset.id.get_offset() + index * row
    chunk_rows = dset.chunks[0]
    info = dset.id.get_chunk_info_by_coord((index - index % chunk_rows,) + (0,) * (len(dset.shape) - 1))
    return info.byte_offset + (index % chunk_rows) * row


def refused(r, row, *files_before):
    assert r.returncode == 2, r.stderr
    assert r.stderr.count("\n") == 1 and f"row {row} " in r.stderr and "checksum" in r.stderr, r.stderr
    for path, before in files_before:
        assert read(path) == before, f"{path} was changed"


def test_sweep_resume_refuses_a_damaged_row_naming_it(tmp_path):
    spec = tmp_path / "spec.toml"
    spec.write_text(LONG_SWEEP.replace("SCENES", SCENES))
    out = str(tmp_path / "s.h5")
    partial = out + ".partial"
    p = subprocess.Popen([LGI, "sweep", "--spec", str(spec), "--out", out, "--threads", "1", "--quiet"])
    wait_part_way(p, partial)
    p.send_signal(signal.SIGKILL)
    p.wait()
    with h5py.File(partial, "r") as f:
        status = f["sweep/status"][()]
        done, pending = np.flatnonzero(status >= 0), np.flatnonzero(status < 0)
        assert len(done) > 2 and len(pending) > 0
        momentum = element_offset(f["sweep/angular_momentum"], int(done[1]))
        status_done = element_offset(f["sweep/status"], int(done[2]))
        status_pending = element_offset(f["sweep/status"], int(pending[-1]))
    pristine = read(partial)
    resume = [LGI, "sweep", "--spec", str(spec), "--out", out, "--threads", "1", "--quiet", "--resume"]
    for change, row in [(lambda: flip(partial, momentum + 3), done[1]),
                        (lambda: flip(partial, status_done), done[2]),
                        (lambda: put(partial, status_pending, struct.pack("<q", 0)), pending[-1])]:
        change()
        before = read(partial)
        refused(subprocess.run(resume, capture_output=True, text=True, timeout=120), int(row), (partial, before))
        assert not os.path.exists(out)
        with open(partial, "wb") as f:
            f.write(pristine)


def test_long_time_resume_refuses_a_damaged_row_naming_it(tmp_path):
    out = str(tmp_path / "lt.h5")
    csv = str(tmp_path / "lt.csv.partial")
    partial = out + ".partial"
    args = [LGI, "long-time", "--scene", FREE, "--scheme", "rkmk4", "--dt", "1e-4", "--t-end", "1e5", "--samples",
            "200", "--flush-seconds", "0.05", "--out", out, "--quiet"]
    p = subprocess.Popen(args, stderr=subprocess.DEVNULL)
    while not os.path.exists(partial):
        assert p.poll() is None
        time.sleep(0.01)
    time.sleep(1.0 * slowdown(LGI))
    p.send_signal(signal.SIGINT)
    assert p.wait(timeout=60) == 130
    with h5py.File(partial, "r") as f:
        record = f["resume/checkpoint"][()].tobytes()
        # The newest checkpoint's row count (run_checkpoint.hpp: magic, sequence, length, hash, then rows).
        slots = [record[k:k + 4096] for k in (0, 4096)]
        rows = max((struct.unpack_from("<Qq", s, 8)[0], struct.unpack_from("<q", s, 32)[0])
                   for s in slots if s[:8] == b"lgickpt1")[1]
        assert rows > 3, rows
        time_offset = element_offset(f["series/time"], rows - 2)
    csv_text = read(csv)
    line_start = [i + 1 for i, c in enumerate(csv_text) if c == ord("\n")]  # after the header, after each row
    originals = (read(partial), csv_text)
    resume = args + ["--resume"]
    for path, offset, row in [(partial, time_offset, rows - 2), (csv, line_start[1], 1)]:
        flip(path, offset)
        before = [(partial, read(partial)), (csv, read(csv))]
        refused(subprocess.run(resume, capture_output=True, text=True, timeout=120), row, *before)
        for p_, data in zip((partial, csv), originals):
            with open(p_, "wb") as f:
                f.write(data)
    # Undamaged, the same files resume (cut again: only the start matters here).
    p = subprocess.Popen(resume, stderr=subprocess.PIPE, text=True)
    time.sleep(0.5 * slowdown(LGI))
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=60)
    assert p.returncode in (0, 130), err
