"""Shared helpers of the plot scripts in scripts/plots (Debian's /usr/bin/python3:
python3-matplotlib, python3-h5py, python3-numpy; no network, no other package).

Readers for the files lgi writes (experiments/OUTPUT.md: H5MD trajectories;
experiments/RESULTS.md: result tables), the attitude helpers of
shared/spec/conventions.md (quaternion (w, x, y, z), body -> space; Euler ZXZ),
one colour and marker per scheme across every figure, and save() that writes
PDF and PNG side by side.
"""
import argparse
import hashlib
import os
import sys
import tomllib

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

# ── style ────────────────────────────────────────────────────────────────────
plt.rcParams.update({
    "font.size": 8.5,
    "axes.titlesize": 9,
    "axes.labelsize": 8.5,
    "legend.fontsize": 7,
    "xtick.labelsize": 7.5,
    "ytick.labelsize": 7.5,
    "lines.linewidth": 1.1,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "grid.linewidth": 0.5,
    "savefig.bbox": "tight",
    "savefig.pad_inches": 0.03,
    "pdf.fonttype": 42,
})

# Families get a colour map, members a shade; unknown names a stable hash.
_FAMILY_ORDER = [
    ("exact", ["exact"]),
    ("rkmk", ["lie-euler", "rkmk2", "rkmk3", "rkmk4", "rkmk-dp54"]),
    ("cg", ["cg3", "cg4a", "cf4"]),
    ("dmv", ["dmv", "lgvi", "dmv-pre4", "dmv-pre6", "dmv-pre8", "dmv-pre10"]),
    ("em", ["simo-wong", "split-exact"]),
    ("implicit", ["rkmk-gauss2", "rkmk-gauss4", "rkmk-radau5", "lie-genalpha"]),
]
_PALETTE = plt.get_cmap("tab20").colors + plt.get_cmap("tab20b").colors
_MARKERS = ["o", "s", "^", "v", "D", "P", "X", "<", ">", "h", "*", "p", "d", "8"]


def _stable_index(name, n):
    return int(hashlib.sha1(name.encode()).hexdigest(), 16) % n


def scheme_style(name):
    """Colour, marker and line style of a scheme, the same in every figure."""
    known = [s for _, members in _FAMILY_ORDER for s in members]
    if name in known:
        i = known.index(name)
        color = _PALETTE[(2 * i) % len(_PALETTE)] if i < 10 else _PALETTE[(2 * (i - 10) + 1) % len(_PALETTE)]
        marker = _MARKERS[i % len(_MARKERS)]
    else:
        i = _stable_index(name, len(_PALETTE))
        color = _PALETTE[i]
        marker = _MARKERS[_stable_index(name + "m", len(_MARKERS))]
    if "/" in name:            # Boost.Odeint baselines: dashed
        ls = "--"
    elif "@" in name:          # compositions: dash-dot
        ls = "-."
    else:
        ls = "-"
    return {"color": color, "marker": marker, "linestyle": ls}


def save(fig, outdir, name, png_dpi=160):
    """Write outdir/name.pdf and outdir/name.png; return the two paths."""
    os.makedirs(outdir, exist_ok=True)
    paths = [os.path.join(outdir, name + ".pdf"), os.path.join(outdir, name + ".png")]
    fig.savefig(paths[0])
    fig.savefig(paths[1], dpi=png_dpi)
    plt.close(fig)
    print(f"wrote {paths[0]} and .png", file=sys.stderr)
    return paths


def parser(description):
    p = argparse.ArgumentParser(description=description)
    p.add_argument("files", nargs="*", help="HDF5 files written by lgi")
    p.add_argument("--out", required=True, help="output folder for the PDF and PNG files")
    return p


def die(msg):
    print(f"{os.path.basename(sys.argv[0])}: {msg}", file=sys.stderr)
    sys.exit(1)


# ── readers ──────────────────────────────────────────────────────────────────
def _attr(v):
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray) and v.shape == ():
        return v.item()
    return v


def attrs(group):
    return {k: _attr(v) for k, v in group.attrs.items()}


def load_trajectory(path):
    """An lgi simulate trajectory (experiments/OUTPUT.md) as a dict of arrays."""
    with h5py.File(path, "r") as f:
        body = f["particles/body"]
        d = {
            "path": path,
            "t": body["orientation/time"][:],
            "q": body["orientation/value"][:, 0, :],
            "Pi": body["angular_momentum_body/value"][:, 0, :],
            "Omega": body["angular_velocity_body/value"][:, 0, :],
            "observables": {k: f["observables"][k]["value"][:] for k in f["observables"]},
            "parameters": attrs(f["parameters"]),
            "diagnostics": attrs(f["diagnostics"]),
        }
        d["euler_zxz"] = body["euler_zxz/value"][:, 0, :] if "euler_zxz" in body else None
    d["energy"] = d["observables"].get("energy")
    d["scene"] = tomllib.loads(d["parameters"].get("scene_toml", "")) if d["parameters"].get("scene_toml") else {}
    d["scheme"] = d["parameters"].get("scheme", "?")
    return d


def load_table(path, group="results"):
    """A result table (experiments/RESULTS.md): column name -> 1-D array; str columns as lists of str."""
    out = {}
    with h5py.File(path, "r") as f:
        if group not in f:
            return None
        g = f[group]
        for k in g:
            v = g[k][:]
            if v.dtype.kind in "OS":
                v = np.array([x.decode() if isinstance(x, bytes) else str(x) for x in v], dtype=object)
            out[k] = v
    return out


def load_attrs(path, group):
    with h5py.File(path, "r") as f:
        return attrs(f[group]) if group in f else {}


def scene_label(params_or_path):
    """A short scene name from a scene file path."""
    s = params_or_path if isinstance(params_or_path, str) else params_or_path.get("scene_file", "?")
    return os.path.splitext(os.path.basename(s))[0]


# ── attitude (conventions.md) ────────────────────────────────────────────────
def quat_to_matrix(q):
    """(n, 4) unit quaternions (w, x, y, z), body -> space, to (n, 3, 3) matrices."""
    q = np.asarray(q, dtype=float)
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    w, x, y, z = q[..., 0], q[..., 1], q[..., 2], q[..., 3]
    R = np.empty(q.shape[:-1] + (3, 3))
    R[..., 0, 0] = 1 - 2 * (y * y + z * z)
    R[..., 0, 1] = 2 * (x * y - w * z)
    R[..., 0, 2] = 2 * (x * z + w * y)
    R[..., 1, 0] = 2 * (x * y + w * z)
    R[..., 1, 1] = 1 - 2 * (x * x + z * z)
    R[..., 1, 2] = 2 * (y * z - w * x)
    R[..., 2, 0] = 2 * (x * z - w * y)
    R[..., 2, 1] = 2 * (y * z + w * x)
    R[..., 2, 2] = 1 - 2 * (x * x + y * y)
    return R


def euler_zxz_from_matrix(R):
    """(psi, theta, phi) of R = Rz(psi) Rx(theta) Rz(phi), each wrapped to (-pi, pi]
    (theta in [0, pi]); Trindade & Sampaio eq. (13)."""
    theta = np.arctan2(np.hypot(R[..., 2, 0], R[..., 2, 1]), R[..., 2, 2])
    phi = np.arctan2(R[..., 2, 0], R[..., 2, 1])
    psi = np.arctan2(R[..., 0, 2], -R[..., 1, 2])
    return psi, theta, phi


def continuous_quaternion(q):
    """q and −q are one attitude (conventions.md); a file may switch between them
    (e.g. a matrix-to-quaternion conversion that keeps w ≥ 0). Flip signs so that
    consecutive samples are the closer of ±q: the curve is then as smooth as the motion."""
    q = np.array(q, dtype=float, copy=True)
    for k in range(1, len(q)):
        if np.dot(q[k], q[k - 1]) < 0:
            q[k] = -q[k]
    return q


def attitude_distance(qa, qb):
    """Geodesic angle between attitudes, 2 atan2(|vec(qa* qb)|, |w(qa* qb)|)."""
    w = np.sum(qa * qb, axis=-1)
    v = qa[..., :1] * qb[..., 1:] - qb[..., :1] * qa[..., 1:] - np.cross(qa[..., 1:], qb[..., 1:])
    return 2.0 * np.arctan2(np.linalg.norm(v, axis=-1), np.abs(w))


def inertia_of(scene):
    """Principal (diagonal) inertia about the reference point from a parsed scene:
    [body] inertia, or inertia_cm + parallel axis with mass and center_of_mass."""
    body = scene.get("body", {})
    if "inertia" in body:
        J = np.asarray(body["inertia"], dtype=float)
        return np.diag(J) if J.ndim == 1 else J
    Jc = np.asarray(body["inertia_cm"], dtype=float)
    Jc = np.diag(Jc) if Jc.ndim == 1 else Jc
    chi = np.asarray(body.get("center_of_mass", [0, 0, 0]), dtype=float)
    m = float(body.get("mass", 0.0))
    return Jc + m * (chi @ chi * np.eye(3) - np.outer(chi, chi))
