"""The Python module lgi against the command line lgi (CTest python_module):
the same numbers from the same scene, the same messages for bad input and
failed runs, the GIL released during runs, out= writing the CLI's file,
Stepper equal to one run, the exact flow, the registry and scenes, sweeps."""
import json
import os
import stat
import subprocess
import threading
import time

import h5py
import numpy as np
import pytest

import lgi

from conftest import SCENES

BOOK = os.path.join(SCENES, "dzhanibekov_book_axis2.toml")
TOP = os.path.join(SCENES, "heavy_top_trindade_1.toml")
HLW = os.path.join(SCENES, "free_body_hlw.toml")


def run_cli(exe, *args):
    return subprocess.run([exe, *args], capture_output=True, text=True)


def cli_error(exe, *args):
    """The one line lgi prints on stderr, without its 'lgi: ' prefix."""
    r = run_cli(exe, *args)
    assert r.returncode != 0, r.stdout
    line = r.stderr.strip()
    assert line.startswith("lgi: ") and "\n" not in line, r.stderr
    return line[len("lgi: "):]


def series(f):
    """Every time series of a trajectory file, by module attribute name."""
    out = {
        "t": f["/particles/body/orientation/time"][()],
        "step": f["/particles/body/orientation/step"][()],
        "q": f["/particles/body/orientation/value"][()].reshape(-1, 4),
        "Pi": f["/particles/body/angular_momentum_body/value"][()].reshape(-1, 3),
        "omega": f["/particles/body/angular_velocity_body/value"][()].reshape(-1, 3),
        "energy": f["/observables/energy/value"][()],
        "orthogonality_error": f["/observables/orthogonality_error/value"][()],
    }
    if "angular_momentum_space" in f["/observables"]:
        out["angular_momentum_space"] = f["/observables/angular_momentum_space/value"][()]
    return out


def max_rel_diff(a, b):
    a, b = np.asarray(a, float), np.asarray(b, float)
    scale = np.maximum(np.abs(b), np.finfo(float).tiny)
    return float(np.max(np.abs(a - b) / scale)) if a.size else 0.0


@pytest.fixture(scope="module")
def cli_book(lgi_exe, tmp_path_factory):
    path = str(tmp_path_factory.mktemp("cli") / "book.h5")
    r = run_cli(lgi_exe, "simulate", "--scene", BOOK, "--scheme", "rkmk4", "--dt", "1e-3", "--t-end", "1",
                "--out", path, "--quiet")
    assert r.returncode == 0, r.stderr
    return path


def test_simulate_matches_cli(cli_book):
    run = lgi.simulate(lgi.Scene.from_file(BOOK), "rkmk4", 1.0, dt=1e-3)
    with h5py.File(cli_book, "r") as f:
        ref = series(f)
        invariants = {k: f[f"/observables/{k}/value"][()] for k in run.invariants}
        diag = dict(f["/diagnostics"].attrs)
    assert len(run) == 1001 and run.out is None
    for name, values in ref.items():
        got = getattr(run, name)
        assert got.shape == values.shape, name
        assert max_rel_diff(got, values) <= 1e-15, name
        assert np.array_equal(got, values), name  # in fact bit for bit
    for name, values in invariants.items():
        assert np.array_equal(run.invariants[name], values), name
    for key in ("steps", "rhs_evaluations", "rejected_steps", "newton_iterations_max", "newton_failures"):
        assert run.diagnostics[key] == diag[key], key
    assert run.diagnostics["ok"] and run.diagnostics["status"] == "ok"
    # R is the scheme's own matrix, q its quaternion: the same attitude.
    w, x, y, z = run.q[-1]
    R_q = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                    [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                    [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    assert np.allclose(run.R[-1], R_q, atol=1e-14)
    assert run.errors["energy"][0] == 0.0 and run.errors["energy"][-1] < 1e-12


def test_out_writes_the_cli_file(cli_book, tmp_path):
    out = tmp_path / "module.h5"
    run = lgi.simulate(BOOK, "rkmk4", 1.0, dt=1e-3, out=out)
    assert run.out == str(out) and os.path.exists(out) and not os.path.exists(str(out) + ".partial")
    with h5py.File(out, "r") as mine, h5py.File(cli_book, "r") as cli:
        names = []
        cli.visit(lambda n: names.append(n) if isinstance(cli[n], h5py.Dataset) else None)
        assert names
        for n in names:
            assert np.array_equal(mine[n][()], cli[n][()]), n
            assert dict(mine[n].attrs) == dict(cli[n].attrs), n
        for key, value in cli["/diagnostics"].attrs.items():
            if key not in ("cpu_seconds", "output_seconds"):
                assert mine["/diagnostics"].attrs[key] == value, key
        for key in ("scheme", "dt", "t_end", "save_every", "scene_toml", "scene_file", "build_type", "cxx_flags"):
            assert mine["/parameters"].attrs[key] == cli["/parameters"].attrs[key], key
        assert mine["/parameters"].attrs["command_line"].startswith("lgi.simulate(")
    with pytest.raises(OSError, match="exists"):
        lgi.simulate(BOOK, "rkmk4", 0.01, dt=1e-3, out=out)
    lgi.simulate(BOOK, "rkmk4", 0.01, dt=1e-3, out=out, force=True)


def test_force_never_replaces_what_is_not_a_regular_file(tmp_path):
    """README.md, "Limits": out='' is refused, and force=True replaces only a regular file; a
    FIFO, a directory or (as root, a private one) a device node stays as it was."""
    with pytest.raises(OSError, match="empty"):
        lgi.simulate(BOOK, "rkmk4", 0.01, dt=1e-3, out="")
    fifo = str(tmp_path / "fifo")
    os.mkfifo(fifo)
    folder = str(tmp_path / "folder")
    os.mkdir(folder)
    targets = [(fifo, "FIFO"), (folder, "directory")]
    if os.geteuid() == 0:
        node = str(tmp_path / "node")
        try:
            os.mknod(node, 0o600 | stat.S_IFCHR, os.makedev(1, 3))
            targets.append((node, "device"))
        except PermissionError:
            pass
    for path, word in targets:
        before = os.lstat(path)
        with pytest.raises(OSError, match=word):
            lgi.simulate(BOOK, "rkmk4", 0.01, dt=1e-3, out=path, force=True)
        after = os.lstat(path)
        assert (after.st_mode, after.st_ino, after.st_rdev) == (before.st_mode, before.st_ino, before.st_rdev)
        assert not os.path.exists(path + ".partial")
    with pytest.raises(ValueError, match="threads"):
        lgi.sweep({"scene": BOOK}, threads=10**6)


def test_no_file_without_out(tmp_path):
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        lgi.simulate(BOOK, "rkmk4", 0.01, dt=1e-3)
    finally:
        os.chdir(cwd)
    assert os.listdir(tmp_path) == []


def test_bad_scene_key_names_it_as_the_cli(lgi_exe, tmp_path):
    text = 'name = "bad"\n[body]\ninertia = [1.0, 2.0]\n[initial]\nangular_velocity = [0.0, 1.0, 0.0]\n'
    path = tmp_path / "bad.toml"
    path.write_text(text)
    expected = cli_error(lgi_exe, "simulate", "--scene", str(path), "--scheme", "rkmk4", "--dt", "0.1",
                         "--t-end", "1", "--out", str(tmp_path / "x.h5"))
    assert "[body] inertia:" in expected
    with pytest.raises(ValueError) as file_error:
        lgi.Scene.from_file(str(path))
    assert str(file_error.value) == expected
    with pytest.raises(ValueError) as kwargs_error:
        lgi.Scene(name="bad", body={"inertia": [1.0, 2.0]}, initial={"angular_velocity": [0.0, 1.0, 0.0]})
    # The same message, located at the keyword arguments instead of a file line.
    assert str(kwargs_error.value) == "Scene(**kwargs):" + expected.split(":", 2)[2]
    with pytest.raises(ValueError, match=r"\[body\] inertai"):
        lgi.Scene(name="typo", body={"inertai": [1.0, 2.0, 3.0]}, initial={"angular_velocity": [0.0, 1.0, 0.0]})


def test_output_dt_interpolates_a_dense_pair(tmp_path):
    out = str(tmp_path / "d.h5")
    plain = lgi.simulate(TOP, "rkmk-verner87", 1.0, tol=1e-10)
    run = lgi.simulate(TOP, "rkmk-verner87", 1.0, tol=1e-10, output_dt=0.125, out=out)
    assert list(run.t) == [0.125 * k for k in range(9)]
    assert run.diagnostics["steps"] == plain.diagnostics["steps"]
    assert np.array_equal(run.R[-1], plain.R[-1]) and np.array_equal(run.Pi[-1], plain.Pi[-1])
    with h5py.File(out, "r") as f:
        assert f["/parameters"].attrs["output_dt"] == 0.125
        assert "output_dt=0.125" in f["/parameters"].attrs["command_line"]
    with pytest.raises(ValueError, match="--output-dt"):
        lgi.simulate(TOP, "rkmk4", 1.0, dt=0.01, output_dt=0.015)
    with pytest.raises(ValueError, match="--output-dt"):
        lgi.simulate(TOP, "rkmk4", 1.0, dt=0.01, output_dt=0.1, save_every=2)


def test_scene_from_keywords_equals_the_file():
    book = lgi.Scene.from_file(BOOK)
    same = lgi.Scene(name=book.name, body={"inertia": np.diag(book.inertia)},
                     initial={"angular_velocity": [0.01, 10.0, 0.01]}, run={"t_end": 14.0, "dt": 1e-3})
    assert np.array_equal(same.inertia, book.inertia) and np.array_equal(same.Pi0, book.Pi0)
    assert same.t_end == 14.0 and same.dt == 1e-3 and same.tol is None
    assert same.free_body and same.invariants == book.invariants
    a = lgi.simulate(book, "rkmk4", 0.1, dt=1e-3)
    b = lgi.simulate(same, "rkmk4", 0.1, dt=1e-3)
    assert np.array_equal(a.R, b.R) and np.array_equal(a.Pi, b.Pi)


def test_bad_scheme_and_unsupported_scene_as_the_cli(lgi_exe, tmp_path):
    out = str(tmp_path / "x.h5")
    expected = cli_error(lgi_exe, "simulate", "--scene", BOOK, "--scheme", "rkmk5", "--dt", "0.1", "--out", out)
    with pytest.raises(ValueError) as e:
        lgi.simulate(BOOK, "rkmk5", 1.0, dt=0.1)
    assert str(e.value) == expected
    expected = cli_error(lgi_exe, "simulate", "--scene", TOP, "--scheme", "exact", "--dt", "0.1", "--out", out)
    with pytest.raises(ValueError) as e:
        lgi.simulate(TOP, "exact", dt=0.1)
    assert str(e.value) == expected
    expected = cli_error(lgi_exe, "simulate", "--scene", BOOK, "--scheme", "rkmk4", "--tol", "1e-6", "--out", out)
    with pytest.raises(ValueError) as e:
        lgi.simulate(BOOK, "rkmk4", tol=1e-6)
    assert str(e.value) == expected


def test_failed_run_raises_the_cli_message(lgi_exe, tmp_path):
    cli_out = str(tmp_path / "cli.h5")
    expected = cli_error(lgi_exe, "simulate", "--scene", TOP, "--scheme", "rkmk-radau5", "--dt", "0.5",
                         "--out", cli_out)
    assert "did not converge" in expected and expected.endswith(cli_out + ".partial")
    with pytest.raises(RuntimeError) as e:
        lgi.simulate(TOP, "rkmk-radau5", dt=0.5)
    assert str(e.value) == expected.split("; partial trajectory kept in")[0]
    mine = str(tmp_path / "mine.h5")
    with pytest.raises(RuntimeError) as e:
        lgi.simulate(TOP, "rkmk-radau5", dt=0.5, out=mine)
    assert str(e.value) == expected.replace(cli_out, mine)
    assert os.path.exists(mine + ".partial") and not os.path.exists(mine)


LONG = dict(t_end=4.0, dt=4e-6, save_every=10**6)  # 1e6 rkmk4 steps, about 0.2 s of CPU


def test_gil_released_other_threads_run_meanwhile():
    """While one thread is inside a long simulate, another completes many short ones
    (with the GIL held throughout, it could complete at most one)."""
    done = []
    t_start = time.perf_counter()
    worker = threading.Thread(target=lambda: done.append(lgi.simulate(BOOK, "rkmk4", **LONG)))
    worker.start()
    short = 0
    while worker.is_alive():
        lgi.simulate(BOOK, "rkmk4", 0.01, dt=1e-3)
        short += 1 if worker.is_alive() else 0
    worker.join()
    assert done and short >= 5, f"{short} short runs during a {time.perf_counter() - t_start:.2f} s run"


@pytest.mark.skipif((os.cpu_count() or 1) < 2, reason="needs 2 cores")
def test_gil_released_two_runs_in_parallel():
    """Two threads' runs overlap: their CPU seconds add up to more than the wall time.
    Skipped when other processes keep every core busy (the parallelism cannot show)."""
    if os.getloadavg()[0] > (os.cpu_count() or 1) - 0.5:
        pytest.skip(f"machine busy (load average {os.getloadavg()[0]:.1f})")
    best = 0.0
    for _ in range(3):
        results = []
        threads = [threading.Thread(target=lambda: results.append(lgi.simulate(BOOK, "rkmk4", **LONG)))
                   for _ in range(2)]
        wall = time.perf_counter()
        for t in threads:
            t.start()
        for t in threads:
            t.join()
        wall = time.perf_counter() - wall
        cpu = sum(r.diagnostics["cpu_seconds"] for r in results)
        best = max(best, cpu / wall)
        if best > 1.4:
            break
    assert best > 1.4, f"CPU/wall of two concurrent runs: {best:.2f} (1 = serialised, 2 = fully parallel)"


def test_stepper_equals_one_run():
    dt = 1e-3
    stepper = lgi.Stepper(BOOK, "rkmk4", dt)
    for _ in range(100):
        stepper.step()
    run = lgi.simulate(BOOK, "rkmk4", 100 * dt, dt=dt)
    assert stepper.t == run.t[-1]
    assert np.array_equal(stepper.state["R"], run.R[-1]) and np.array_equal(stepper.state["Pi"], run.Pi[-1])
    assert stepper.stats["steps"] == 100 and stepper.stats["rhs_evaluations"] == run.diagnostics["rhs_evaluations"]
    batched = lgi.Stepper(lgi.Scene.from_file(BOOK), "rkmk4", dt)
    batched.step(100)
    assert np.array_equal(batched.state["R"], run.R[-1])
    with pytest.raises(ValueError, match="adaptive"):
        lgi.Stepper(BOOK, "rkmk-dp54", dt)
    with pytest.raises(ValueError, match="free bod"):
        lgi.Stepper(TOP, "exact", dt)


def test_stepper_failure_raises():
    stepper = lgi.Stepper(TOP, "rkmk-radau5", 0.5)
    with pytest.raises(RuntimeError, match="did not converge"):
        stepper.step(3)


def test_exact_free_flow_against_a_fine_run():
    run = lgi.simulate(BOOK, "rkmk4", 2.0, dt=1e-4, save_every=500)
    R, Pi = lgi.exact_free_flow(lgi.Scene.from_file(BOOK), run.t)
    assert R.shape == (len(run), 3, 3) and Pi.shape == (len(run), 3)
    assert np.max(np.abs(R - run.R)) < 1e-10
    assert np.max(np.linalg.norm(Pi - run.Pi, axis=1)) < 1e-10 * np.linalg.norm(Pi[0])
    exact = lgi.simulate(BOOK, "exact", 2.0, dt=0.1)
    R2, Pi2 = lgi.exact_free_flow(BOOK, exact.t)
    assert np.max(np.abs(R2 - exact.R)) < 1e-13 and np.allclose(Pi2, exact.Pi, rtol=0, atol=1e-13)
    assert np.allclose(lgi.exact_free_flow(BOOK, [0.0])[0][0], lgi.Scene.from_file(BOOK).R0, rtol=0, atol=1e-15)
    with pytest.raises(ValueError, match="free bod"):
        lgi.exact_free_flow(TOP, [0.0, 1.0])
    for bad in (np.nan, np.inf, -np.inf):  # issue 50: refused naming the element, not returned as NaN
        with pytest.raises(ValueError, match="element 1 is not a finite number"):
            lgi.exact_free_flow(BOOK, [0.0, bad])


def test_schemes_match_lgi_schemes_json(lgi_exe):
    r = run_cli(lgi_exe, "schemes", "--json")
    assert r.returncode == 0
    cli = json.loads(r.stdout)
    mine = lgi.schemes()
    assert [s["name"] for s in mine] == [s["name"] for s in cli]
    for m, c in zip(mine, cli):
        flat = {k: v for k, v in m.items() if k not in ("properties", "support")}
        flat.update(m["properties"])
        flat["scenes"] = m["support"]
        assert flat == c
    rkmk4 = next(s for s in mine if s["name"] == "rkmk4")
    assert rkmk4["order"] == 4 and rkmk4["kind"] == "lie-group" and rkmk4["reference"]
    assert not rkmk4["properties"]["adaptive"] and rkmk4["support"] == "all scenes"
    dense = {s["name"] for s in mine if s["properties"]["dense_output"]}
    assert {"rkmk-dop853", "rkmk-verner65", "rkmk-verner87", "rkmk-verner98", "quat/dopri5"} <= dense
    assert not dense & {"rkmk-dp54", "rkmk4", "quat/rkf78"}


def test_scenes_match_lgi_scenes(lgi_exe):
    r = run_cli(lgi_exe, "scenes", SCENES)
    assert r.returncode == 0
    lines = [line.split("\t") for line in r.stdout.splitlines()]
    mine = lgi.scenes()
    assert os.path.samefile(lgi.scenes_dir(), SCENES)
    assert [(s["file"], s["name"]) for s in mine] == [(f, n) for f, n, _ in lines]
    for s, (_, _, inv) in zip(mine, lines):
        assert inv == "invariants: " + (", ".join(s["invariants"]) or "none")
    book = next(s for s in mine if s["file"] == "dzhanibekov_book_axis2.toml")
    assert book["free_body"] and book["dt"] == 1e-3 and book["t_end"] == 14.0


def test_sweep_matches_lgi_sweep(lgi_exe, tmp_path):
    spec = {"name": "tiny", "scene": HLW, "scheme": "rkmk4", "dt": 0.01, "t_end": 1.0,
            "vary": [{"key": "initial.angular_momentum", "component": 1, "linspace": [-1.0, 1.0, 3]}]}
    table = lgi.sweep(spec, threads=2)
    assert len(table) == 3 and list(table["index"]) == [0, 1, 2]
    assert np.all(table["status"] == 0) and np.all(table["t_final"] == 1.0)
    assert table["angular_momentum"].shape == (3, 3)
    spec_file = tmp_path / "tiny.toml"
    spec_file.write_text(f'name = "tiny"\nscene = "{HLW}"\nscheme = "rkmk4"\ndt = 0.01\nt_end = 1.0\n'
                         '[[vary]]\nkey = "initial.angular_momentum"\ncomponent = 1\nlinspace = [-1.0, 1.0, 3]\n')
    out = tmp_path / "cli.h5"
    r = run_cli(lgi_exe, "sweep", "--spec", str(spec_file), "--out", str(out), "--threads", "1", "--quiet")
    assert r.returncode == 0, r.stderr
    with h5py.File(out, "r") as f:
        for name in table.dtype.names:
            if name in ("cpu_seconds", "reason"):
                continue
            assert np.array_equal(table[name], f["/sweep/" + name][()]), name
    from_file = lgi.sweep(str(spec_file))
    assert np.array_equal(from_file["angular_momentum"], table["angular_momentum"])
    with pytest.raises(ValueError, match="scheme"):
        lgi.sweep(dict(spec, scheme="rkmk5"))


def test_docstrings_are_useful():
    assert "t_end" in lgi.simulate.__doc__ and "RuntimeError" in lgi.simulate.__doc__
    for f in (lgi.schemes, lgi.scenes, lgi.exact_free_flow, lgi.sweep, lgi.Stepper, lgi.Scene):
        assert f.__doc__ and len(f.__doc__) > 60, f
    stub = os.path.join(os.path.dirname(lgi.__file__), "__init__.pyi")
    assert os.path.exists(stub)
