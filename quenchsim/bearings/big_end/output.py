"""Time-series CSV and plots of a big-end run (slip ratios, pocket force, cage-centre orbit)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from quenchsim.bearings.big_end.simulate import RunResult
from quenchsim.bearings.big_end.state import StateView
from quenchsim.figures import save, subplots


def cage_orbit_um(result: RunResult) -> tuple[np.ndarray, np.ndarray]:
    """Cage centre relative to the outer-ring centre [um], in the frame of the run."""
    s = StateView(result.y, result.params.n)
    return 1e6 * (s.cage_x - s.ring_x), 1e6 * (s.cage_y - s.ring_y)


def write_csv(result: RunResult, path: Path) -> Path:
    """One row per sample: time, crank angle, cage slip, roller-mean slips, roller 1 pocket force,
    max pocket force, cage centre relative to the outer ring."""
    cx, cy = cage_orbit_um(result)
    cols = np.column_stack([
        result.t, np.degrees(result.crank_angle), result.cage_slip_pct,
        result.roller_orbital_slip_pct.mean(axis=0), result.roller_spin_slip_pct.mean(axis=0),
        result.pocket_force_n[0], result.pocket_force_n.max(axis=0), cx, cy,
    ])
    header = ("time_s,crank_angle_deg,cage_slip_pct,roller_orbital_slip_mean_pct,roller_spin_slip_mean_pct,"
              "pocket_force_roller1_N,pocket_force_max_N,cage_x_um,cage_y_um")
    path.parent.mkdir(parents=True, exist_ok=True)
    np.savetxt(path, cols, delimiter=",", header=header, comments="", fmt="%.6g")
    return path


def plot_run(result: RunResult, path: Path, title: str) -> Path:
    """Four panels: cage / roller-1 slips, pocket force of roller 1, cage-centre orbit."""
    rev = result.crank_angle / (2 * np.pi)
    fig, ax = subplots(2, 2, figsize=(11, 7))
    ax[0, 0].plot(rev, result.cage_slip_pct, lw=0.6)
    ax[0, 0].set(xlabel="crank revolutions", ylabel="cage slip [%]", title="cage slip ratio")
    ax[0, 1].plot(rev, result.roller_orbital_slip_pct[0], lw=0.6, label="orbital")
    ax[0, 1].plot(rev, result.roller_spin_slip_pct[0], lw=0.6, label="spin")
    ax[0, 1].set(xlabel="crank revolutions", ylabel="slip [%]", title="roller 1 slip ratios")
    ax[0, 1].legend()
    ax[1, 0].plot(rev, result.pocket_force_n[0], lw=0.6)
    ax[1, 0].set(xlabel="crank revolutions", ylabel="force [N]", title="roller 1 pocket force")
    cx, cy = cage_orbit_um(result)
    c = 1e6 * result.params.guide_clearance
    phi = np.linspace(0, 2 * np.pi, 200)
    ax[1, 1].plot(c * np.cos(phi), c * np.sin(phi), "k--", lw=0.8, label="guide clearance")
    ax[1, 1].plot(cx, cy, lw=0.6, label="cage centre")
    ax[1, 1].set(xlabel="x [um]", ylabel="y [um]", title="cage centre (relative to outer ring)", aspect="equal")
    ax[1, 1].legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    save(fig, path)
    return path
