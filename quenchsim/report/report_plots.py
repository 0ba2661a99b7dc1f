"""The plots of the run/sweep report, each returned as PNG bytes (matplotlib figures without pyplot, so
importing this module selects no backend and leaves the user's matplotlib state alone).

Sections are drawn in the r-z plane in mm (the VTK files hold x = r, y = z in metres).
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from typing import Any

import numpy as np
from matplotlib.figure import Figure
from matplotlib.tri import Triangulation

from quenchsim.figures import png_bytes, subplots
from quenchsim.results import Frame

DISTORTION_SCALE = 10.0
"""Displacements are drawn magnified by this factor over the pre-quench outline."""
DPI = 100


def _png(fig: Figure) -> bytes:
    return png_bytes(fig, DPI)


def cooling_curves(time_s: np.ndarray, temperatures_C: dict[str, np.ndarray], title: str) -> bytes:
    """Temperature against time at every probe, linear and logarithmic time axes side by side."""
    fig, axes = subplots(1, 2, figsize=(11.0, 4.2))
    t = np.asarray(time_s)
    for name, T in temperatures_C.items():
        axes[0].plot(t, T, label=name)
        axes[1].plot(np.where(t > 0, t, np.nan), T, label=name)
    axes[1].set_xscale("log")
    for ax in axes:
        ax.set_xlabel("time (s)")
        ax.set_ylabel("temperature (C)")
        ax.grid(True, which="both", lw=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Cooling curves at the probes: {title}")
    fig.tight_layout()
    return _png(fig)


def field_maps(frame: Frame, fields: Sequence[tuple[str, str, str, float | None, float | None]], title: str) -> bytes:
    """One tripcolor map per ``(point-data name, label, colormap, vmin, vmax)`` of the last frame."""
    tri = Triangulation(frame.points[:, 0] * 1e3, frame.points[:, 1] * 1e3, frame.triangles)
    width = np.ptp(tri.x) or 1.0
    height = np.ptp(tri.y) or 1.0
    panel_w = 2.6
    panel_h = float(np.clip(panel_w * height / width, 2.5, 7.5))
    fig, axes = subplots(1, len(fields), figsize=(panel_w * len(fields) + 0.6, panel_h + 1.2), squeeze=False)
    for ax, (name, label, cmap, vmin, vmax) in zip(axes[0], fields):
        values = frame.point_data[name]
        pc = ax.tripcolor(tri, values, shading="gouraud", cmap=cmap, vmin=vmin, vmax=vmax)
        ax.set_aspect("equal")
        ax.set_title(label, fontsize=9)
        ax.set_xlabel("r (mm)", fontsize=8)
        ax.tick_params(labelsize=7)
        fig.colorbar(pc, ax=ax, shrink=0.8)
    axes[0][0].set_ylabel("z (mm)", fontsize=8)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return _png(fig)


def hardness_traverse(depth_mm: np.ndarray, curves: dict[str, np.ndarray], threshold_HRC: float | None,
                      title: str) -> bytes:
    """HRC against depth below the surface at mid-width, one curve per surface."""
    fig, ax = subplots(figsize=(7.0, 4.2))
    for label, hrc in curves.items():
        ax.plot(depth_mm, hrc, label=label)
    if threshold_HRC is not None:
        ax.axhline(threshold_HRC, color="k", lw=0.8, ls="--", label=f"{threshold_HRC:g} HRC")
    ax.set_xlabel("depth below the surface at mid-width (mm)")
    ax.set_ylabel("hardness (HRC)")
    ax.set_title(f"Hardness-depth traverse: {title}", fontsize=10)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _png(fig)


def distortion(r_before_mm: np.ndarray, z_before_mm: np.ndarray, r_after_mm: np.ndarray, z_after_mm: np.ndarray,
               title: str, source: str) -> bytes:
    """Left: the pre-quench section outline and the after-quench outline with the displacement x10.
    Right: the radial displacement of the bore and OD faces against height (taper, barrelling) in um."""
    def closed(a: np.ndarray) -> np.ndarray:
        return np.append(a, a[:1])

    r_mag = r_before_mm + DISTORTION_SCALE * (r_after_mm - r_before_mm)
    z_mag = z_before_mm + DISTORTION_SCALE * (z_after_mm - z_before_mm)
    height = np.ptp(z_before_mm) or 1.0
    width = np.ptp(r_before_mm) or 1.0
    fig, (ax, ax2) = subplots(1, 2, figsize=(10.0, float(np.clip(4.5 * height / width, 4.0, 8.0))),
                                  gridspec_kw={"width_ratios": [1.0, 1.3]})
    ax.plot(closed(r_before_mm), closed(z_before_mm), "k-", lw=1.0, label="before quench")
    ax.plot(closed(r_mag), closed(z_mag), "r-", lw=1.4, label=f"after quench, displacement x{DISTORTION_SCALE:g}")
    ax.set_aspect("equal")
    ax.set_xlabel("r (mm)")
    ax.set_ylabel("z (mm)")
    ax.set_title(f"Section outline ({source})", fontsize=9)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.12))
    tol = 1e-3 * width
    for face, r_face, style in (("bore", r_before_mm.min(), "b.-"), ("OD", r_before_mm.max(), "g.-")):
        on = np.abs(r_before_mm - r_face) < tol
        order = np.argsort(z_before_mm[on])
        ax2.plot(1e3 * (r_after_mm[on] - r_before_mm[on])[order], z_before_mm[on][order], style, ms=3,
                 label=f"{face} face")
    ax2.axvline(0.0, color="k", lw=0.6)
    ax2.set_xlabel("radial displacement after - before (um)")
    ax2.set_ylabel("z before quench (mm)")
    ax2.set_title("Radial displacement of the bore and OD faces", fontsize=9)
    ax2.grid(True, lw=0.3)
    ax2.legend(fontsize=8)
    fig.suptitle(f"Distortion: {title}", fontsize=10)
    fig.tight_layout()
    return _png(fig)


BUDGET_LABELS = {"free_strain": "free strain vs annealed", "thermal_plasticity": "thermal plasticity",
                 "transformation_plasticity": "transformation plasticity", "elastic_residue": "elastic residue"}
BUDGET_PANELS = {"id": "ID change (mm)", "od": "OD change (mm)", "width": "width change (mm)",
                 "area_mm2": "section area change (mm$^2$)"}


def distortion_budget(budget: dict[str, Any], title: str) -> bytes:
    """One bar chart per dimension of the ``distortion_budget_mm`` block of summary.json: a bar per part
    and the total (hatched)."""
    parts = [p for p in BUDGET_LABELS if p in budget.get("parts", {})]
    keys = [k for k in BUDGET_PANELS if k in budget.get("total", {})]
    fig, axes = subplots(1, len(keys), figsize=(3.0 * len(keys) + 0.6, 3.8), squeeze=False)
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:gray"]
    for ax, key in zip(axes[0], keys):
        values = [budget["parts"][p][key] for p in parts] + [budget["total"][key]]
        bars = ax.bar(range(len(values)), values, color=colours[:len(parts)] + ["white"], edgecolor="black", lw=0.6)
        bars[-1].set_hatch("//")
        ax.axhline(0.0, color="black", lw=0.6)
        ax.set_xticks(range(len(values)))
        ax.set_xticklabels([BUDGET_LABELS[p] for p in parts] + ["total"], rotation=40, ha="right", fontsize=7)
        ax.set_title(BUDGET_PANELS[key], fontsize=9)
        ax.tick_params(axis="y", labelsize=7)
        ax.grid(True, axis="y", lw=0.3)
    fig.suptitle(f"Distortion budget: {title}")
    fig.tight_layout()
    return _png(fig)


def stress_traverse(r_mm: np.ndarray, curves: dict[str, np.ndarray], title: str) -> bytes:
    """Residual stress against radius at mid-width (MPa)."""
    fig, ax = subplots(figsize=(7.0, 4.2))
    for label, values in curves.items():
        ax.plot(r_mm, values, label=label)
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel("r (mm), bore to OD at mid-width")
    ax.set_ylabel("residual stress (MPa)")
    ax.set_title(f"Residual stress traverse: {title}", fontsize=10)
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _png(fig)


def compare_curves(panels: dict[str, dict[str, tuple[np.ndarray, np.ndarray]]], xlabel: str, ylabel: str,
                   title: str, log_x: bool = False) -> bytes:
    """One panel per key of ``panels``; in each, one curve ``label: (x, y)`` per run."""
    n = len(panels)
    ncol = min(3, n)
    nrow = -(-n // ncol)
    fig, axes = subplots(nrow, ncol, figsize=(4.4 * ncol, 3.4 * nrow), squeeze=False)
    for ax, (name, curves) in zip(axes.ravel(), panels.items()):
        for label, (x, y) in curves.items():
            ax.plot(np.where(x > 0, x, np.nan) if log_x else x, y, label=label)
        if log_x:
            ax.set_xscale("log")
        ax.set_title(name, fontsize=9)
        ax.set_xlabel(xlabel, fontsize=8)
        ax.set_ylabel(ylabel, fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="both", lw=0.3)
    for ax in axes.ravel()[n:]:
        ax.set_visible(False)
    axes[0][0].legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return _png(fig)


def responses(rows: list[dict[str, Any]], x: str, group_by: list[str], outputs: list[str], title: str) -> bytes:
    """Each output against swept input ``x``; one line per combination of the other swept inputs."""
    n = len(outputs)
    ncol = min(3, n)
    nrow = -(-n // ncol)
    fig, axes = subplots(nrow, ncol, figsize=(4.2 * ncol, 3.3 * nrow), squeeze=False)
    groups = sorted({tuple(r.get(g) for g in group_by) for r in rows},
                    key=lambda k: tuple((0, v, "") if isinstance(v, (int, float)) else (1, 0, str(v)) for v in k))
    markers = itertools.cycle("os^vD<>")
    styles = {g: next(markers) for g in groups}
    for ax, out in zip(axes.ravel(), outputs):
        for g in groups:
            pts = sorted((r[x], r[out]) for r in rows
                         if tuple(r.get(k) for k in group_by) == g and isinstance(r.get(x), (int, float))
                         and isinstance(r.get(out), (int, float)))
            if not pts:
                continue
            label = ", ".join(f"{k.split('.')[-1]}={v:g}" if isinstance(v, float) else f"{k.split('.')[-1]}={v}"
                              for k, v in zip(group_by, g)) or None
            ax.plot(*zip(*pts), marker=styles[g], label=label)
        ax.set_xlabel(x.split(".")[-1], fontsize=8)
        ax.set_title(out, fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, lw=0.3)
    for ax in axes.ravel()[n:]:
        ax.set_visible(False)
    if group_by:
        axes[0][0].legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    return _png(fig)
