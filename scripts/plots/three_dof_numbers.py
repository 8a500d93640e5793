#!/usr/bin/python3
"""The numbers of the paper's section "Three degrees of freedom" (paper/sections/three_dof.tex),
from the files scripts/paper_3dof.sh writes in its data folder.

Usage: three_dof_numbers.py --data DIR --commands FILE --gen DIR --tilt ALPHA

Writes GEN/three_dof_numbers.tex (LaTeX macros \\Tdof...) and GEN/three_dof_commands.tex
(the lgi command lines, verbatim, as the other sections print them).
"""
import argparse
import json
import os
import re

import h5py
import numpy as np

from atlas_tables import commands_block


def chaos_map(path):
    with h5py.File(path, "r") as f:
        m = {k: np.asarray(f["chaos_map"][k][()]) for k in f["chaos_map"]}
        wall = float(f["parameters"].attrs["wall_seconds"])
    ok = m["status"] == 0
    chaotic = np.where(ok, m["chaotic"], 0)
    orbits = np.where(ok, m["orbits"], 0)
    col = lambda j: chaotic[j].sum() / max(orbits[j].sum(), 1)  # noqa: E731
    cols = [col(j) for j in range(len(m["vary"]))]
    same = bool(np.array_equal(chaotic, chaotic[:1].repeat(len(m["vary"]), axis=0)))
    return {"chaotic": int(chaotic.sum()), "orbits": int(orbits.sum()), "upright": cols[0],
            "tilted": max(cols[1:]) if len(cols) > 1 else float("nan"), "cells": int(ok.sum()),
            "same_columns": same, "wall": wall}


def frequency_map(data):
    with h5py.File(os.path.join(data, "frequency_map.h5"), "r") as f:
        d = {k: np.asarray(f["frequency_diffusion"][k][()]) for k in f["frequency_diffusion"]}
        par = dict(f["parameters"].attrs)
    a, b = d["frequency_first_half"].reshape(-1, 3), d["frequency_second_half"].reshape(-1, 3)
    with np.errstate(divide="ignore", invalid="ignore"):
        diff = np.log10(np.linalg.norm(b - a, axis=1) / np.linalg.norm(a, axis=1))
    ok = np.isfinite(diff)
    with h5py.File(os.path.join(data, "family.h5"), "r") as f:
        h = float(f["family"].attrs["h"])
        spread = float(f["family"].attrs["potential_spread"])
    return {"states": int(len(diff)), "finite": int(ok.sum()), "above": float(np.mean(diff[ok] > -3)),
            "below": float(np.mean(diff[ok] < -6)), "median": float(np.median(diff[ok])), "h": h,
            "spread": spread, "t_end": float(par["t_end"]), "wall": float(par["wall_seconds"])}


def steady(data):
    text = open(os.path.join(data, "steady_precession.log")).read()
    omega = float(re.search(r"Omega = ([-0-9.e+]+)", text).group(1))
    residual = float(re.search(r"dp2/dt = ([-0-9.e+]+)", text).group(1))
    with h5py.File(os.path.join(data, "steady_precession_freq.h5"), "r") as f:
        t = {k: np.asarray(f["frequencies"][k][()]) for k in f["frequencies"]}
    names = np.array([s.decode() for s in t["observable"]])
    lead = lambda n: float(t["frequency"][names == n][0])  # noqa: E731
    q2 = t["amplitude"][names == "cardan_angle_2"]
    return {"omega": omega, "residual": residual, "w1": lead("sin_cardan_angle_1"), "w3": lead("sin_cardan_angle_3"),
            "nutation": float(q2.max()) if q2.size else 0.0}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", required=True)
    ap.add_argument("--commands", required=True)
    ap.add_argument("--gen", required=True)
    ap.add_argument("--tilt", required=True)
    a = ap.parse_args()
    maps = {k: chaos_map(os.path.join(a.data, f"map_{k}.h5")) for k in ("lagrange", "euler", "general")}
    fm = frequency_map(a.data)
    sp = steady(a.data)
    g = json.load(open(os.path.join(a.data, "gali.json")))
    macros = {}
    for key, name in (("lagrange", "Lag"), ("euler", "Eul"), ("general", "Gen")):
        m = maps[key]
        macros[f"Tdof{name}Chaotic"] = f"{m['chaotic']}"
        macros[f"Tdof{name}Orbits"] = f"{m['orbits']}"
        macros[f"Tdof{name}Upright"] = f"{m['upright']:.2f}"
        macros[f"Tdof{name}Tilted"] = f"{m['tilted']:.2f}"
        macros[f"Tdof{name}Wall"] = f"{m['wall']:.0f}"
    macros["TdofEulSame"] = "the same in every column" if maps["euler"]["same_columns"] else "not the same in every column"
    macros["TdofFmStates"] = f"{fm['finite']}"
    macros["TdofFmH"] = f"{fm['h']:g}"
    macros["TdofFmTilt"] = a.tilt
    macros["TdofFmTend"] = f"{fm['t_end']:g}"
    macros["TdofFmAbove"] = f"{100 * fm['above']:.0f}"
    macros["TdofFmBelow"] = f"{100 * fm['below']:.0f}"
    macros["TdofFmMedian"] = f"{fm['median']:.1f}"
    macros["TdofFmSpread"] = f"{fm['spread']:.0e}"
    macros["TdofFmWall"] = f"{fm['wall']:.0f}"
    macros["TdofSpOmega"] = f"{sp['omega']:.10f}"
    macros["TdofSpResidual"] = f"{sp['residual']:.0e}"
    macros["TdofSpWone"] = f"{sp['w1']:.10f}"
    macros["TdofSpWthree"] = f"{sp['w3']:.10f}"
    macros["TdofSpNutation"] = "no line (the angle is constant to the last bit)" if sp["nutation"] == 0 else \
        f"a line of amplitude {sp['nutation']:.1e}"
    for key, name in (("torus3", "Three"), ("torus2", "Two")):
        macros[f"Tdof{name}Slopes"] = ", ".join(f"{s:.2f}" for s in g[key]["slopes"])
        macros[f"Tdof{name}Laws"] = ", ".join(f"{s:g}" for s in g[key]["laws"])
        macros[f"Tdof{name}Window"] = f"[{g[key]['window'][0]:.0f}, {g[key]['window'][1]:.0f}]"
        macros[f"Tdof{name}Megno"] = f"{g[key]['megno']:.2f}"
    ch = g["chaos"]
    macros["TdofChaosRates"] = ", ".join(f"{r:.2f}" for r in ch["rates"])
    macros["TdofChaosExpected"] = ", ".join(f"{r:.2f}" for r in ch["expected"])
    macros["TdofChaosSpectrum"] = ", ".join(f"{r:.3f}" for r in ch["spectrum"])
    macros["TdofChaosStart"] = f"{ch['windows'][0][0]:.0f}"
    macros["TdofChaosEnds"] = ", ".join(f"{w[1]:.0f}" for w in ch["windows"])
    macros["TdofChaosMegno"] = f"{ch['megno']:.1f}"
    macros["TdofChaosTend"] = f"{ch['t_end']:g}"
    with open(os.path.join(a.gen, "three_dof_numbers.tex"), "w") as f:
        for k, v in macros.items():
            f.write(f"\\newcommand{{\\{k}}}{{{v}}}\n")
    with open(os.path.join(a.gen, "three_dof_commands.tex"), "w") as f:
        f.write(commands_block(a.commands))


if __name__ == "__main__":
    main()
