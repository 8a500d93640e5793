#!/usr/bin/python3
"""Short comparison of the demo's trajectories (scripts/demo.sh).

For each book scene: the largest attitude and momentum differences between
rkmk4 and the exact flow over the run, the energy drift of rkmk4, and the
times at which Omega_2 changes sign (the flips of the intermediate axis).
Reads the H5MD files with h5py (Debian's python3-h5py).
"""
import sys

import h5py
import numpy as np


def load(path):
    with h5py.File(path, "r") as f:
        body = f["particles/body"]
        return {
            "t": body["orientation/time"][:],
            "q": body["orientation/value"][:, 0, :],
            "Pi": body["angular_momentum_body/value"][:, 0, :],
            "Omega": body["angular_velocity_body/value"][:, 0, :],
            "energy": f["observables/energy/value"][:],
        }


def attitude_distance(qa, qb):
    """2 atan2(|vec(qa* qb)|, |w(qa* qb)|), treating q and -q alike."""
    w = np.sum(qa * qb, axis=1)
    # vector part of conj(qa) * qb
    v = qa[:, :1] * qb[:, 1:] - qb[:, :1] * qa[:, 1:] - np.cross(qa[:, 1:], qb[:, 1:])
    return 2.0 * np.arctan2(np.linalg.norm(v, axis=1), np.abs(w))


def sign_changes(t, x):
    idx = np.nonzero(np.signbit(x[1:]) != np.signbit(x[:-1]))[0]
    # linear interpolation of the zero crossing
    return t[idx] - x[idx] * (t[idx + 1] - t[idx]) / (x[idx + 1] - x[idx])


def main(folder):
    print(f"{'scene':<28}{'max |att diff|':>15}{'max |dPi|/|Pi|':>16}{'rkmk4 energy drift':>20}   Omega_2 sign changes (s)")
    for axis in (1, 2, 3):
        a = load(f"{folder}/book_axis{axis}_rkmk4.h5")
        e = load(f"{folder}/book_axis{axis}_exact.h5")
        att = attitude_distance(a["q"], e["q"]).max()
        dpi = (np.linalg.norm(a["Pi"] - e["Pi"], axis=1) / np.linalg.norm(e["Pi"], axis=1)).max()
        drift = abs(a["energy"][-1] - a["energy"][0]) / abs(a["energy"][0])
        flips = sign_changes(e["t"], e["Omega"][:, 1]) if axis == 2 else []
        flip_text = ", ".join(f"{x:.3f}" for x in flips) if axis == 2 else "none (stable axis)"
        print(f"dzhanibekov_book_axis{axis:<7}{att:>15.3e}{dpi:>16.3e}{drift:>20.3e}   {flip_text}")
    print("axis 2 is the intermediate axis: the book flips; axes 1 and 3 are stable.")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "build/demo")
