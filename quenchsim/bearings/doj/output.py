"""Results of a DOJ revolution: arrays over phase, summary numbers, CSV and figures."""

from __future__ import annotations

import csv
import pathlib
from dataclasses import dataclass
from typing import Any

import numpy as np

from quenchsim.bearings.doj.model import PhaseResult
from quenchsim.figures import save, subplots


@dataclass
class Revolution:
    """Per-phase results (phase (n,), per-ball arrays (n, 6), sphere forces (n,)) in N and degrees, with P_n."""

    phase_deg: np.ndarray
    p_inner_N: np.ndarray
    p_outer_N: np.ndarray
    p_window_N: np.ndarray
    wedge_angle_deg: np.ndarray
    f_inner_cage_N: np.ndarray
    f_cage_outer_N: np.ndarray
    outer_race_torque_Nm: np.ndarray
    shaft_reaction_N: np.ndarray
    p_n_N: float
    outer_race_axial_N: np.ndarray | None = None

    @classmethod
    def from_phases(cls, phases: list[PhaseResult], p_n_N: float) -> "Revolution":
        get = lambda name: np.array([getattr(r, name) for r in phases])  # noqa: E731
        return cls(get("phase_deg"), get("p_inner_N"), get("p_outer_N"), get("p_window_N"), get("wedge_angle_deg"),
                   get("f_inner_cage_N"), get("f_cage_outer_N"), get("outer_race_torque_Nm"),
                   get("shaft_reaction_N"), p_n_N, get("outer_race_axial_N"))


def harmonic_amplitude(phase_deg: np.ndarray, values: np.ndarray, order: int) -> float:
    """Amplitude of the ``order``-per-revolution harmonic of ``values`` sampled uniformly over one revolution
    (the last sample, at 360 deg, is dropped when it repeats the first)."""
    if phase_deg[-1] - phase_deg[0] >= 360.0 - 1e-9:
        phase_deg, values = phase_deg[:-1], values[:-1]
    phi = np.radians(phase_deg)
    return float(2.0 * abs(np.mean(values * np.exp(-1j * order * phi))))


def summary(rev: Revolution, torque_Nm: float) -> dict:
    """Ranges over the revolution (in units of P_n and as N), the share of ball-phases with no outer-track force,
    the 6-per-revolution amplitude of F_ic, and the largest |outer-race torque / T - 1|."""
    pn = rev.p_n_N
    out: dict[str, Any] = {"p_n_N": pn}
    for name, arr in (("p_inner", rev.p_inner_N), ("p_outer", rev.p_outer_N), ("p_window", rev.p_window_N),
                      ("f_inner_cage", rev.f_inner_cage_N), ("f_cage_outer", rev.f_cage_outer_N)):
        out[name] = {"min_over_p_n": float(arr.min() / pn), "max_over_p_n": float(arr.max() / pn),
                     "mean_over_p_n": float(arr.mean() / pn)}
    wedge = rev.wedge_angle_deg[np.isfinite(rev.wedge_angle_deg)]
    out["wedge_angle_deg"] = {"min": float(wedge.min()) if wedge.size else None,
                              "max": float(wedge.max()) if wedge.size else None}
    out["unloaded_ball_phase_fraction"] = float(np.mean(rev.p_outer_N < 1e-6 * pn))
    out["f_inner_cage_6_per_rev_over_p_n"] = harmonic_amplitude(rev.phase_deg, rev.f_inner_cage_N, 6) / pn
    out["torque_ratio_error"] = float(np.abs(rev.outer_race_torque_Nm / torque_Nm - 1.0).max())
    return out


def write_csv(rev: Revolution, path: pathlib.Path) -> pathlib.Path:
    """One row per phase: phase, P_i / P_o / P_p / wedge angle of each ball, F_ic, F_co, outer-race torque."""
    path = pathlib.Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["phase_deg", *[f"{q}_{i}" for q in ("P_i_N", "P_o_N", "P_p_N", "wedge_deg") for i in range(6)],
                    "F_ic_N", "F_co_N", "outer_race_torque_Nm"])
        for k in range(rev.phase_deg.size):
            w.writerow([rev.phase_deg[k], *rev.p_inner_N[k], *rev.p_outer_N[k], *rev.p_window_N[k],
                        *rev.wedge_angle_deg[k], rev.f_inner_cage_N[k], rev.f_cage_outer_N[k],
                        rev.outer_race_torque_Nm[k]])
    return path


def plot_runs(runs: dict[str, Revolution], title: str, path: pathlib.Path) -> pathlib.Path:
    """P_o, P_p (ball 0), F_ic and the wedge angle (ball 0) over the revolution, normalised by P_n, one line per run
    (the paper's Figs. 8 and 9)."""
    fig, axes = subplots(2, 2, figsize=(10, 6.4))
    panels = ((axes[0, 0], "P_o / P_n (ball 0)", lambda r: r.p_outer_N[:, 0] / r.p_n_N),
              (axes[0, 1], "P_p / P_n (ball 0, + along +z)", lambda r: r.p_window_N[:, 0] / r.p_n_N),
              (axes[1, 0], "F_ic / P_n", lambda r: r.f_inner_cage_N / r.p_n_N),
              (axes[1, 1], "wedge angle, deg (ball 0)", lambda r: r.wedge_angle_deg[:, 0]))
    for ax, label, get in panels:
        for name, rev in runs.items():
            ax.plot(rev.phase_deg, get(rev), label=name)
        ax.set_xlabel("rotational phase (deg)")
        ax.set_ylabel(label)
        ax.set_xlim(0.0, 360.0)
        ax.set_xticks(np.arange(0, 361, 60))
        ax.grid(True, alpha=0.3)
    axes[0, 0].legend(fontsize=7)
    axes[0, 0].set_title(title, fontsize=9)
    fig.tight_layout()
    return save(fig, path)


def plot_polar(rev: Revolution, title: str, path: pathlib.Path) -> pathlib.Path:
    """Magnitude of P_o of each ball against its angular position psi = phase + 60 i (the paper's Fig. 10)."""
    fig, ax = subplots(figsize=(5, 5), subplot_kw={"projection": "polar"})
    for i in range(rev.p_outer_N.shape[1]):
        psi = np.radians(rev.phase_deg + 60.0 * i)
        ax.plot(psi, rev.p_outer_N[:, i] / rev.p_n_N, lw=0.8, color=f"C{i}", label=f"ball {i}")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=6, loc="lower left")
    return save(fig, path)
