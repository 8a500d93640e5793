#!/usr/bin/python3
"""Animations (GIF, matplotlib's PillowWriter) of a tumbling box drawn with its
attitude from trajectory files, and a filmstrip of the same frames for the paper.

Usage: animate.py --out DIR [--frames N] [--fps F] TRAJ.h5 ...

For each trajectory (e.g. dzhanibekov_book_axis2.toml and prism_edurev.toml)
writes DIR/<scene>.gif (<scene> the stem of the scene file, e.g.
dzhanibekov_book_axis2.gif; DIR/<scene>_<input stem>.gif when several inputs
share a scene; DIR is created if missing); all of them together give DIR/tumbling_frames.{pdf,png}
(one row per file, six snapshots). The box is the uniform box with the scene's
principal moments: side_i² = (6/m)(ΣI − 2 I_i) (m from the scene, else 1;
a 4 × 1 × 2 prism of mass 12 has I = (5, 20, 17)). Its vertices are drawn in
space coordinates x = R(t) X with R from the file's quaternions; opposite faces
share a colour, the body axis of the initial spin is drawn as an arrow, and the
constant spatial angular momentum m = RΠ as a black arrow.
"""
import os

import numpy as np
from matplotlib.animation import PillowWriter
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

import lgi_plot_common as c

FACE_COLORS = np.array([[0.85, 0.33, 0.10], [0.85, 0.33, 0.10],   # ±x
                        [0.00, 0.45, 0.74], [0.00, 0.45, 0.74],   # ±y
                        [0.47, 0.67, 0.19], [0.47, 0.67, 0.19]])  # ±z
LIGHT = np.array([0.4, -0.5, 0.77]) / np.linalg.norm([0.4, -0.5, 0.77])


def box_dims(scene):
    I = np.diag(c.inertia_of(scene))
    m = float(scene.get("body", {}).get("mass", 1.0))
    sq = 6.0 / m * (I.sum() - 2.0 * I)
    return np.sqrt(np.maximum(sq, 1e-6 * sq.max()))


def box_faces(dims):
    a, b, cc = dims / 2
    v = np.array([[sx * a, sy * b, sz * cc] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)])
    idx = [[0, 1, 3, 2], [4, 5, 7, 6],   # x = -a, +a
           [0, 1, 5, 4], [2, 3, 7, 6],   # y = -b, +b
           [0, 2, 6, 4], [1, 3, 7, 5]]   # z = -c, +c
    normals = np.array([[-1, 0, 0], [1, 0, 0], [0, -1, 0], [0, 1, 0], [0, 0, -1], [0, 0, 1]], float)
    return v, idx, normals


class BoxArtist:
    def __init__(self, ax, r, title):
        self.r = r
        self.R = c.quat_to_matrix(r["q"])
        self.dims = box_dims(r["scene"])
        self.v, self.idx, self.normals = box_faces(self.dims)
        self.scale = 0.5 * np.linalg.norm(self.dims)
        w0 = r["Omega"][0]
        self.spin_axis = int(np.argmax(np.abs(w0)))
        m = self.R[0] @ r["Pi"][0]
        self.m_dir = m / np.linalg.norm(m)
        self.ax = ax
        self.poly = Poly3DCollection([], edgecolor="k", linewidths=0.4)
        ax.add_collection3d(self.poly)
        lim = self.scale * 1.05
        ax.set_xlim(-lim, lim)
        ax.set_ylim(-lim, lim)
        ax.set_zlim(-lim, lim)
        ax.set_box_aspect((1, 1, 1))
        ax.set_axis_off()
        ax.view_init(elev=18, azim=-60)
        ax.quiver(0, 0, 0, *(self.m_dir * self.scale * 1.0), color="k", lw=1.2, arrow_length_ratio=0.12)
        self.axis_line, = ax.plot([], [], [], color="crimson", lw=2.0)
        self.text = ax.text2D(0.03, 0.90, "", transform=ax.transAxes, fontsize=7)
        self.title = title

    def draw(self, k):
        R = self.R[k]
        verts = self.v @ R.T
        faces = [verts[i] for i in self.idx]
        shade = 0.45 + 0.55 * np.clip((self.normals @ R.T) @ LIGHT, 0, 1)
        self.poly.set_verts(faces)
        self.poly.set_facecolor(np.clip(FACE_COLORS * shade[:, None], 0, 1))
        e = np.zeros(3)
        e[self.spin_axis] = 0.5 * self.dims[self.spin_axis] + 0.35 * self.scale
        tip = R @ e
        self.axis_line.set_data_3d([-tip[0], tip[0]], [-tip[1], tip[1]], [-tip[2], tip[2]])
        self.text.set_text(f"{self.title}\nt = {self.r['t'][k]:5.2f} s")
        return self.poly, self.axis_line, self.text


def scene_title(r):
    name = c.scene_label(r["parameters"])
    if name.startswith("dzhanibekov_book"):
        return f"book ({r['scheme']})"
    if name.startswith("prism"):
        return f"prism 4×1×2 ({r['scheme']})"
    return f"{name} ({r['scheme']})"


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--frames", type=int, default=120)
    p.add_argument("--fps", type=int, default=12)
    args = p.parse_args()
    runs = [c.load_trajectory(f) for f in args.files]
    if not runs:
        c.die("no trajectory files given")
    names = c.unique_names([c.scene_label(r["parameters"]) for r in runs], args.files)
    for r, name in zip(runs, names):
        fig = c.plt.figure(figsize=(3.2, 3.2), dpi=80)
        ax = fig.add_axes([0, 0, 1, 1], projection="3d")
        art = BoxArtist(ax, r, scene_title(r))
        frames = np.unique(np.linspace(0, len(r["t"]) - 1, args.frames).round().astype(int))
        path = c.claim(os.path.join(args.out, name + ".gif"))
        writer = PillowWriter(fps=args.fps)
        with c.plt.rc_context({"savefig.bbox": None}), writer.saving(fig, path, dpi=80):
            for k in frames:  # a fixed frame size: no tight bounding box here
                art.draw(k)
                writer.grab_frame()
        c.plt.close(fig)
        print(f"wrote {path}")
    n = 6
    fig = c.plt.figure(figsize=(7.0, 1.35 * len(runs) + 0.1))
    for row, r in enumerate(runs):
        ks = np.linspace(0, len(r["t"]) - 1, n).round().astype(int)
        for j, k in enumerate(ks):
            ax = fig.add_subplot(len(runs), n, row * n + j + 1, projection="3d")
            art = BoxArtist(ax, r, scene_title(r) if j == 0 else "")
            art.draw(k)
            if j:
                art.text.set_text(f"t = {r['t'][k]:.2f} s")
    fig.subplots_adjust(left=0, right=1, top=1, bottom=0, wspace=0, hspace=0)
    c.save(fig, args.out, "tumbling_frames")


if __name__ == "__main__":
    main()
