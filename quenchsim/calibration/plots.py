"""The corner plot of a posterior (matplotlib through :mod:`quenchsim.figures`, no pyplot)."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.calibration.inputs import FreeInput
from quenchsim.figures import save, subplots


def _factor_ticks(axis: Any, bounds: tuple[float, float]) -> None:
    """Ticks at the prior's bounds and at 1 (the data file's value), plain numbers, no minor labels."""
    from matplotlib.ticker import FixedLocator, NullFormatter, NullLocator

    ticks = sorted({bounds[0], 1.0, bounds[1]} if bounds[0] < 1.0 < bounds[1] else set(bounds))
    axis.set_major_locator(FixedLocator(ticks))
    axis.set_major_formatter(lambda x, _pos: f"{x:.3g}")
    axis.set_minor_locator(NullLocator())
    axis.set_minor_formatter(NullFormatter())


def corner_plot(factors: np.ndarray, inputs: Sequence[FreeInput], path: Path,
                truth: Sequence[float] | None = None) -> Path:
    """Histograms of each input's factor on the diagonal, pairwise sample clouds below it; axes span the prior
    (log scale), the nominal factor 1 dashed, ``truth`` (a synthetic problem's inputs) in red."""
    d = len(inputs)
    fig, axes = subplots(d, d, figsize=(2.3 * d + 0.6, 2.3 * d + 0.6), squeeze=False)
    bins = [np.geomspace(*inp.factor_bounds, 31) for inp in inputs]
    for i in range(d):
        for j in range(d):
            ax = axes[i, j]
            if j > i:
                ax.set_axis_off()
                continue
            ax.set_xscale("log")
            ax.set_xlim(*inputs[j].factor_bounds)
            if i == j:
                ax.hist(factors[:, j], bins=bins[j], color="0.4")
                ax.set_yticks([])
            else:
                ax.set_yscale("log")
                ax.set_ylim(*inputs[i].factor_bounds)
                ax.plot(factors[:, j], factors[:, i], ".", ms=1.0, alpha=0.25, color="0.2")
                ax.axhline(1.0, ls="--", lw=0.6, color="tab:blue")
                if truth is not None:
                    ax.axhline(truth[i], lw=0.8, color="tab:red")
            ax.axvline(1.0, ls="--", lw=0.6, color="tab:blue")
            if truth is not None:
                ax.axvline(truth[j], lw=0.8, color="tab:red")
            _factor_ticks(ax.xaxis, inputs[j].factor_bounds)
            if i != j:
                _factor_ticks(ax.yaxis, inputs[i].factor_bounds)
            if i == d - 1:
                ax.set_xlabel(f"{inputs[j].label}\n(factor)", fontsize=8)
            if j == 0 and i > 0:
                ax.set_ylabel(f"{inputs[i].label}\n(factor)", fontsize=8)
            ax.tick_params(labelsize=7)
    fig.suptitle("posterior of the free inputs (factors on the data files' values; axes = prior range)", fontsize=9)
    fig.tight_layout()
    return save(fig, path)
