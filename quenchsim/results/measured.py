"""A case's measured dimensions (its ``[measured]`` table) and the run's comparison with them.

``[measured]`` holds ``before_mm`` and ``after_mm`` (``id``, ``od``, ``width``, ... in mm), a ``source`` and, when the
measurement belongs to one condition of a case with several, ``condition = "NAME"``: runs of other conditions are
not compared with it (ring A's Table 3 is condition 1's).
"""

from __future__ import annotations

from typing import Any

__all__ = ["measured_dimensions", "compare_with_measured"]


def measured_dimensions(case: dict[str, Any] | None, condition: str | None = None) -> dict[str, dict[str, float]]:
    """``{"before": {...}, "after": {...}, "change": {...}}`` in mm from the case's ``[measured]`` table; empty
    tables when there is none or when it names another condition than ``condition``."""
    measured = (case or {}).get("measured", {})
    own = measured.get("condition")
    if own is not None and condition is not None and str(own) != str(condition):
        measured = {}
    before = {k: float(v) for k, v in measured.get("before_mm", {}).items() if isinstance(v, (int, float))}
    after = {k: float(v) for k, v in measured.get("after_mm", {}).items() if isinstance(v, (int, float))}
    change = {k: after[k] - before[k] for k in after if k in before}
    return {"before": before, "after": after, "change": change}


def compare_with_measured(dimensions_mm: dict[str, Any] | None, case: dict[str, Any] | None,
                          condition: str | None) -> dict[str, Any] | None:
    """The run's dimension changes against the measured ones (mm): ``{"source", "change": {k: {"simulated",
    "measured", "simulated_minus_measured"}}}`` for every dimension both have; None when nothing compares.

    >>> case = {"measured": {"before_mm": {"id": 218.3}, "after_mm": {"id": 217.9}, "condition": "1"}}
    >>> compare_with_measured({"change": {"id": 0.032}}, case, "1")["change"]["id"]["simulated_minus_measured"]
    0.432
    >>> compare_with_measured({"change": {"id": 0.032}}, case, "2") is None
    True
    """
    meas = measured_dimensions(case, condition)
    sim = (dimensions_mm or {}).get("change", {})
    rows = {k: {"simulated": float(sim[k]), "measured": round(meas["change"][k], 9),
                "simulated_minus_measured": round(float(sim[k]) - meas["change"][k], 9)}
            for k in meas["change"] if k in sim}
    if not rows:
        return None
    return {"source": str((case or {}).get("measured", {}).get("source", "")), "change": rows}
