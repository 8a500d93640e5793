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


def crossings(x0, T, J, w, e, richter, directions=False):
    """[(phi, theta, sheet)] of the orbit through x0 of period T, one per crossing in (0, T] (the one at T is the one at 0);
    with directions, (that list, [the sign of dS/dt at each])."""
    from scipy.integrate import solve_ivp
    J_inv = np.linalg.inv(J)

    def f(_, x):
        Pi, G = x[:3], x[3:]
        Om = J_inv @ Pi
        return np.concatenate([np.cross(Pi, Om) + np.cross(G, w), np.cross(G, Om)])

    def s(_, x):
        return np.cross(x[3:], J_inv @ x[:3]) @ e if richter else x[3:] @ e

    # A little past T: an orbit whose point lies on the section (lgi periodic --seeds-from-poincare)
    # crosses it at 0 and T, where the root finder may see neither end; the one near T is kept for both.
    sol = solve_ivp(f, (0.0, T * (1 + 1e-4)), x0, method="DOP853", rtol=1e-11, atol=1e-12, events=s,
                    dense_output=False)
    ts, xs = sol.t_events[0], sol.y_events[0]
    keep = (ts > T * 1e-6) & (ts <= T * (1 + 1e-6))
    points = [coordinates(x, J_inv, e, richter) for x in xs[keep]]
    if not directions:
        return points
    step = 1e-7  # dS/dt by a central difference along the field
    return points, [1 if s(0, x + step * f(0, x)) > s(0, x - step * f(0, x)) else -1 for x in xs[keep]]


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
