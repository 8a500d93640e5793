"""The periodic orbits of `lgi periodic` files drawn into the Kovalevskaya top's
(h, k) diagram of bifurcation.py (experiments/PERIODIC.md, "Kovalevskaya's top:
critical orbits"; docs/atlas.md §9): each family of a file at the panel's l is a
line through its orbits' (h / (J3 c), k), coloured by stability class (the colours of
periodic.py), its orbits dotted. A module of bifurcation.py (--periodic FILE),
drawn in no figure of its own."""
import numpy as np

import lgi_plot_common as c

COLOURS = {"elliptic": "tab:green", "hyperbolic": "tab:brown", "inverse_hyperbolic": "deeppink",
           "complex": "tab:olive"}
NEEDED = ("family", "l", "h", "k", "stability")


def load(paths):
    """The /periodic tables of paths; dies on a file without /periodic or without its k column."""
    tables = []
    for path in paths or []:
        tables.append(c.load_periodic(path, NEEDED, "written before lgi periodic recorded k"))
    return tables


def draw(ax, l, scale, tables):
    """Draws the orbits at l (to 1e-9) of every table on ax; scale = J3 c divides h.
    Returns the number of orbits drawn. A class change along a family changes colour there."""
    drawn = 0
    for t in tables:
        at = (np.abs(t["l"] - l) <= 1e-9 * max(1.0, abs(l))) & np.isfinite(t["k"])
        for fam in np.unique(t["family"][at]):
            rows = np.flatnonzero(at & (t["family"] == fam))
            h, k, s = t["h"][rows] / scale, t["k"][rows], t["stability"][rows]
            for i in range(len(rows) - 1):
                ax.plot(h[i:i + 2], k[i:i + 2], color=COLOURS.get(s[i], "k"), lw=2.4, alpha=0.55, zorder=5)
            for cls in np.unique(s):
                sel = s == cls
                ax.plot(h[sel], k[sel], "o", ms=2.2, color=COLOURS.get(cls, "k"), zorder=6)
            drawn += len(rows)
    return drawn


def legend_entries(tables):
    """(handle, label) for each class present in the tables."""
    present = set()
    for t in tables:
        present |= set(t["stability"][np.isfinite(t["k"])])
    return [(c.plt.Line2D([], [], color=COLOURS[s], lw=2.4, alpha=0.55, marker="o", ms=2.2),
             f"periodic orbits ({s.replace('_', ' ')})") for s in COLOURS if s in present]
