"""quenchsim: oil-quench simulation of steel bearing rings and bearing-analysis solvers.

The facade::

    import quenchsim as qs
    case = qs.load_case("cases/crb_outer_ring.toml", condition="1")   # typed, checked case
    result = qs.run(case, out="runs/crb_1")                            # writes the run folder
    run = qs.load_results("runs/crb_1")                                # summary, probes, traverses, ...
    run.summary["dimensions_mm"]["change"]

The submodules are imported on first use, so ``import quenchsim`` stays cheap.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

__version__ = "0.1.0"

if TYPE_CHECKING:
    from quenchsim.case import Case
    from quenchsim.pipeline import RunResult
    from quenchsim.results import RunResults

__all__ = ["load_case", "run", "load_results", "__version__"]


def load_case(path: str | Path, condition: str | None = None, overrides: dict[str, Any] | None = None) -> "Case":
    """Load and check a case file (see :mod:`quenchsim.case`); ``overrides`` are dotted paths -> values."""
    from quenchsim.case import load_case as _load_case

    return _load_case(path, condition, overrides)


def run(case: "Case", out: str | Path, progress: bool = True, resume: bool = False, force: bool = False
        ) -> "RunResult":
    """Run a case into the folder ``out`` (see README "What a run writes"); ``resume=True`` continues the
    interrupted run of the same case in ``out`` from its checkpoint. A new run replaces an earlier run's outputs
    in ``out``; a non-empty folder that is not a run folder is refused unless ``force=True``."""
    from quenchsim.pipeline import run as _run

    return _run(case, out, progress=progress, resume=resume, force=force)


def load_results(run_dir: str | Path) -> "RunResults":
    """Read a run folder back (see :mod:`quenchsim.results`)."""
    from quenchsim.results import load

    return load(run_dir)
