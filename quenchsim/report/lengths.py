"""How a length in mm is written in every report and terminal table: fixed decimals, the same everywhere."""

from __future__ import annotations

import math
from typing import Any

LENGTH_DECIMALS = 3
"""Decimals of every length in mm in a report or terminal table (1 um: what a dimension is measured to; 4
significant figures showed a 218.3 mm bore before and after a 0.03 mm change as 218.3 -> 218.3)."""


def mm(value: Any) -> str:
    """A length in mm with :data:`LENGTH_DECIMALS` fixed decimals; a dash when missing, text as it is."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return str(value)
    return f"{value:.{LENGTH_DECIMALS}f}"


def is_length(key: str) -> bool:
    """Whether a dotted summary or case key holds a length in mm (a part ending in ``_mm``: ``dimensions_mm.change.id``,
    ``hardness.depth_mm.HRC58_bore_mid``, ``mesh.size_mm``; not ``..._mm_s`` or ``..._mm2``)."""
    return any(part.endswith("_mm") for part in key.split("."))
