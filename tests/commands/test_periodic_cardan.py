"""`lgi periodic` on a Cardan top with a vertical outer axis (experiments/PERIODIC.md,
"Cardan tops"): the flow reduced at p1 = l.
 - --from-equilibria on cardan_general_asymmetric_up at l = 1: every family's
   first period is 2*pi/omega to 1e-6, omega from g1, g2 of `lgi equilibria`;
   residuals <= 1e-10; the four trivial multipliers (q1, p1, H, the flow) at 1
   to 1e-8 and the product of all six at 1 to 1e-8;
 - each orbit's point (cardan_angles, cardan_momenta), integrated for one period
   by SciPy's DOP853 on the canonical field recomputed here from docs/cardan.md
   eqs. (1)-(5) (dH/dq by complex steps), returns to itself in q2, q3 (mod 2 pi),
   p to 1e-8, q1 turned by cardan_drift; angular_momentum and gamma are the
   body's J E(q) qdot and R(q)^T e3;
 - --seed-file (q1 q2 q3 p1 p2 p3 T) finds a family's orbit again, by single
   shooting and by multiple shooting on 3 segments (period to 1e-9, same drift);
 - refusals with exit 2 and one line: a tilted frame (naming suspension.tilt
   and the missing cyclic angle), a seed whose p1 is not --l, --from-critical;
 - --seeds-from-poincare (a point of lgi poincare's section, its rows) and --continue-in l;
 - --manifolds on an inverse hyperbolic orbit (lambda = -3.63), against the return map computed
   here by DOP853 from the section's points (test_manifolds_of_an_inverse_hyperbolic_cardan_orbit)."""
import math
import os
import shutil

import h5py
import numpy as np
from lgi_cli import SCENES, columns, lgi, refused
from scipy.integrate import solve_ivp

UP = os.path.join(SCENES, "cardan_general_asymmetric_up.toml")
HORIZONTAL = os.path.join(SCENES, "cardan_general_horizontal.toml")

# cardan_general_asymmetric_up.toml: J about the fixed point, m chi, g; thin rings.
J = np.diag([1.0, 1.5, 2.0])
M_CHI = np.array([0.8, 0.4, 0.3])
G = 1.0
C_O, K = 0.3, np.array([0.15, 0.3, 0.15])


def rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0 * a], [s, c, 0 * a], [0 * a, 0 * a, 1 + 0 * a]])


def rx(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1 + 0 * a, 0 * a, 0 * a], [0 * a, c, -s], [0 * a, s, c]])


def e_matrix(q):
    s2, c2, s3, c3 = np.sin(q[1]), np.cos(q[1]), np.sin(q[2]), np.cos(q[2])
    return np.array([[s2 * s3, c3, 0 * s2], [s2 * c3, -s3, 0 * s2], [c2, 0 * s2, 0 * s2 + 1]])


def mass_matrix(q):
    """docs/cardan.md eq. (4)."""
    E = e_matrix(q)
    F = np.array([[0 * q[1], 1 + 0 * q[1], 0 * q[1]], [np.sin(q[1]), 0 * q[1], 0 * q[1]],
                  [np.cos(q[1]), 0 * q[1], 0 * q[1]]])
    M = E.T @ J @ E + F.T @ np.diag(K) @ F
    M[0, 0] = M[0, 0] + C_O
    return M


def energy(q, p):
    """H = p M^-1 p / 2 + V, V = g e3 . Rz(q1) Rx(q2) Rz(q3) m chi (eq. (5), tilt 0, massless-centred rings)."""
    return 0.5 * p @ np.linalg.solve(mass_matrix(q), p) + G * (rz(q[0]) @ rx(q[1]) @ rz(q[2]) @ M_CHI)[2]


def field(_, x):
    q, p = x[:3], x[3:]
    qdot = np.linalg.solve(mass_matrix(q), p)
    h = 1e-30  # complex step: dH/dq_k = Im H(q + i h e_k) / h, exact to round-off
    dH = [energy(q + 1j * h * np.eye(3)[k], p.astype(complex)).imag / h for k in range(3)]
    return np.concatenate([qdot, -np.array(dH)])


def assert_returns_after_one_period(p, i):
    """Row i's point, integrated for one period by SciPy's DOP853 on the field above, returns to itself:
    (q2, q3) mod 2 pi and p to 1e-8, and q1 turned by cardan_drift."""
    q0, p0 = p["cardan_angles"][i], p["cardan_momenta"][i]
    s = solve_ivp(field, (0, p["period"][i]), np.concatenate([q0, p0]), method="DOP853", rtol=1e-13, atol=1e-13)
    end = s.y[:, -1]
    dq = (end[1:3] - q0[1:3] + math.pi) % (2 * math.pi) - math.pi
    assert np.abs(dq).max() < 1e-8 and np.abs(end[3:] - p0).max() < 1e-8, (i, dq, end[3:] - p0)
    assert abs(end[0] - q0[0] - p["cardan_drift"][i]) < 1e-8


def frequencies(g1, g2):
    disc = math.sqrt(g1 * g1 - 4 * g2)
    return sorted(math.sqrt(-mu) for mu in (0.5 * (-g1 - disc), 0.5 * (-g1 + disc)) if mu < 0)


def test_lyapunov_families_of_a_cardan_top(tmp_path):
    eq_out, out = str(tmp_path / "e.h5"), str(tmp_path / "p.h5")
    lgi("equilibria", "--scene", UP, "--l", "1", "--out", eq_out, "--quiet")
    lgi("periodic", "--scene", UP, "--l", "1", "--from-equilibria", "--steps", "2", "--h-step", "0.02",
        "--out", out, "--quiet")
    e, p = columns(eq_out, "equilibria"), columns(out, "periodic")
    for column in ("angular_momentum", "gamma", "multipliers", "stability", "event", "cardan_angles",
                   "cardan_momenta", "cardan_drift", "trivial_deviation"):
        assert column in p, column
    first = np.flatnonzero(p["index"] == 0)
    stable = np.flatnonzero(e["stability"] == 0)
    assert len(stable) >= 1 and len(first) >= len(stable)
    for i in first:
        row = p["equilibrium"][i]
        omegas = frequencies(e["g1"][row], e["g2"][row])
        assert min(abs(p["period"][i] - 2 * math.pi / w) for w in omegas) < 1e-6
    assert (p["residual"] <= 1e-10).all()
    assert (p["l"] == 1.0).all()
    mu = p["multipliers"].reshape(-1, 6, 2)
    assert np.abs(mu[:, :4, 0] - 1).max() <= 1e-8 and np.abs(mu[:, :4, 1]).max() <= 1e-8
    assert (p["trivial_deviation"] <= 1e-8).all() and (p["product_deviation"] <= 1e-8).all()
    assert set(p["stability"].astype(str)) <= {"elliptic", "hyperbolic", "inverse_hyperbolic"}

    # Each row's point returns after one period under an independent integrator.
    for i in range(len(p["h"])):
        q0, p0 = p["cardan_angles"][i], p["cardan_momenta"][i]
        assert abs(q0[0]) < 1e-12 and abs(p0[0] - 1.0) < 1e-12
        assert abs(energy(q0, p0) - p["h"][i]) < 1e-10
        assert_returns_after_one_period(p, i)
        R = rz(q0[0]) @ rx(q0[1]) @ rz(q0[2])
        qdot = np.linalg.solve(mass_matrix(q0), p0)
        assert np.allclose(p["gamma"][i], R.T @ [0, 0, 1], atol=1e-14)
        assert np.allclose(p["angular_momentum"][i], J @ e_matrix(q0) @ qdot, atol=1e-12)

    # A seed from the last orbit, q1 anywhere (it is dropped), the period 1 % long, is found again.
    last = len(p["h"]) - 1
    seed = tmp_path / "seeds.txt"
    q0, p0 = p["cardan_angles"][last], p["cardan_momenta"][last]
    seed.write_text("# q1 q2 q3 p1 p2 p3 T\n" + " ".join(repr(float(v)) for v in
                    [0.7, q0[1], q0[2], p0[0], p0[1], p0[2], p["period"][last] * 1.01]) + "\n")
    lgi("periodic", "--scene", UP, "--l", "1", "--seed-file", str(seed), "--steps", "0", "--out",
        str(tmp_path / "s.h5"), "--quiet")
    s = columns(str(tmp_path / "s.h5"), "periodic")
    assert abs(s["period"][0] - p["period"][last]) < 1e-9 and abs(s["h"][0] - p["h"][last]) < 1e-12
    assert s["residual"][0] <= 1e-10 and abs(s["cardan_angles"][0][0]) < 1e-12
    lgi("periodic", "--scene", UP, "--l", "1", "--seed-file", str(seed), "--steps", "0", "--shooting-points", "3",
        "--out", str(tmp_path / "m.h5"), "--quiet")
    m = columns(str(tmp_path / "m.h5"), "periodic")
    assert abs(m["period"][0] - p["period"][last]) < 1e-9 and m["residual"][0] <= 1e-10
    assert abs(m["cardan_drift"][0] - p["cardan_drift"][last]) < 1e-8

    # Refusals: a seed off the level p1 = l; --from-critical.
    bad = tmp_path / "bad.txt"
    bad.write_text(" ".join(repr(float(v)) for v in [0, q0[1], q0[2], 1.5, p0[1], p0[2], 6.0]) + "\n")
    line = refused("periodic", "--scene", UP, "--l", "1", "--seed-file", str(bad), "--out", str(tmp_path / "b.h5"))
    assert "--seed-file" in line and "p1" in line
    line = refused("periodic", "--scene", UP, "--l", "1", "--from-critical", "1", "--out", str(tmp_path / "c.h5"))
    assert "--from-critical" in line


def test_tilted_cardan_top_refused(tmp_path):
    line = refused("periodic", "--scene", HORIZONTAL, "--l", "1", "--from-equilibria", "--out", str(tmp_path / "t.h5"))
    assert "suspension.tilt" in line and "cyclic" in line
    assert not os.path.exists(tmp_path / "t.h5")


def shape_velocity(q, p):
    return np.linalg.solve(mass_matrix(q), p)


def first_crossing(q0, p0, T):
    """The first crossing of dq2/dt = 0 after t = 0 of the orbit from (q0, p0), by DOP853 (its event
    located on the dense output): the state and its section point (x, y, piece) as lgi poincare writes it."""
    event = lambda _, x: shape_velocity(x[:3], x[3:])[1]
    s = solve_ivp(field, (1e-6, T), np.concatenate([q0, p0]), method="DOP853", rtol=1e-13, atol=1e-13, events=event)
    x = s.y_events[0][0]
    v = shape_velocity(x[:3], x[3:])
    return x, (x[2] % (2 * math.pi), x[1] % (2 * math.pi), 1 if v[2] >= 0 else -1)


def assert_orbits_meet_the_bar(p):
    """Residuals, the four trivial multipliers and the product, and the return under DOP853."""
    assert (p["residual"] <= 1e-10).all()
    mu = p["multipliers"].reshape(-1, 6, 2)
    assert np.abs(mu[:, :4, 0] - 1).max() <= 1e-8 and np.abs(mu[:, :4, 1]).max() <= 1e-8
    assert (p["trivial_deviation"] <= 1e-8).all() and (p["product_deviation"] <= 1e-8).all()
    for i in range(len(p["h"])):
        q0, p0 = p["cardan_angles"][i], p["cardan_momenta"][i]
        assert abs(q0[0]) < 1e-12 and abs(p0[0] - p["l"][i]) < 1e-12 and abs(energy(q0, p0) - p["h"][i]) < 1e-10
        assert_returns_after_one_period(p, i)


# A point of the l = 1 family of period ~5.745 at h = -0.6467 (lgi periodic --l 1 --from-equilibria
# --steps 1 --h-step 0.02, row 3).
ORBIT_Q = [0.0, -2.1105776366446233, 1.0512403313064836]
ORBIT_P = [1.0, 0.12341348, -0.34719336]


def test_seeds_from_a_cardan_section(tmp_path):
    """--seeds-from-poincare on a file of lgi poincare on the same Cardan top: the orbit through a
    point (x, y, piece) of its section is found again (its crossing computed here by DOP853), its
    section columns are that point, and each orbit meets the bar; files that do not fit are refused."""
    base = str(tmp_path / "b.h5")
    lgi("periodic", "--scene", UP, "--l", "1", "--from-equilibria", "--steps", "1", "--h-step", "0.02",
        "--out", base, "--quiet")
    b = columns(base, "periodic")
    i = 3
    x, pt = first_crossing(b["cardan_angles"][i], b["cardan_momenta"][i], b["period"][i])
    h = repr(float(b["h"][i]))
    sec = str(tmp_path / "s.h5")
    lgi("poincare", "--scene", UP, "--l", "1", "--h", h, "--ics", "2", "--t-end", "5", "--out", sec, "--quiet")
    point = "%r,%r,%d" % (float(pt[0]), float(pt[1]), pt[2])
    out = str(tmp_path / "o.h5")
    lgi("periodic", "--scene", UP, "--seeds-from-poincare", sec, "--poincare-point", point, "--steps", "1",
        "--out", out, "--quiet")
    s = columns(out, "periodic")
    assert len(s["h"]) == 2 and s["h"][0] == b["h"][i]
    assert abs(s["period"][0] - b["period"][i]) < 1e-8
    assert abs(s["section_phi"][0] - pt[0]) < 1e-7 and abs(s["section_theta"][0] - pt[1]) < 1e-7
    assert (s["section_sheet"] == pt[2]).all()
    for q, p in zip(s["cardan_angles"], s["cardan_momenta"]):  # on the sheet dq2/dt = 0
        assert abs(shape_velocity(q, p)[1]) < 1e-10
    assert_orbits_meet_the_bar(s)

    # A row of /events near the orbit's crossing (row 0 replaced here by it, q3 moved by 1e-6) finds it too.
    rows = str(tmp_path / "r.h5")
    shutil.copy(sec, rows)
    with h5py.File(rows, "r+") as f:
        f["events"]["cardan_angles"][0] = [0.0, x[1], x[2] + 1e-6]
        f["events"]["cardan_momenta"][0] = x[3:]
        f["events"]["piece"][0] = pt[2]
    lgi("periodic", "--scene", UP, "--seeds-from-poincare", rows, "--poincare-rows", "0", "--steps", "0",
        "--out", str(tmp_path / "ro.h5"), "--quiet")
    r = columns(str(tmp_path / "ro.h5"), "periodic")
    assert abs(r["period"][0] - s["period"][0]) < 1e-8 and abs(r["section_phi"][0] - s["section_phi"][0]) < 1e-7

    # Refusals: --l not the file's, a piece not of the section, a point off the level, a row off the
    # file's h, another top's file, a heavy top's file.
    o = str(tmp_path / "x.h5")
    assert "--l" in refused("periodic", "--scene", UP, "--l", "1.5", "--seeds-from-poincare", sec,
                            "--poincare-point", point, "--out", o)
    assert "--poincare-point" in refused("periodic", "--scene", UP, "--seeds-from-poincare", sec,
                                         "--poincare-point", "1,1,5", "--out", o)
    assert "--poincare-point" in refused("periodic", "--scene", UP, "--seeds-from-poincare", sec,
                                         "--poincare-point", "0,0.1,1", "--out", o)
    with h5py.File(rows, "r+") as f:
        f["events"]["cardan_momenta"][0] = x[3:] * 1.1
    assert "--poincare-rows" in refused("periodic", "--scene", UP, "--seeds-from-poincare", rows,
                                        "--poincare-rows", "0", "--out", o)
    other = tmp_path / "other.toml"
    other.write_text(open(UP).read().replace("outer_inertia = 0.3", "outer_inertia = 0.31"))
    lgi("poincare", "--scene", str(other), "--l", "1", "--h", h, "--ics", "1", "--t-end", "1", "--out",
        str(tmp_path / "os.h5"), "--quiet")
    line = refused("periodic", "--scene", UP, "--seeds-from-poincare", str(tmp_path / "os.h5"),
                   "--poincare-point", point, "--out", o)
    assert "--seeds-from-poincare" in line and "another top" in line
    lgi("poincare", "--scene", os.path.join(SCENES, "general_top_richter.toml"), "--l", "1", "--h", "2",
        "--ics", "1", "--t-end", "1", "--out", str(tmp_path / "hs.h5"), "--quiet")
    line = refused("periodic", "--scene", UP, "--seeds-from-poincare", str(tmp_path / "hs.h5"),
                   "--poincare-rows", "0", "--out", o)
    assert "--seeds-from-poincare" in line and "heavy top" in line
    assert not os.path.exists(o)


def test_cardan_continuation_in_l(tmp_path):
    """--continue-in l on a Cardan top: p1 = l varies along each family at fixed h, every orbit meets
    the bar (residual, multipliers, return under DOP853)."""
    out = str(tmp_path / "l.h5")
    seed = tmp_path / "seed.txt"
    seed.write_text(" ".join(repr(float(v)) for v in [*ORBIT_Q, *ORBIT_P, 5.745]) + "\n")
    lgi("periodic", "--scene", UP, "--l", "1", "--seed-file", str(seed), "--continue-in", "l", "--l-step", "0.02",
        "--steps", "2", "--out", out, "--quiet")
    p = columns(out, "periodic")
    assert len(p["h"]) == 3 and np.ptp(p["h"]) == 0.0
    assert p["l"][0] == 1.0 and (np.diff(p["l"]) > 0.005).all()
    assert_orbits_meet_the_bar(p)


def section_state(x, y, piece, l, h):
    """The state over a point (x, y, piece = +-1) of the section at (l, h), written out here: q = (0, y, x),
    qdot2 = 0, qdot1 from p1 = l, qdot3 (of the piece's sign) from H = h (docs/cardan.md section 9.5)."""
    q = np.array([0.0, y, x])
    M, V = mass_matrix(q), energy(q, np.zeros(3))
    a, b = np.array([l / M[0, 0], 0, 0]), np.array([-M[0, 2] / M[0, 0], 0, 1.0])  # qdot = a + b qdot3
    c2, c1, c0 = 0.5 * b @ M @ b, a @ M @ b, 0.5 * a @ M @ a + V - h
    u = (-c1 + piece * math.sqrt(c1 * c1 - 4 * c2 * c0)) / (2 * c2)
    return np.concatenate([q, M @ (a + b * u)])


def nth_crossing(x, n, t_max):
    """The n-th crossing (n >= 1) of either factor of the section (dq2/dt, sin q2) after t = 0 (before it if
    t_max < 0) of the orbit from x, by DOP853: (t, state)."""
    factors = [lambda _, z: shape_velocity(z[:3], z[3:])[1], lambda _, z: math.sin(z[1])]
    s = solve_ivp(field, (0, t_max), x, method="DOP853", rtol=1e-12, atol=1e-12, events=factors)
    c = sorted(((t, y) for k in (0, 1) for t, y in zip(s.t_events[k], s.y_events[k]) if abs(t) > 1e-9),
               key=lambda r: abs(r[0]))
    return c[n - 1]


def torus_xy(z):
    """(x, y) = (q3, q2) mod 2 pi of a state on a torus piece."""
    return np.array([z[2] % (2 * math.pi), z[1] % (2 * math.pi)])


# An inverse hyperbolic orbit: lgi periodic --l 1 --from-equilibria --steps 25 --h-step 0.05, family 2 (the
# period-5.76 mode of equilibrium 0) past its period doubling at h = -0.1037, row 8 (T = 6.4536, tr P = -3.906):
# its crossing of dq2/dt = 0 at t = 3.121 by DOP853, (x, y, piece), and its h.
HYPERBOLIC_H = -0.005340203719125776
HYPERBOLIC_POINT = (0.9341797680757195, 4.766096729250444, -1)


def test_manifolds_of_an_inverse_hyperbolic_cardan_orbit(tmp_path):
    """--manifolds on a Cardan section (experiments/PERIODIC.md, "Cardan tops", "Manifolds"), checked against
    the return map F (the m-th return, m = `returns`) computed here with DOP853 from the section's points:
    F(x0) = x0; the eigenvalues of DF (central differences in (x, y)) are lgi's lambda and 1/lambda; each
    branch's domain leaves x0 along DF's eigenvector; every point lies on H = h, p1 = l and dq2/dt = 0; and
    points started here on DF's eigenvectors between the domain's points, mapped by F^2 (F^-2 for the stable
    branch; F swaps the sides of an inverse hyperbolic orbit), land on lgi's polyline of the domain's F^2
    images (F^-2): the manifolds are invariant and the right ones."""
    sec, out = str(tmp_path / "s.h5"), str(tmp_path / "m.h5")
    lgi("poincare", "--scene", UP, "--l", "1", "--h", repr(HYPERBOLIC_H), "--ics", "1", "--t-end", "1", "--out", sec,
        "--quiet")
    lgi("periodic", "--scene", UP, "--seeds-from-poincare", sec, "--poincare-point", "%r,%r,%d" % HYPERBOLIC_POINT,
        "--steps", "0", "--manifolds", "6", "--manifold-periods", "2.5", "--out", out, "--quiet")
    p, m = columns(out, "periodic"), columns(out, "manifolds")
    assert p["stability"][0].decode() == "inverse_hyperbolic" and len(p["h"]) == 1
    assert_orbits_meet_the_bar(p)
    h, T, lam, m_ret = p["h"][0], p["period"][0], m["multiplier"][0], m["returns"][0]
    assert lam < -1 and (m["multiplier"] == lam).all() and (m["returns"] == m_ret).all() and m_ret == 2
    mu = p["multipliers"][0].reshape(6, 2)[4:, 0]
    assert abs(lam - mu[np.argmax(abs(mu))]) < 1e-12 * abs(lam)
    x0 = np.array([p["section_phi"][0], p["section_theta"][0]])
    piece = int(p["section_sheet"][0])
    assert np.abs(x0 - HYPERBOLIC_POINT[:2]).max() < 1e-6 and piece == HYPERBOLIC_POINT[2]

    def F(xy, n=m_ret, t_max=1.2 * T):
        return torus_xy(nth_crossing(section_state(*xy, piece, 1.0, h), n, t_max)[1])

    assert np.abs(F(x0) - x0).max() < 1e-9
    d = 1e-6
    DF = np.array([(F(x0 + d * e) - F(x0 - d * e)) / (2 * d) for e in np.eye(2)]).T
    w, V = np.linalg.eig(DF)
    assert np.abs(w.imag).max() == 0.0
    w, V = w.real, V.real
    u, s = np.argmax(abs(w)), np.argmin(abs(w))
    assert abs(w[u] - lam) < 1e-7 * abs(lam) and abs(w[s] * lam - 1) < 1e-7

    # Every point on the level and on the section's sheet dq2/dt = 0 (the orbit stays off q2 = 0, pi here).
    for q, pp in zip(m["cardan_angles"], m["cardan_momenta"]):
        assert abs(energy(q, pp) - h) < 1e-9 and pp[0] == 1.0 and q[0] == 0.0
        assert abs(shape_velocity(q, pp)[1]) < 1e-10
    assert set(m["sheet"]) == {1, -1}

    branch = m["branch"].astype(str)
    xy = np.stack([m["phi"], m["theta"]], axis=1)
    for name, v, sense in (("unstable", V[:, u], 1), ("stable", V[:, s], -1)):
        for side in (1, -1):
            rows = (branch == name) & (m["side"] == side)
            domain, images = xy[rows & (m["crossing"] == 0)] - x0, xy[rows & (m["crossing"] == 2 * m_ret)]
            assert len(domain) == 6 and len(images) == 6
            # The domain leaves x0 along DF's eigenvector, to O(s): measured angles 8e-6 ... 1.1e-4 at
            # |off| = 3.7e-5 ... 3.6e-4 (at most 0.32 |off|); the two eigenvectors are 0.87 (sine) apart.
            for off in domain:
                assert abs(np.cross(off / np.linalg.norm(off), v)) < 0.5 * np.linalg.norm(off)
            # A point between domain points 2 and 3 on the eigenvector, mapped by F^2 along the branch,
            # lies on the segment of lgi's images of points 2 and 3 (measured: 4.3e-8 and 7.2e-8 off
            # segments of 6.1e-4 and 7.1e-4, at t = 0.446; the chord's sag), not merely near it.
            r = math.sqrt(np.linalg.norm(domain[2]) * np.linalg.norm(domain[3]))
            z = F(x0 + r * np.sign(v @ domain[2]) * v, 2 * m_ret, sense * 2.2 * T)
            a, b = images[2], images[3]
            t = (z - a) @ (b - a) / ((b - a) @ (b - a))
            assert 0.2 < t < 0.8 and np.linalg.norm(a + t * (b - a) - z) < 1e-3 * np.linalg.norm(b - a)


def test_a_seed_that_collapses_to_zero_period_is_no_orbit(tmp_path):
    """Newton from the section point (0.75, 4.8) of piece 1 at h = -0.5117 (l = 1) goes to the trivial
    solution of phi_T(x0) = x0, T -> 0 (found as a period of 2.3e-16 with all multipliers 1, once
    listed as an elliptic orbit). A period of at most one step is no orbit: the seed is reported as
    failed, with that reason, and nothing of it is written; a seed of a true orbit beside it still is."""
    section, out = str(tmp_path / "s.h5"), str(tmp_path / "p.h5")
    lgi("poincare", "--scene", UP, "--l", "1", "--h", "-0.5116918184608042", "--ics", "1", "--t-end", "1",
        "--out", section, "--quiet")
    r = lgi("periodic", "--scene", UP, "--seeds-from-poincare", section, "--poincare-point", "0.75,4.8,1",
            "--poincare-point", "1.0307348182774148,3.9087648709016305,1", "--steps", "0", "--out", out, "--quiet")
    assert "Newton went to the trivial solution T = 0" in r.stderr, r.stderr
    p = columns(out, "periodic")
    assert len(p["period"]) == 1 and abs(p["period"][0] - 5.672563603501278) < 1e-8
    assert_orbits_meet_the_bar(p)
