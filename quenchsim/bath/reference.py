"""The documented nozzle layouts of the two reference rings (``reference_nozzles.toml``) as bath specs."""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

from quenchsim.case import deep_merge
from quenchsim.errors import InputError

REFERENCE_FILE = Path(__file__).with_name("reference_nozzles.toml")
CONDITIONS = {"case_A": ("1", "2", "3"), "case_B": ("4", "5", "6")}
RING_SECTIONS_MM = {  # ID (raceway diameter at mid-width for B), OD, width: quench_cases.md
    "case_A": (218.3, 301.0, 173.0),
    "case_B": (427.0, 460.6, 118.5),
}


def reference_bath_spec(case: str, condition: str | int) -> dict[str, Any]:
    """The [quench.bath] table of reference ``case`` ("case_A" | "case_B") under ``condition`` (1-6)."""
    with REFERENCE_FILE.open("rb") as fh:
        data = tomllib.load(fh)
    if case not in CONDITIONS:
        raise InputError("case", case, f"must be one of {', '.join(CONDITIONS)}")
    cond = str(condition)
    if cond not in CONDITIONS[case]:
        raise InputError("condition", condition, f"{case} has conditions {', '.join(CONDITIONS[case])}")
    spec = data[case]["quench"]["bath"]
    override = data[case].get("conditions", {}).get(cond, {}).get("quench", {}).get("bath", {})
    return deep_merge(spec, override)


def case_of_condition(condition: str | int) -> str:
    """The reference case a condition number belongs to."""
    for case, conds in CONDITIONS.items():
        if str(condition) in conds:
            return case
    raise InputError("condition", condition, "reference conditions are 1-6")
