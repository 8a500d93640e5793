#!/usr/bin/python3
"""Poisson-sphere potentials and energy-surface topologies from `lgi region` files
(experiments/REGION.md: /potential, /critical_points, /components; with --cells, /cells
and /equilibria).

Usage: region.py --out DIR [--combine NAME] [--l-range A:B] [--h-range A:B] [--l-nonneg] REGION.h5 ...

A file of `lgi region --l L --h H` gives DIR/region_<file stem>.{pdf,png}: the amended
potential U_l on the sphere (phi across, theta down, body axes), the accessible region
U_l <= h shaded by component, the critical points (relative equilibria) marked by Morse
index, and the energy surface's topology in the title (docs/atlas.md §8). With
--combine NAME those files go into one figure DIR/NAME.{pdf,png}, one panel each (the
seed's "Poisson sphere potentials" with the topologies named). A file of
`lgi region --cells` gives DIR/region_cells_<file stem>.{pdf,png}: the (l, h) plane
coloured by the topology of the energy surface, with the branches of relative
equilibria on top, each large patch named and a legend of every topology that
occurs (so a small patch is told by its colour); --l-range, --h-range and
--l-nonneg set its window (default: the file's grid).
"""
import os

import numpy as np

import lgi_plot_common as c

# One colour per topology name, the same in every figure; others get grey shades.
TOPOLOGY_COLOURS = {"empty": "white", "S3": "#9ecae1", "2S3": "#3182bd", "S1xS2": "#fdae6b", "RP3": "#a1d99b",
                    "S3 + S1xS2": "#e6550d", "2(S1xS2)": "#fd8d3c", "3S3": "#08519c", "S3 + RP3": "#31a354"}
MARKERS = {0: ("v", "minimum"), 1: ("x", "saddle"), 2: ("^", "maximum")}


def tex_topology(name):
    """S1xS2 -> $S^1\\times S^2$ and so on, for titles and labels."""
    out = name.replace("S1xS2", "S^1\\times S^2").replace("RP3", "\\mathbb{RP}^3").replace("S3", "S^3")
    out = out.replace("#", "\\#")
    return "empty" if name == "empty" else f"${out}$"


def read_single(f):
    p = {k: np.asarray(f["potential"][k][()]) for k in f["potential"]}
    cp = {k: np.asarray(f["critical_points"][k][()]) for k in f["critical_points"]}
    return p, cp, c.attrs(f["parameters"])


def draw_single(ax, p, cp, par):
    theta, phi, U, comp = p["theta"], p["phi"], p["U"], p["component"]
    h = float(par["h"])
    extent = (0.0, 2 * np.pi, np.pi, 0.0)
    ax.imshow(U, extent=extent, aspect="auto", cmap="Greys", alpha=0.55, interpolation="nearest")
    shade = np.ma.masked_less(comp.astype(float), 0)
    ax.imshow(shade, extent=extent, aspect="auto", cmap="tab10", vmin=0, vmax=9, alpha=0.45, interpolation="nearest")
    if np.ptp(U) > 0:
        ax.contour(phi, theta, U, levels=[h], colors="k", linewidths=0.8)
    g = cp.get("gamma", np.zeros((0, 3)))
    for k in range(len(g)):
        th = np.arccos(np.clip(g[k, 2], -1, 1))
        ph = np.arctan2(g[k, 1], g[k, 0]) % (2 * np.pi)
        m, _ = MARKERS[int(cp["index"][k])]
        ax.plot(ph, th, m, color="tab:red" if cp["below"][k] else "0.3", ms=5, mfc="none" if cp["circle"][k] else None,
                clip_on=False, zorder=5)  # the poles and phi = 0 are on the frame: markers drawn whole
    ax.set_xlim(0, 2 * np.pi)
    ax.set_ylim(np.pi, 0)
    ax.set_xlabel("$\\varphi$")
    ax.set_ylabel("$\\vartheta$")
    ax.set_title(f"$\\ell$ = {c.num(par['l'])}, h = {c.num(h)}: {tex_topology(par['topology'])}"
                 + ("" if par.get("resolved", "yes") == "yes" else " (unresolved)"), fontsize=8)


def draw_cells(ax, f, args):
    cells = {k: np.asarray(f["cells"][k][()]) for k in f["cells"]}
    names = c.attrs(f["cells"])["topology_names"].split("\n")
    l, h, code = cells["l"], cells["h"], cells["topology"]
    grey = iter(np.linspace(0.35, 0.8, max(1, len(names))))
    colours = [TOPOLOGY_COLOURS.get(n) or str(next(grey)) for n in names]
    rgb = np.array([c.matplotlib.colors.to_rgb(col) for col in colours])
    img = rgb[code.T]  # rows: h, columns: l
    img[cells["resolved"].T == 0] = (0.55, 0.55, 0.55)
    dl = (l[-1] - l[0]) / max(1, len(l) - 1) if len(l) > 1 else 1.0
    dh = (h[-1] - h[0]) / max(1, len(h) - 1) if len(h) > 1 else 1.0
    ax.imshow(img, origin="lower", aspect="auto", interpolation="nearest",
              extent=(l[0] - dl / 2, l[-1] + dl / 2, h[0] - dh / 2, h[-1] + dh / 2))
    if "equilibria" in f:
        e = {k: np.asarray(f["equilibria"][k][()]) for k in ("l", "h", "branch", "fold")}
        for b in np.unique(e["branch"]):
            sel = (e["branch"] == b) & (e["fold"] == 0)
            ax.plot(e["l"][sel], e["h"][sel], color="k", lw=0.7)
    ax.plot(l, cells["h_min"], color="k", lw=0.7, ls="--")
    from scipy import ndimage
    for k, name in enumerate(names):
        if name == "empty":
            continue
        patches, count = ndimage.label((code == k) & (cells["resolved"] == 1))
        for p in range(1, count + 1):
            il, ih = np.nonzero(patches == p)
            if len(il) < 0.01 * code.size:
                continue
            ax.text(l[int(np.median(il))], h[int(np.median(ih))], tex_topology(name), ha="center", va="center",
                    fontsize=7, bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.7))
    l0, l1 = args.l_range if args.l_range else (l[0] - dl / 2, l[-1] + dl / 2)
    if args.l_nonneg:
        l0 = max(l0, 0.0)
    ax.set_xlim(l0, l1)
    ax.set_ylim(*(args.h_range if args.h_range else (h[0] - dh / 2, h[-1] + dh / 2)))
    ax.set_xlabel("$\\ell = \\Pi\\cdot\\Gamma$")
    ax.set_ylabel("$h$")
    # Every topology present, small patches too, and the grey of unresolved cells.
    present = sorted(set(np.unique(code[cells["resolved"] == 1]).tolist()))
    handles = [c.matplotlib.patches.Patch(fc=colours[k], ec="0.4", lw=0.4, label=tex_topology(names[k]))
               for k in present]
    if np.any(cells["resolved"] == 0):
        handles.append(c.matplotlib.patches.Patch(fc=(0.55, 0.55, 0.55), label="not resolved by the grid"))
    handles.append(c.plt.Line2D([], [], color="k", lw=0.7, label="relative equilibria"))
    handles.append(c.plt.Line2D([], [], color="k", lw=0.7, ls="--", label="least energy"))
    ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=6.5, borderaxespad=0)


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--combine", metavar="NAME", help="put every single-region file into one figure NAME")
    c.add_plane_options(p)
    args = p.parse_args()
    if not args.files:
        c.die("give at least one file written by lgi region")
    singles = []
    for path in args.files:
        with c.h5py.File(path, "r") as f:
            if "cells" in f:
                fig, ax = c.plt.subplots(figsize=(6.0, 3.8))
                draw_cells(ax, f, args)
                ax.set_title(c.scene_label(c.attrs(f["parameters"])), fontsize=8)
                c.save(fig, args.out, f"region_cells_{c.file_stem(path)}")
            elif "potential" in f:
                singles.append((path, read_single(f)))
            else:
                c.die(f"{path}: neither /potential nor /cells (not a file written by lgi region)")
    if args.combine and singles:
        cols = min(3, len(singles))
        rows = (len(singles) + cols - 1) // cols
        fig, axes = c.plt.subplots(rows, cols, figsize=(3.0 * cols, 2.5 * rows), squeeze=False)
        labels = [c.scene_label(data[2]) for _, data in singles]
        for ax, (path, data), label in zip(axes.ravel(), singles, labels):
            draw_single(ax, *data)
            if len(set(labels)) > 1:  # panels of different scenes: each names its own
                ax.set_title(f"{label}\n{ax.get_title()}", fontsize=8)
        for ax in axes.ravel()[len(singles):]:
            ax.axis("off")
        if len(set(labels)) == 1:
            fig.suptitle(labels[0], fontsize=9)
        fig.tight_layout()
        c.save(fig, args.out, args.combine)
    else:
        for path, data in singles:
            fig, ax = c.plt.subplots(figsize=(4.6, 3.0))
            draw_single(ax, *data)
            ax.set_title(c.scene_label(data[2]) + "\n" + ax.get_title(), fontsize=8)
            c.save(fig, args.out, f"region_{c.file_stem(path)}")


if __name__ == "__main__":
    main()
