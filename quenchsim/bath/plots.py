"""Plots of the bath model: HTC(T_s) per boundary segment and the local oil speed along the outline.
matplotlib is imported inside the functions only."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from quenchsim.bath.htc import BoundaryHTC
from quenchsim.bath.segments import MAIN_SEGMENTS, perimeter_coordinate, segment_groups
from quenchsim.figures import save, subplots
from quenchsim.geometry.boundary import BoundaryPoints


def plot_htc(htc: BoundaryHTC, title: str, path: Path) -> Path:
    """Segment-mean HTC(T_s) with the min-max band of the segment's points."""

    fig, ax = subplots(figsize=(7.5, 4.5))
    for name, idx in segment_groups(htc).items():
        h = htc.h_W_m2K[idx]
        line, = ax.plot(htc.T_grid_C, h.mean(axis=0), label=name, lw=1.6 if name in MAIN_SEGMENTS else 0.9)
        ax.fill_between(htc.T_grid_C, h.min(axis=0), h.max(axis=0), color=line.get_color(), alpha=0.12)
    ax.set_xlabel("surface temperature (C)")
    ax.set_ylabel("HTC (W/m$^2$K)")
    ax.set_xlim(htc.T_grid_C[0], 900.0)
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    save(fig, path)
    return path


def plot_velocity(results: dict[str, tuple[BoundaryPoints, BoundaryHTC]], title: str, path: Path) -> Path:
    """Local oil speed along the outline (counter-clockwise from the bottom face) for several conditions."""

    fig, ax = subplots(figsize=(8.5, 4.0))
    spans: list[tuple[str, float, float]] = []
    for cond, (points, htc) in results.items():
        x, spans = perimeter_coordinate(points)
        order = np.argsort(x)
        ax.plot(x[order] * 1e3, htc.velocity_m_s[order], label=f"condition {cond}")
    for name, a, b in spans:
        ax.axvline(a * 1e3, color="0.8", lw=0.6)
        if name in MAIN_SEGMENTS:
            ax.text(0.5 * (a + b) * 1e3, ax.get_ylim()[1] * 0.95, name, ha="center", va="top", fontsize=8)
    ax.set_xlabel("position along the section outline, counter-clockwise from the bottom face (mm)")
    ax.set_ylabel("local oil speed (m/s)")
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    save(fig, path)
    return path


def plot_jet_response(new: dict, old: dict | None, title: str, path: Path) -> Path:
    """The bore's h against the ID jet speed and the OD's h against the OD jet speed at each surface temperature of
    the response tables (:func:`quenchsim.bath.segments.jet_response`; new model solid, ``old`` dashed)."""
    fig, axes = subplots(1, 2, figsize=(10.5, 4.2))
    for ax, side, seg in ((axes[0], "id", "bore"), (axes[1], "od", "od")):
        speeds = sorted(new[side], key=float)
        temps = [k for k in new[side][speeds[0]][seg] if k != "T_L"]
        for j, T in enumerate(temps):
            v = np.array([float(s) for s in speeds]) * 1e-3
            line, = ax.plot(v, [new[side][s][seg][T] for s in speeds], "-o", ms=3, color=f"C{j}", label=f"{T} C")
            if old is not None and all(s in old[side] for s in speeds):
                ax.plot(v, [old[side][s][seg][T] for s in speeds], "--", color=line.get_color(), lw=1.0)
        ax.set_xlabel(f"{side.upper()} jet exit speed (m/s)")
        ax.set_ylabel(f"{seg}: segment-mean HTC (W/m$^2$K)")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, title="surface T (solid new, dashed old)", title_fontsize=7)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    save(fig, path)
    return path
