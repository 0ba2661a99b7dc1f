"""Plots of the metallurgy: the CCT diagram implied by a material's kinetics (used by `quenchsim cct` and the
materials/cct validation study). matplotlib is imported inside the function only."""

from __future__ import annotations

import pathlib

import numpy as np

from quenchsim.figures import save, subplots
from quenchsim.metallurgy.cct import CCTDiagram
from quenchsim.metallurgy.kinetics import Kinetics

CURVE_RATES_C_S = (0.3, 1.0, 3.0, 10.0, 30.0, 100.0)
COLOURS = {"pearlite": "tab:red", "bainite": "tab:blue"}


def plot_cct(diagram: CCTDiagram, kin: Kinetics, path: pathlib.Path) -> pathlib.Path:
    """Temperature vs log time: start/finish lines of each product, Ms, cooling curves labelled with the final HRC."""

    fig, ax = subplots(figsize=(8.0, 6.0))
    d = diagram
    for p in kin.reactions:
        ax.plot(d.start_time_s[p], d.start_T_C[p], "-", color=COLOURS[p], lw=2, label=f"{p} 1 %")
        ax.plot(d.finish_time_s[p], d.finish_T_C[p], "--", color=COLOURS[p], lw=1.5, label=f"{p} 99 % of final")
        ax.axhline(kin.reactions[p].T_upper_C, color=COLOURS[p], lw=0.6, ls=":")
    ax.axhline(d.Ms_C, color="k", lw=1.2, ls="-.", label=f"Ms = {d.Ms_C:.0f} C")
    t = np.logspace(-1.5, 4.5, 400)
    for rate in CURVE_RATES_C_S:
        T = d.T_start_C - rate * t
        keep = T >= d.T_end_C
        ax.plot(t[keep], T[keep], color="0.75", lw=0.8)
        i = int(np.argmin(np.abs(np.log(d.rates_C_s / rate))))
        label = f"{rate:g} C/s: {d.hardness_HRC[i]:.0f} HRC" if np.isfinite(d.hardness_HRC[i]) else f"{rate:g} C/s: {d.hardness_HV[i]:.0f} HV"
        t_end = (d.T_start_C - 60.0) / rate
        if t_end < t[-1]:
            ax.annotate(label, (t_end, 60.0), fontsize=7, rotation=-60, ha="left", va="bottom", color="0.35")
    ax.set_xscale("log")
    ax.set_xlim(0.1, 3e4)
    ax.set_ylim(0.0, d.T_start_C + 20.0)
    ax.set_xlabel("time from the austenitising temperature (s)")
    ax.set_ylabel("temperature (C)")
    ax.set_title(f"{d.material}: CCT from the kinetics, T_aust = {d.T_aust_C:g} C, "
                 f"dissolved C = {kin.dissolved['C']:.2f} %")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    save(fig, path)
    return path
