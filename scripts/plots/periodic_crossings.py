"""The crossings of periodic orbits (a file of `lgi periodic`, experiments/PERIODIC.md)
with the section of a file of `lgi poincare` (experiments/POINCARE.md), for
poincare.py --periodic.

Each orbit is integrated for one period from its point by scipy's DOP853
(rtol 1e-11) on the Euler–Poisson equations Π̇ = Π × Ω + Γ × mgχ,
Γ̇ = Γ × Ω, Ω = J⁻¹Π (the body from the periodic file's scene), and its
crossings of the section are located by solve_ivp's event root finder on the
section function of docs/atlas.md §6: S = (Γ × Ω)·e (Richter's section) or
Γ·e (--section gamma), both directions. Their coordinates are those of
experiments/analysis/poincare_section.cpp: φ the azimuth of Γ about e in the
frame (f1, f2, e); ϑ the angle of Γ from e and the sheet the sign of
e·(Γ × Γ̇) (Richter's), or ϑ the angle of Π from e and the sheet the sign of
d(Γ·e)/dt (gamma).

A Cardan top's orbit (docs/cardan.md; its point (q, p) the /periodic columns
cardan_angles, cardan_momenta) is integrated the same way on the canonical
field of docs/cardan.md eq. (7), q̇ = M(q)⁻¹p, ṗ = −∂H/∂q (the derivatives of
M and V by complex steps), and its crossings are those of either factor of
S = −sin q2 · q̇2 (docs/cardan.md §9.2), with the coordinates (x, y, piece)
of experiments/analysis/cardan_section.cpp.
"""
import tomllib

import numpy as np

import lgi_plot_common as c


def body_of(scene_toml):
    """(J, m g chi) of a heavy top from its scene text."""
    scene = tomllib.loads(scene_toml)
    J = c.inertia_of(scene)
    g = scene.get("gravity", {}).get("g", 9.81) if "gravity" in scene else 0.0
    b = scene.get("body", {})
    return J, float(b.get("mass", 0.0)) * g * np.asarray(b.get("center_of_mass", [0, 0, 0]), dtype=float)


def section_frame(e):
    """f1, f2 of analysis/poincare_section.cpp: f1 the body axis least aligned with e, made orthogonal."""
    k = int(np.argmin(np.abs(e)))
    f1 = np.eye(3)[k] - e[k] * e
    f1 /= np.linalg.norm(f1)
    return f1, np.cross(e, f1)


def coordinates(x, J_inv, e, richter):
    """(phi, theta, sheet) of a state x = (Pi, Gamma) on the section."""
    Pi, G = x[:3], x[3:]
    Om = J_inv @ Pi
    f1, f2 = section_frame(e)
    phi = np.arctan2(G @ f2, G @ f1) % (2 * np.pi)
    if richter:
        theta = np.arccos(np.clip(G @ e / np.linalg.norm(G), -1.0, 1.0))
        sheet = -1 if (G @ e) * (G @ Om) - Om @ e < 0 else 1
    else:
        n = np.linalg.norm(Pi)
        theta = np.arccos(np.clip(Pi @ e / n, -1.0, 1.0)) if n > 0 else 0.0
        sheet = -1 if np.cross(G, Om) @ e < 0 else 1
    return phi, theta, sheet


def section_hits(f, events, x0, T):
    """[(t, x, k)] in time order: the crossings in (0, T] of the orbit of x' = f(t, x) through x0 with the
    zero sets of the functions events[k] (both directions), by DOP853 (rtol 1e-11) and solve_ivp's event
    root finder; the one at T is the one at 0."""
    from scipy.integrate import solve_ivp
    # A little past T: an orbit whose point lies on the section (lgi periodic --seeds-from-poincare)
    # crosses it at 0 and T, where the root finder may see neither end; the one near T is kept for both.
    sol = solve_ivp(f, (0.0, T * (1 + 1e-4)), x0, method="DOP853", rtol=1e-11, atol=1e-12, events=list(events),
                    dense_output=False)
    hits = [(t, x, k) for k in range(len(events)) for t, x in zip(sol.t_events[k], sol.y_events[k])
            if T * 1e-6 < t <= T * (1 + 1e-6)]
    return sorted(hits, key=lambda hit: hit[0])


def crossings(x0, T, J, w, e, richter, directions=False):
    """[(phi, theta, sheet)] of the orbit through x0 of period T, one per crossing in (0, T] (the one at T is the one at 0);
    with directions, (that list, [the sign of dS/dt at each])."""
    J_inv = np.linalg.inv(J)

    def f(_, x):
        Pi, G = x[:3], x[3:]
        Om = J_inv @ Pi
        return np.concatenate([np.cross(Pi, Om) + np.cross(G, w), np.cross(G, Om)])

    def s(_, x):
        return np.cross(x[3:], J_inv @ x[:3]) @ e if richter else x[3:] @ e

    xs = [x for _, x, _ in section_hits(f, [s], x0, T)]
    points = [coordinates(x, J_inv, e, richter) for x in xs]
    if not directions:
        return points
    step = 1e-7  # dS/dt by a central difference along the field
    return points, [1 if s(0, x + step * f(0, x)) > s(0, x - step * f(0, x)) else -1 for x in xs]


def orbits_at(table, l, h, h_tol):
    """Row positions of table (a /periodic table) at l and within h_tol of h: of each family
    the row nearest h, event rows (bifurcation points) left out."""
    out = []
    near_l = np.abs(table["l"] - l) <= 1e-9 * max(1.0, abs(l))
    for fam in np.unique(table["family"]):
        sel = np.flatnonzero(near_l & (table["family"] == fam) & (table["event"] == "none")
                             & (np.abs(table["h"] - h) <= h_tol))
        if len(sel):
            out.append(int(sel[np.argmin(np.abs(table["h"][sel] - h))]))
    return out


# ── Cardan tops (docs/cardan.md) ─────────────────────────────────────────────
def cardan_of(scene_toml):
    """The parameters of a Cardan top (docs/cardan.md §3, §6) from its scene text, as one flat float array
    (J 9, m chi 3, g, tilt, C_o, (A_i, B_i, C_i), m_o c_o 3, m_i c_i 3): two files hold the same mechanism
    when these agree; None for a scene without [suspension] (a heavy top)."""
    scene = tomllib.loads(scene_toml)
    if "suspension" not in scene:
        return None
    s = scene["suspension"]
    J, b = c.inertia_of(scene), scene["body"]
    g = scene.get("gravity", {}).get("g", 9.81) if "gravity" in scene else 0.0
    m_chi = float(b.get("mass", 0.0)) * np.asarray(b["center_of_mass"], dtype=float)
    ring = [float(s.get(f"{k}_mass", 0.0)) * np.asarray(s.get(f"{k}_center", [0, 0, 0]), dtype=float)
            for k in ("outer", "inner")]
    return np.concatenate([np.asarray(J, dtype=float).ravel(), m_chi, [g, float(s["tilt"]), float(s["outer_inertia"])],
                           np.asarray(s["inner_inertia"], dtype=float), ring[0], ring[1]])


def _rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0 * a], [s, c, 0 * a], [0 * a, 0 * a, 1 + 0 * a]])


def _rx(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[1 + 0 * a, 0 * a, 0 * a], [0 * a, c, -s], [0 * a, s, c]])


def cardan_mass_matrix(top, q):
    """M(q) = Eᵀ J E + Fᵀ K F + C_o e1 e1ᵀ (docs/cardan.md eqs. (2)-(4)); q may be complex (complex steps)."""
    J, C_o, K = top[:9].reshape(3, 3), top[14], np.diag(top[15:18])
    s2, c2, s3, c3, z = np.sin(q[1]), np.cos(q[1]), np.sin(q[2]), np.cos(q[2]), 0 * q[1]
    E = np.array([[s2 * s3, c3, z], [s2 * c3, -s3, z], [c2, z, z + 1]])
    F = np.array([[z, z + 1, z], [s2, z, z], [c2, z, z]])
    M = E.T @ J @ E + F.T @ K @ F
    M[0, 0] = M[0, 0] + C_o
    return M


def cardan_potential(top, q):
    """V(q) = g γ·(Rz(q1)[Rx(q2)(Rz(q3) m χ + m_i c_i) + m_o c_o]), γ = (−sin α, 0, cos α) (docs/cardan.md eq. (5))."""
    m_chi, g, tilt, mo_co, mi_ci = top[9:12], top[12], top[13], top[18:21], top[21:24]
    gamma = np.array([-np.sin(tilt), 0.0, np.cos(tilt)])
    return g * gamma @ (_rz(q[0]) @ (_rx(q[1]) @ (_rz(q[2]) @ m_chi + mi_ci) + mo_co))


def cardan_field(top):
    """f(t, x) of x = (q, p): q̇ = M⁻¹p, ṗ_k = ½ q̇ᵀ (∂M/∂q_k) q̇ − ∂V/∂q_k (docs/cardan.md eq. (7)), the
    derivatives by complex steps (exact to round-off)."""
    step = 1e-30

    def f(_, x):
        q, p = x[:3], x[3:]
        v = np.linalg.solve(cardan_mass_matrix(top, q), p)
        pdot = np.empty(3)
        for k in range(3):
            qc = q + 1j * step * np.eye(3)[k]
            dM = cardan_mass_matrix(top, qc).imag / step
            pdot[k] = 0.5 * v @ dM @ v - cardan_potential(top, qc).imag / step
        return np.concatenate([v, pdot])
    return f


def cardan_section_point(top, x, factor):
    """(x, y, piece) of a state on the Cardan section (experiments/analysis/cardan_section.cpp,
    docs/cardan.md §9.2): factor 0 (q̇2 = 0) on the torus copies ±1 (the sign of q̇3), (q3, q2);
    factor 1 (sin q2 = 0) on the cylinders 2 (q2 = 0), 3 (q2 = π), (q3, ψ = atan2(q̇3, q̇2))."""
    q = x[:3]
    v = np.linalg.solve(cardan_mass_matrix(top, q), x[3:])
    if factor == 0:
        return q[2] % (2 * np.pi), q[1] % (2 * np.pi), 1 if v[2] >= 0 else -1
    return q[2] % (2 * np.pi), float(np.arctan2(v[2], v[1])), 2 if np.cos(q[1]) > 0 else 3


def cardan_crossings(top, q0, p0, T):
    """[(x, y, piece)] of the Cardan top's orbit through (q0, p0) of period T, one per crossing in (0, T] of
    either factor of S = −sin q2 · q̇2 (docs/cardan.md §9.2, as lgi poincare tracks them)."""
    f = cardan_field(top)

    def qdot2(_, x):
        return np.linalg.solve(cardan_mass_matrix(top, x[:3]), x[3:])[1]

    def sin_q2(_, x):
        return np.sin(x[1])

    hits = section_hits(f, [qdot2, sin_q2], np.concatenate([q0, p0]).astype(float), T)
    return [cardan_section_point(top, x, k) for _, x, k in hits]
