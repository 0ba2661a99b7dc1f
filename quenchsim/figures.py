"""Matplotlib figures without pyplot: no backend is selected and no global figure state is touched, so a
module that plots can be imported anywhere (a Dask worker, a notebook, a headless CI) at no cost.

    fig, ax = subplots(figsize=(6, 4)); ax.plot(x, y); save(fig, "out.png")
"""

from __future__ import annotations

import io
from pathlib import Path
from typing import Any


def subplots(*grid: int, figsize: tuple[float, float], **kwargs: Any) -> tuple[Any, Any]:
    """A new figure and its axes, as ``matplotlib.pyplot.subplots`` would return them."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize)
    return fig, fig.subplots(*grid, **kwargs)


def save(fig: Any, path: str | Path, dpi: int = 110) -> Path:
    """Write the figure as an image (format from the file name)."""
    fig.savefig(path, dpi=dpi)
    return Path(path)


def png_bytes(fig: Any, dpi: int = 100) -> bytes:
    """The figure as PNG bytes."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return buf.getvalue()
