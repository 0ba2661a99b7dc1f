"""The design study's plots: the Pareto front of two objectives, and each quantity's map over two variables."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from matplotlib.tri import Triangulation


def pareto_plot(all_xy: np.ndarray, feasible: np.ndarray, front_xy: np.ndarray, best_xy: np.ndarray | None,
                labels: Sequence[str], title: str, path: Path) -> Path:
    """Every ok trial in the plane of two objectives (feasible filled, infeasible hollow), the front joined, the
    recommended point starred."""
    fig = Figure(figsize=(6.0, 4.5))
    ax = fig.subplots()
    ax.scatter(all_xy[feasible, 0], all_xy[feasible, 1], s=18, c="tab:blue", label="trial (meets the constraints)")
    if np.any(~feasible):
        ax.scatter(all_xy[~feasible, 0], all_xy[~feasible, 1], s=18, facecolors="none", edgecolors="tab:gray",
                   label="trial (misses a constraint)")
    if len(front_xy):
        order = np.argsort(front_xy[:, 0])
        ax.plot(front_xy[order, 0], front_xy[order, 1], "r.-", lw=1.2, label="Pareto front")
    if best_xy is not None:
        ax.plot(*best_xy, "k*", ms=14, label="recommended")
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7)
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return path


def map_plot(x: np.ndarray, y: np.ndarray, z: np.ndarray, feasible: np.ndarray, best: tuple[float, float] | None,
             labels: Sequence[str], title: str, path: Path) -> Path:
    """A quantity over two variables: filled contours of the trials' values (linear on their Delaunay
    triangulation: no model between them), the trials marked (hollow: misses a constraint), the recommended star."""
    fig = Figure(figsize=(6.0, 4.5))
    ax = fig.subplots()
    if len(x) >= 3 and np.ptp(x) > 0 and np.ptp(y) > 0:
        try:
            cs = ax.tricontourf(Triangulation(x, y), z, levels=12, cmap="viridis")
            fig.colorbar(cs, ax=ax, label=labels[2])
        except (ValueError, RuntimeError):   # points on a line: no triangulation, the markers alone
            pass
    ax.scatter(x[feasible], y[feasible], s=14, c="w", edgecolors="k", lw=0.6, label="trial")
    if np.any(~feasible):
        ax.scatter(x[~feasible], y[~feasible], s=14, c="none", edgecolors="r", lw=0.8, label="misses a constraint")
    if best is not None:
        ax.plot(*best, "r*", ms=14, label="recommended")
    ax.set_xlabel(labels[0])
    ax.set_ylabel(labels[1])
    ax.legend(fontsize=7)
    ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    return path
