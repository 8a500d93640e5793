#!/usr/bin/python3
"""Projected weak scaling of `lgi sweep` to 1024 MPI ranks (README "Running on a cluster").

Usage: sweep_scaling.py --out DIR SWEEP.h5 [SWEEP.h5 ...]

Each SWEEP.h5 is a finished sweep measured on one machine. From it: the
per-trajectory CPU costs c_i (/sweep/cpu_seconds), the bytes a trajectory
sends to rank 0 (its /sweep row and its crossings), and rank 0's measured
cost per row of writing the partial file and of writing the final file
(/provenance partial_write_seconds, final_write_seconds). The model, per
rank with T threads and n trajectories per thread (weak scaling: n fixed):

  compute  = n c̄ + ½ (chunk cost)                   dynamic chunks: at most one chunk of imbalance
  writer   = K T n (w + b/B)                        rank 0 writes every row and receives every byte
  T(K)     = max(compute, writer) + K T n f + L(K)  the final file is written once, at the end
  E(K)     = T(1) / T(K)

with w, f the measured write costs per row, b bytes per row, B = 5 GB/s
(interconnect bandwidth into rank 0, assumed) and L(K) = 0.3 s + 0.05 s·log2 K
(job start-up; the 0.3 s is mpirun's measured start on this machine, the
growth is assumed). T = 32, n = 1000 as in scripts/slurm/lgi_sweep.sbatch.
Writes DIR/sweep_scaling.{pdf,png} and prints the table.
"""
import math

import numpy as np

import lgi_plot_common as c

THREADS, PER_THREAD, BANDWIDTH = 32, 1000, 5e9
RANKS = [2 ** k for k in range(11)]


def measured(path):
    with c.h5py.File(path, "r") as f:
        s, prov = f["sweep"], f["provenance"].attrs
        cost = np.asarray(s["cpu_seconds"][()])
        n = len(cost)
        events = len(f["events/t"]) if "events" in f and "t" in f["events"] else 0
        row_bytes = sum(np.asarray(s[k][()]).nbytes for k in s) / n + 15 * 8 * events / n
        name = f["parameters"].attrs["spec_file"]
        name = name.decode() if isinstance(name, bytes) else name
        w = float(prov["partial_write_seconds"]) / n
        fin = float(prov["final_write_seconds"]) / n
    return {"name": name.rsplit("/", 1)[-1].removesuffix(".toml"), "mean": cost.mean(), "std": cost.std(),
            "n": n, "row_bytes": row_bytes, "w": w, "f": fin}


def efficiency(m):
    chunk = max(1, PER_THREAD // 16)  # lgi's default chunk: about 16 per thread
    compute = PER_THREAD * m["mean"] + 0.5 * chunk * m["mean"]
    out = []
    t1 = None
    for k in RANKS:
        rows = k * THREADS * PER_THREAD
        writer = rows * (m["w"] + m["row_bytes"] / BANDWIDTH)
        total = max(compute, writer) + rows * m["f"] + 0.3 + 0.05 * math.log2(k)
        t1 = total if t1 is None else t1
        out.append(t1 / total)
    return out


def main():
    args = c.parser(__doc__.split("\n\n")[0]).parse_args()
    if not args.files:
        raise SystemExit("sweep_scaling.py: give at least one finished sweep file")
    fig, ax = c.plt.subplots(figsize=(4.2, 2.8))
    print(f"{'sweep':28s} {'c_mean':>10s} {'w/row':>9s} {'f/row':>9s} {'B/row':>7s}  E(2) ... E(1024)")
    for path in args.files:
        m = measured(path)
        e = efficiency(m)
        print(f"{m['name']:28s} {m['mean']:10.3e} {m['w']:9.2e} {m['f']:9.2e} {m['row_bytes']:7.0f}  "
              + " ".join(f"{x:.2f}" for x in e[1:]))
        ax.plot(RANKS, e, marker="o", ms=3, label=f"{m['name']} ($\\bar c$ = {m['mean'] * 1e3:.3g} ms)")
    ax.set_xscale("log", base=2)
    ax.set_ylim(0, 1.05)
    ax.set_xlabel(f"MPI ranks ({THREADS} threads each, {PER_THREAD} trajectories per thread)")
    ax.set_ylabel("projected weak-scaling efficiency")
    ax.legend(loc="lower left")
    c.save(fig, args.out, "sweep_scaling")


if __name__ == "__main__":
    main()
