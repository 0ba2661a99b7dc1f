"""Figures of the gas journal bearing module (matplotlib, Agg backend): pressure field, load and
attitude curves, orbits, stability trials, grid convergence, narrow-groove limit and solver timings."""

from __future__ import annotations

import pathlib
from collections.abc import Sequence

import numpy as np

from quenchsim.bearings.gas_journal.geometry import Grid
from quenchsim.figures import save, subplots


def _save(fig, path: pathlib.Path) -> pathlib.Path:
    fig.tight_layout()
    save(fig, path)
    return path


def pressure_field(grid: Grid, p: np.ndarray, title: str, path: pathlib.Path) -> pathlib.Path:
    """P over the sleeve angle and Z (half bearing, end at Z = 0, mid-plane at the top)."""
    jj, ii = np.meshgrid(np.arange(grid.n_eta + 1), np.arange(grid.n_xi + 1), indexing="ij")
    theta = np.degrees(grid.theta(ii.astype(float), jj.astype(float)))
    z = jj * grid.h_eta
    pp = np.concatenate([p, p[:, :1]], axis=1)
    fig, ax = subplots(figsize=(8, 3.2))
    mesh = ax.pcolormesh(theta, z, pp, shading="gouraud", cmap="viridis")
    fig.colorbar(mesh, ax=ax, label="P = p / pa")
    ax.set_xlabel("theta (deg, grid frame; skewed grid lines follow the grooves)")
    ax.set_ylabel("Z = z / r")
    ax.set_title(title)
    return _save(fig, path)


def load_curves(curves: dict[float, tuple[np.ndarray, np.ndarray, np.ndarray]], raimondi: Sequence[tuple],
                path: pathlib.Path) -> pathlib.Path:
    """Load and attitude vs eccentricity per bearing number, with Raimondi's points."""
    fig, (a1, a2) = subplots(1, 2, figsize=(9, 3.6))
    for lam, (eps, load, att) in curves.items():
        line, = a1.plot(eps, load, label=f"Lambda = {lam:g}")
        a2.plot(eps, att, color=line.get_color())
        pts = [r for r in raimondi if r[0] == lam]
        a1.plot([r[1] for r in pts], [r[2] for r in pts], "o", color=line.get_color())
        a2.plot([r[1] for r in pts], [r[3] for r in pts], "o", color=line.get_color())
    a1.set_xlabel("eccentricity ratio")
    a1.set_ylabel("F = W / (pa L D)")
    a2.set_xlabel("eccentricity ratio")
    a2.set_ylabel("attitude angle (deg)")
    a1.legend()
    a1.set_title("plain bearing L/D = 1 (lines) vs Raimondi (dots)")
    return _save(fig, path)


def orbits(runs: Sequence[tuple[str, np.ndarray, np.ndarray]], path: pathlib.Path) -> pathlib.Path:
    """Rotor-centre orbits (displacement over clearance) with the clearance circle."""
    fig, ax = subplots(figsize=(5, 5))
    t = np.linspace(0, 2 * np.pi, 200)
    ax.plot(np.cos(t), np.sin(t), "k-", lw=0.8)
    for label, x, y in runs:
        ax.plot(x, y, lw=0.8, label=label)
        ax.plot(x[-1], y[-1], "k.")
    ax.set_aspect("equal")
    ax.set_xlabel("e_x / c")
    ax.set_ylabel("e_y / c")
    ax.legend(fontsize=7)
    return _save(fig, path)


def stability_trials(trials: Sequence[tuple[float, bool, float, float]], critical: float, title: str,
                     path: pathlib.Path) -> pathlib.Path:
    """Orbit growth rate vs mass parameter for every bisection trial (stability map at one Lambda); an
    orbit that touched down (infinite growth rate) is a red triangle at the top edge."""
    fig, ax = subplots(figsize=(6, 3.6))
    for mbar, stable, growth, _ in trials:
        if np.isinf(growth):
            ax.semilogx(mbar, 1.0, "^", color="tab:red", transform=ax.get_xaxis_transform(), clip_on=False)
        else:
            ax.semilogx(mbar, growth, "o", color="tab:green" if stable else "tab:red")
    ax.axvline(critical, color="k", ls="--", label=f"critical Mbar = {critical:.3g}")
    ax.axhline(0.0, color="gray", lw=0.8)
    ax.set_xlabel("mass parameter Mbar")
    ax.set_ylabel("orbit growth rate (1 / T)")
    ax.set_title(title)
    ax.legend()
    return _save(fig, path)


def convergence(series: dict[str, tuple[np.ndarray, np.ndarray]], xlabel: str, ylabel: str, title: str,
                path: pathlib.Path, loglog: bool = True) -> pathlib.Path:
    """Generic convergence plot: one line per series."""
    fig, ax = subplots(figsize=(6, 3.8))
    for label, (x, y) in series.items():
        (ax.loglog if loglog else ax.plot)(x, y, "o-", label=label)
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    return _save(fig, path)


def dynamic_coefficients(gammas: np.ndarray, stiffness: np.ndarray, damping: np.ndarray, title: str,
                         path: pathlib.Path) -> pathlib.Path:
    """Stiffness and damping (shape (n, 2, 2)) against the whirl ratio, one line per entry xx, xy, yx, yy."""
    fig, (a1, a2) = subplots(1, 2, figsize=(9, 3.6))
    for i, j, name in ((0, 0, "xx"), (0, 1, "xy"), (1, 0, "yx"), (1, 1, "yy")):
        a1.plot(gammas, stiffness[:, i, j], label=f"K_{name}")
        a2.plot(gammas, damping[:, i, j], label=f"C_{name}")
    for ax, name in ((a1, "K = k c / (pa L D)"), (a2, "C = d omega c / (pa L D)")):
        ax.axhline(0.0, color="gray", lw=0.8)
        ax.set_xlabel("whirl ratio (whirl frequency / rotor speed)")
        ax.set_ylabel(name)
        ax.legend(fontsize=7)
    a1.set_title(title, fontsize=9)
    return _save(fig, path)


def growth_rates(panels: Sequence[tuple[str, np.ndarray, np.ndarray, Sequence[tuple[float, float]]]],
                 path: pathlib.Path) -> pathlib.Path:
    """Per panel: the linear growth rate against Mbar (line) and the orbits' measured growth rates (dots)."""
    fig, axes = subplots(1, len(panels), figsize=(4.2 * len(panels), 3.6))
    for ax, (title, mbar, growth, points) in zip(np.atleast_1d(axes), panels):
        ax.semilogx(mbar, growth, "-", color="tab:blue", label="linear (Lund)")
        finite = [(m, g) for m, g in points if np.isfinite(g)]
        ax.semilogx([m for m, _ in finite], [g for _, g in finite], "o", color="tab:red", label="orbits")
        ax.axhline(0.0, color="gray", lw=0.8)
        ax.set_xlabel("mass parameter Mbar")
        ax.set_ylabel("whirl growth rate (1 / T)")
        ax.set_title(title, fontsize=9)
        ax.legend(fontsize=7)
    return _save(fig, path)


def threshold_map(bearing_numbers: np.ndarray, by_level: dict[int, np.ndarray], estimate: np.ndarray,
                  error: np.ndarray, title: str, path: pathlib.Path) -> pathlib.Path:
    """Critical Mbar against Lambda (log-log): one line per grid level and the grid-converged estimate with its
    grid error as error bars (stable below the curve, whirl above)."""
    fig, ax = subplots(1, 1, figsize=(6.0, 4.0))
    for level, values in sorted(by_level.items()):
        ax.loglog(bearing_numbers, values, "-", lw=0.8, alpha=0.7, label=f"linear, level {level}")
    ok = np.isfinite(estimate)
    ax.errorbar(bearing_numbers[ok], estimate[ok], yerr=np.where(np.isfinite(error[ok]), error[ok], 0.0), fmt="o-",
                color="k", capsize=3, label="grid-converged estimate (Richardson) +- grid error")
    ax.set_xlabel("bearing number Lambda")
    ax.set_ylabel("critical mass parameter Mbar")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=7)
    return _save(fig, path)
