"""What the reports read besides a run folder (:func:`quenchsim.results.load`): sweep folders and the
case's measured dimensions (:mod:`quenchsim.results.measured`)."""

from __future__ import annotations

from pathlib import Path

from quenchsim.materials.properties import PHASES
from quenchsim.results.measured import measured_dimensions

__all__ = ["PHASES", "is_sweep_dir", "measured_dimensions"]


def is_sweep_dir(path: Path) -> bool:
    """A sweep output directory: results.csv plus sweep.json (written by quenchsim.sweep)."""
    return (path / "results.csv").is_file() and (path / "sweep.json").is_file()


