"""`lgi poincare` as a user runs it (experiments/POINCARE.md): crossings on
Richter's section S = d(Gamma.e)/dt = 0 to round-off, section coordinates
consistent with Gamma, identical results for 1 and 2 threads and with or
without the chaos indicators, the gamma section, a gamma_rate event in a
sweep spec, and the refusals (an empty level set, a spring) with exit 2."""
import os
import signal
import subprocess
import time

import h5py
import numpy as np

LGI = os.environ.get("LGI_EXECUTABLE", "build/release/lgi")
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SCENES = os.path.join(ROOT, "experiments", "scenes")
KOVALEVSKAYA = os.path.join(SCENES, "kovalevskaya.toml")
GENERAL = os.path.join(SCENES, "general_top_richter.toml")


def poincare(*args, check=True):
    r = subprocess.run([LGI, "poincare", "--quiet", *args], capture_output=True, text=True, timeout=300)
    if check:
        assert r.returncode == 0, r.stderr
    return r


def columns(path, skip=("cpu_seconds",)):
    out = {}
    with h5py.File(path, "r") as f:
        for g in ("sweep", "events"):
            for k in f[g]:
                if k not in skip:
                    out[g + "/" + k] = f[g][k][()].tobytes()
    return out


def frame(e):
    """(f1, f2) of docs/atlas.md §6: the body axis least aligned with e, made orthogonal to e."""
    k = int(np.argmin(np.abs(e)))
    f1 = np.eye(3)[k] - e[k] * e
    f1 /= np.linalg.norm(f1)
    return f1, np.cross(e, f1)


def test_crossings_on_the_section_and_coordinates(tmp_path):
    out = str(tmp_path / "pc.h5")
    poincare("--scene", GENERAL, "--l", "1", "--h", "1.5", "--ics", "4", "--t-end", "40", "--out", out)
    J = np.array([1.0, 1.5, 2.0])
    e = np.array([0.8, 0.4, 0.3]) / np.linalg.norm([0.8, 0.4, 0.3])  # default axis: chi/|chi|
    with h5py.File(out, "r") as f:
        ev = {k: f["events"][k][()] for k in f["events"]}
        assert np.allclose([f["parameters"].attrs[f"axis_{k}"] for k in (1, 2, 3)], e, atol=1e-15)
    G, P = ev["gamma"], ev["angular_momentum"]
    assert len(G) > 20
    W = P / J
    S = np.cross(G, W) @ e
    assert np.abs(S).max() < 1e-12 * max(1.0, np.abs(W).max())
    f1, f2 = frame(e)
    th, ph = ev["theta"], ev["phi"]
    back = (np.cos(th)[:, None] * e + np.sin(th)[:, None] * (np.cos(ph)[:, None] * f1 + np.sin(ph)[:, None] * f2))
    assert np.abs(back - G).max() < 1e-13
    assert ((ph >= 0) & (ph < 2 * np.pi)).all() and ((th >= 0) & (th <= np.pi)).all()
    phi_rate = (G @ e) * np.sum(G * W, axis=1) - W @ e
    assert (ev["sheet"] == np.where(phi_rate < 0, -1, 1)).all()
    # direction is the sign of dS/dt: S rises through 0 on a +1 crossing.
    assert set(np.unique(ev["direction"])) <= {-1, 1}


def test_threads_and_indicators_leave_the_section_unchanged(tmp_path):
    outs = []
    for threads, flags in (("1", []), ("2", []), ("2", ["--megno", "--lyapunov"])):
        o = str(tmp_path / f"pc{threads}{len(flags)}.h5")
        poincare("--scene", KOVALEVSKAYA, "--l", "1", "--h", "2", "--ics", "6", "--t-end", "30", "--threads", threads,
                 "--out", o, *flags)
        outs.append(o)
    a, b, c = (columns(o) for o in outs)
    assert a == b
    assert {k: v for k, v in c.items() if k not in ("sweep/megno", "sweep/lyapunov")} == a
    # the indicators themselves, 1 against 2 threads
    o1 = str(tmp_path / "m1.h5")
    poincare("--scene", KOVALEVSKAYA, "--l", "1", "--h", "2", "--ics", "6", "--t-end", "30", "--threads", "1",
             "--out", o1, "--megno", "--lyapunov")
    assert columns(o1) == c


def test_gamma_section(tmp_path):
    out = str(tmp_path / "g.h5")
    poincare("--scene", KOVALEVSKAYA, "--l", "1", "--h", "2", "--ics", "2", "--t-end", "30", "--section", "gamma",
             "--axis", "e3", "--out", out)
    with h5py.File(out, "r") as f:
        G = f["events/gamma"][()]
        assert len(G) > 5
        assert np.abs(G[:, 2]).max() < 1e-13
    out3 = str(tmp_path / "g3.h5")
    poincare("--scene", KOVALEVSKAYA, "--l", "1", "--h", "2", "--ics", "2", "--t-end", "30", "--section", "gamma3",
             "--out", out3)
    assert columns(out3) == columns(out)


def test_gamma_rate_event_in_a_sweep_spec(tmp_path):
    spec = tmp_path / "s.toml"
    spec.write_text(f'scene = "{KOVALEVSKAYA}"\nscheme = "rkmk4"\nt_end = 20.0\nsamples = 2\nseed = 1\n'
                    '[level_set]\nl = 1.0\nh = 2.0\n[[event]]\nquantity = "gamma_rate"\ncomponent = 1\n')
    out = str(tmp_path / "s.h5")
    r = subprocess.run([LGI, "sweep", "--spec", str(spec), "--out", out, "--quiet"], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    with h5py.File(out, "r") as f:
        G, P = f["events/gamma"][()], f["events/angular_momentum"][()]
        assert f["events"].attrs["names"][0] in (b"gamma_rate1_both", "gamma_rate1_both")
    assert len(G) > 5
    assert np.abs(np.cross(G, P / [2.0, 2.0, 1.0])[:, 0]).max() < 1e-12


def test_empty_level_and_spring_are_refused(tmp_path):
    out = str(tmp_path / "x.h5")
    r = poincare("--scene", KOVALEVSKAYA, "--l", "1", "--h", "-5", "--ics", "2", "--t-end", "10", "--out", out,
                 check=False)
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1
    assert "h is below the minimum energy at this l" in r.stderr
    assert not os.path.exists(out) and not os.path.exists(out + ".partial")
    r = poincare("--scene", os.path.join(SCENES, "stiff_damped_spring.toml"), "--l", "1", "--h", "2", "--ics", "2",
                 "--t-end", "10", "--out", out, check=False)
    assert r.returncode == 2
    assert "needs a heavy top" in r.stderr
    r = poincare("--scene", KOVALEVSKAYA, "--l", "1", "--h", "2", "--ics", "2", "--t-end", "10", "--axis", "0,0,0",
                 "--out", out, check=False)
    assert r.returncode == 2 and "--axis" in r.stderr


def test_lagrange_crossings_on_the_nutation_circles(tmp_path):
    """Lagrange top, axis e3: S = dGamma3/dt = 0 at the nutation's turning points u1, u2
    (docs/atlas.md §5-§6), so each orbit's crossings lie on two circles theta = arccos u."""
    scene = tmp_path / "lagrange.toml"
    scene.write_text('name = "Lagrange top"\n[body]\nmass = 1.0\ninertia = [1.0, 1.0, 0.5]\n'
                     'center_of_mass = [0.0, 0.0, 1.0]\n[gravity]\ng = 1.0\n[initial]\n'
                     'angular_velocity = [0.1, 0.2, 3.0]\n[run]\nt_end = 10.0\ndt = 0.01\n')
    out = str(tmp_path / "lag.h5")
    poincare("--scene", str(scene), "--l", "1", "--h", "2.5", "--ics", "4", "--t-end", "60", "--out", out)
    with h5py.File(out, "r") as f:
        assert [f["parameters"].attrs[f"axis_{k}"] for k in (1, 2, 3)] == [0.0, 0.0, 1.0]
        idx, th = f["events/index"][()], f["events/theta"][()]
    for i in range(4):
        t = np.sort(th[idx == i])
        assert len(t) >= 6
        gap = np.argmax(np.diff(t))
        low, high = t[:gap + 1], t[gap + 1:]
        assert np.ptp(low) < 1e-6 and np.ptp(high) < 1e-6, (np.ptp(low), np.ptp(high))


def test_sigint_while_the_indicators_are_computed(tmp_path):
    """Ctrl-C after the crossings are written, while MEGNO and Lyapunov are
    integrated: exit 130, the orbits kept in <out>.partial, nothing
    published and no <out>.writing left behind."""
    out = str(tmp_path / "s.h5")
    p = subprocess.Popen([LGI, "poincare", "--quiet", "--scene", GENERAL, "--l", "1", "--h", "1.5", "--ics", "4",
                          "--t-end", "6000", "--threads", "1", "--lyapunov", "--out", out],
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    end = time.monotonic() + 120
    while not os.path.exists(out + ".writing") and p.poll() is None and time.monotonic() < end:
        time.sleep(0.001)
    assert p.poll() is None, "the run ended before its indicators"
    p.send_signal(signal.SIGINT)
    err = p.communicate(timeout=120)[1]
    assert p.returncode == 130, err
    assert "while it computed the indicators" in err and err.count("\n") == 1, err
    assert not os.path.exists(out) and not os.path.exists(out + ".writing")
    with h5py.File(out + ".partial", "r") as f:
        assert f["sweep"]["status"].shape[0] == 4
