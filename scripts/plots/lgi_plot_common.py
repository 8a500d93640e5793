"""Shared helpers of the plot scripts in scripts/plots (Debian's /usr/bin/python3:
python3-matplotlib, python3-h5py, python3-numpy; no network, no other package).

Readers for the files lgi writes (experiments/OUTPUT.md: H5MD trajectories;
experiments/RESULTS.md: result tables), the attitude helpers of
docs/conventions.md (quaternion (w, x, y, z), body -> space; Euler ZXZ),
one colour and marker per scheme across every figure (the line style from the
scheme's facts, never its name: use_scheme_facts), and save() that writes
PDF and PNG side by side. Every script takes --out DIR (created when missing:
out_dir), never writes one file twice in a run (claim, unique_names), and gets
at least three labelled ticks on each log axis (fix_log_ticks, called by save).
"""
import argparse
import hashlib
import json
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
    kind = scheme_fact(name, "kind")
    ls = {"baseline": "--", "composition": "-."}.get(kind, "-")  # Boost.Odeint baselines dashed, compositions dash-dot
    return {"color": color, "marker": marker, "linestyle": ls}


# ── scheme facts: read from `lgi schemes --json`, never parsed from a name ───
# The result files store scheme names only (experiments/RESULTS.md); what a
# scheme is ("kind": lie-group, composition, baseline, exact; "base": a
# composition's base scheme; "family") comes from the registry's records, as
# `lgi schemes --json` writes them (scripts/build_paper.sh: generated/schemes.json).
_FACTS = {}


def use_scheme_facts(records):
    """Make these `lgi schemes --json` records (a list of dicts, or the path of
    such a file) the facts scheme_style and scheme_fact read; returns them by name."""
    if isinstance(records, (str, os.PathLike)):
        try:
            with open(records) as f:
                records = json.load(f)
        except (OSError, ValueError) as e:
            raise argparse.ArgumentTypeError(f"cannot read scheme facts from {records}: {e}")
    _FACTS.clear()
    _FACTS.update({r["name"]: r for r in records})
    return dict(_FACTS)


def scheme_fact(name, key, default=None):
    """One fact of a scheme ("kind", "base", "family", ...); `default` for a
    scheme without facts (no --schemes-json given, or a name lgi does not know)."""
    return _FACTS.get(name, {}).get(key, default)


# ── output folder, file names, log-axis ticks ────────────────────────────────
_WRITTEN = set()


def out_dir(path):
    """The --out folder, created with its parents when missing (an argparse type)."""
    try:
        os.makedirs(path, exist_ok=True)
    except OSError as e:
        raise argparse.ArgumentTypeError(f"cannot create output folder {path}: {e.strerror}")
    if not os.path.isdir(path):
        raise argparse.ArgumentTypeError(f"{path} exists and is not a folder")
    return path


def claim(path):
    """Register an output path of this run; a second write to it (two inputs mapped to
    one file name) stops the script instead of silently replacing the first file."""
    key = os.path.realpath(path)
    if key in _WRITTEN:
        die(f"{path} would be written twice in one run (two inputs give the same name); nothing overwritten")
    _WRITTEN.add(key)
    return path


def file_stem(path):
    """An input file's name without folder and .h5/.hdf5 suffix."""
    base = os.path.basename(path)
    for suffix in (".h5", ".hdf5"):
        if base.endswith(suffix):
            return base[: -len(suffix)]
    return os.path.splitext(base)[0]


def unique_names(names, paths):
    """One output name per input: names[i] where it is unique among the inputs, else
    names[i] + "_" + the stem of paths[i] (and a counter if the stems agree too)."""
    out = [n if names.count(n) == 1 else f"{n}_{file_stem(p)}" for n, p in zip(names, paths)]
    clash = {n for n in out if out.count(n) > 1}
    seen = {}
    for i, n in enumerate(out):
        if n in clash:
            seen[n] = seen.get(n, 0) + 1
            out[i] = f"{n}_{seen[n]}"
    return out


def _ticks_in_view(locs, lo, hi):
    return [v for v in locs if lo * (1 - 1e-9) <= v <= hi * (1 + 1e-9)]


def fix_log_ticks(ax, min_labels=3):
    """Give every log-scaled axis of ax at least min_labels labelled major ticks in view:
    decades where the range holds enough of them, else 1-2-5 or 1..9 mantissas (labelled
    as m×10^k), else a few geometric ticks. Minor labels are switched off, so labels never
    collide; the limits are kept."""
    from matplotlib import ticker
    for axis, get_lim, set_lim, scale in ((ax.xaxis, ax.get_xlim, ax.set_xlim, ax.get_xscale()),
                                         (ax.yaxis, ax.get_ylim, ax.set_ylim, ax.get_yscale())):
        if scale != "log":
            continue
        lim = get_lim()
        lo, hi = sorted(lim)
        if not (lo > 0 and np.isfinite(lo) and np.isfinite(hi)):
            continue
        set_lim(lim)  # freeze: changing the locator must not move the limits
        k0, k1 = int(np.floor(np.log10(lo))) - 1, int(np.ceil(np.log10(hi))) + 1
        decades = 10.0 ** np.arange(k0, k1 + 1)
        chosen = None
        for subs in ((1.0,), (1.0, 3.0), (1.0, 2.0, 5.0), tuple(range(1, 10))):
            locs = np.outer(decades, subs).ravel()
            if len(_ticks_in_view(locs, lo, hi)) >= min_labels:
                chosen = subs
                break
        if chosen == (1.0,):
            axis.set_major_locator(ticker.LogLocator(base=10, numticks=12))
            axis.set_major_formatter(ticker.LogFormatterSciNotation())
        elif chosen is not None:
            axis.set_major_locator(ticker.LogLocator(base=10, subs=chosen, numticks=40))
            # minor_thresholds (inf, inf): label every tick of the locator, whatever the range
            axis.set_major_formatter(ticker.LogFormatterSciNotation(labelOnlyBase=False,
                                                                    minor_thresholds=(np.inf, np.inf)))
        else:  # less than a factor of ~1.3: three geometric ticks
            axis.set_major_locator(ticker.FixedLocator(np.geomspace(lo, hi, 5)[1:4]))
            axis.set_major_formatter(ticker.FormatStrFormatter("%.3g"))
        axis.set_minor_formatter(ticker.NullFormatter())
        set_lim(lim)


def labelled_ticks(ax, which):
    """The (value, text) of the labelled major ticks in view on ax's x or y axis, after a
    draw of its figure (what a reader sees)."""
    ax.figure.canvas.draw()
    axis = ax.xaxis if which == "x" else ax.yaxis
    lo, hi = sorted(ax.get_xlim() if which == "x" else ax.get_ylim())
    out = []
    for tick in axis.get_major_ticks():
        v = tick.get_loc()
        text = tick.label1.get_text()
        if tick.label1.get_visible() and text.strip() and lo * (1 - 1e-9) <= v <= hi * (1 + 1e-9):
            out.append((v, text))
    return out


def save(fig, outdir, name, png_dpi=160):
    """Write outdir/name.pdf and outdir/name.png (the folder created if missing); every
    log axis gets enough labelled ticks first (fix_log_ticks). Return the two paths."""
    os.makedirs(outdir, exist_ok=True)
    for ax in fig.axes:
        if ax.name != "3d":
            fix_log_ticks(ax)
    paths = [claim(os.path.join(outdir, name + ".pdf")), claim(os.path.join(outdir, name + ".png"))]
    fig.savefig(paths[0])
    fig.savefig(paths[1], dpi=png_dpi)
    plt.close(fig)
    print(f"wrote {paths[0]} and .png", file=sys.stderr)
    return paths


def legend_below(fig, handles, ncol, fontsize):
    """One legend for the whole figure, centred under its axes; `handles` maps each label
    to its artist, in the order they were drawn."""
    fig.legend(list(handles.values()), list(handles.keys()), ncol=ncol, loc="upper center",
               bbox_to_anchor=(0.5, 0.0), fontsize=fontsize, frameon=False)


def parser(description):
    p = argparse.ArgumentParser(description=description)
    p.add_argument("files", nargs="*", help="HDF5 files written by lgi")
    p.add_argument("--out", required=True, type=out_dir,
                   help="output folder for the PDF and PNG files (created with its parents if missing)")
    p.add_argument("--schemes-json", type=use_scheme_facts, metavar="FILE",
                   help="the output of `lgi schemes --json`: baselines are drawn dashed and compositions "
                        "dash-dot from its facts (without it every line is solid)")
    return p


def _range(text):
    """A:B (A < B, finite) for --l-range / --h-range / --k-range (an argparse type)."""
    try:
        a, b = (float(x) for x in text.split(":"))
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}': expected A:B, two numbers")
    if not (np.isfinite(a) and np.isfinite(b) and a < b):
        raise argparse.ArgumentTypeError(f"'{text}': expected A:B with A < B, both finite")
    return (a, b)


def add_plane_options(p, k_range=False):
    """--l-range, --h-range (and --k-range) and --l-nonneg: the window of an (l, h)
    (or (h, k)) figure; without them the script frames the features itself."""
    p.add_argument("--l-range", type=_range, metavar="A:B", help="l shown from A to B (default: framed on the data)")
    p.add_argument("--h-range", type=_range, metavar="A:B", help="h shown from A to B (default: framed on the data)")
    if k_range:
        p.add_argument("--k-range", type=_range, metavar="A:B", help="k shown from A to B (default: the attained k)")
    p.add_argument("--l-nonneg", action="store_true",
                   help="only l >= 0 (the diagrams are symmetric under l -> -l, h -> h)")
    return p


def num(x):
    """A number for a title or label: 6 significant digits (2.2, never 2.2000000000000002)."""
    return f"{float(x):.6g}"


def die(msg):
    print(f"{os.path.basename(sys.argv[0])}: {msg}", file=sys.stderr)
    sys.exit(2)  # bad input: one line and exit 2, as lgi itself (README "Using lgi")


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


def load_periodic(path, needed, missing_why):
    """The /periodic table of an lgi periodic file, with the columns `needed`; dies with one
    line naming the file on a file it cannot read, without /periodic or without a column
    (its name and `missing_why`)."""
    try:
        t = load_table(path, "periodic")
    except OSError as e:
        die(f"{path}: cannot read ({e})")
    if t is None:
        die(f"{path}: no /periodic group (not a file written by lgi periodic)")
    missing = [k for k in needed if k not in t]
    if missing:
        die(f"{path}: /periodic has no column {missing[0]} ({missing_why})")
    return t


def load_attrs(path, group):
    with h5py.File(path, "r") as f:
        return attrs(f[group]) if group in f else {}


def scene_label(params_or_path):
    """A short scene name from a scene file path."""
    s = params_or_path if isinstance(params_or_path, str) else params_or_path.get("scene_file", "?")
    return os.path.splitext(os.path.basename(s))[0]


# ── attitude (docs/conventions.md) ───────────────────────────────────────────
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
    """q and −q are one attitude (docs/conventions.md §1); a file may switch between them
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
