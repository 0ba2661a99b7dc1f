"""Figures of the mode II toolkit (quenchsim.figures, no pyplot state): the specimen fits, the critical crack
size against contact pressure, and the effective shear along one pass."""

from __future__ import annotations

import pathlib
from collections.abc import Sequence

import numpy as np

from quenchsim.bearings.mode2 import sif, subsurface
from quenchsim.figures import save, subplots


def fits(path: pathlib.Path) -> pathlib.Path:
    """F_II and F_I of the specimen over a/W in [0, 0.7]."""
    xi = np.linspace(0.0, 0.7, 141)
    fig, ax = subplots(figsize=(6, 3.6))
    ax.plot(xi, sif.F_II(xi), label="F_II (direct shear)")
    ax.plot(xi, sif.F_I(xi), label="F_I (bending moment)")
    ax.axhline(1.1215 * np.sqrt(np.pi), color="0.5", ls=":", label="edge crack 1.1215 sqrt(pi)")
    ax.set_xlabel("a / W")
    ax.set_ylabel("F (K = F sigma sqrt(a))")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save(fig, path)


def critical_size(pressures_Pa: np.ndarray, curves: dict[str, np.ndarray], printed: Sequence[tuple[float, float]],
                  path: pathlib.Path) -> pathlib.Path:
    """Critical crack diameter (um) against p_max (GPa), log-log, one curve per contact shape, printed points."""
    fig, ax = subplots(figsize=(6, 4))
    for label, d in curves.items():
        ax.loglog(pressures_Pa / 1e9, d * 1e6, label=label)
    ax.loglog([p / 1e9 for p, _ in printed], [d * 1e6 for _, d in printed], "ko", label="paper, Fig. 14 points")
    ax.set_xlabel("maximum contact pressure (GPa)")
    ax.set_ylabel("critical crack diameter 2a (um)")
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return save(fig, path)


def pass_shear(ellipticities: Sequence[float], friction: float, path: pathlib.Path) -> pathlib.Path:
    """tau_zx and the effective shear at z = b/2 along a pass (x / b), line and elliptical contacts, per p0."""
    x = np.linspace(-3.0, 3.0, 301)
    fig, ax = subplots(figsize=(6, 3.8))
    line = subsurface.line_contact_stresses(x, 0.5, 1.0, 1.0)
    ax.plot(x, line.tau_zx_Pa, "k-", lw=0.8, label="tau_zx, line")
    ax.plot(x, subsurface.effective_shear_range(line, friction)[1], "k--", label="effective, line")
    for k in ellipticities:
        st = subsurface.elliptical_contact_stresses(x, 0.5, 1.0, k, 1.0)
        ax.plot(x, subsurface.effective_shear_range(st, friction)[1], label=f"effective, ellipse k = {k:g}")
    ax.axhline(0.0, color="0.5", lw=0.5)
    ax.set_xlabel("x / b (contact centre to crack)")
    ax.set_ylabel("shear / p_max")
    ax.legend(fontsize=7)
    fig.tight_layout()
    return save(fig, path)

