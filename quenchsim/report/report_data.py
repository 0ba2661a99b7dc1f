"""What the reports read besides a run folder (:func:`quenchsim.results.load`): sweep folders and the
case's measured dimensions."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from quenchsim.materials.properties import PHASES

__all__ = ["PHASES", "is_sweep_dir", "measured_dimensions"]


def is_sweep_dir(path: Path) -> bool:
    """A sweep output directory: results.csv plus sweep.json (written by quenchsim.sweep)."""
    return (path / "results.csv").is_file() and (path / "sweep.json").is_file()


def measured_dimensions(case: dict[str, Any] | None) -> dict[str, dict[str, float]]:
    """``{"before": {...}, "after": {...}, "change": {...}}`` from the case's ``[measured]`` table (mm)."""
    measured = (case or {}).get("measured", {})
    before = {k: float(v) for k, v in measured.get("before_mm", {}).items() if isinstance(v, (int, float))}
    after = {k: float(v) for k, v in measured.get("after_mm", {}).items() if isinstance(v, (int, float))}
    change = {k: after[k] - before[k] for k in after if k in before}
    return {"before": before, "after": after, "change": change}
