"""A validation study's targets file (``validation/<area>/<study>/targets.toml``): the published or measured values
its metrics are checked against, each with its source and role, declared once."""

from __future__ import annotations

import math
from dataclasses import dataclass

from quenchsim.errors import InputError, require
from quenchsim.inputs.declare import REQUIRED, Table, quantity, resolved

STATUSES = ("open", "reference")
ROLES = ("validation", "calibration", "verification")
FORMS = (("value", "tolerance"), ("value", "rel_tolerance"), ("min", "max"))
"""The forms of a target's band (besides ``min`` or ``max`` alone, and a reference's bare ``value``)."""


@dataclass(frozen=True, kw_only=True)
class Target(Table):
    """``[[targets]]``: one published or measured value of a study. It has exactly one form -- value + tolerance,
    value + rel_tolerance, or min and/or max -- except ``status = "reference"`` (a value without tolerance); an open
    target (a known miss) says why."""

    UNKNOWN = "unknown keys"

    metric: str = quantity(REQUIRED, doc="the name of a metric the study returns (dotted)",
                           allowed="must name a metric the study returns")
    source: str = quantity(REQUIRED, doc="where the value comes from", allowed="every target needs a non-empty source")
    unit: str = quantity("", doc="unit shown on the page")
    value: float | None = quantity(None, doc="the target value")
    tolerance: float | None = quantity(None, ge=0.0, doc="accepted +- around value")
    rel_tolerance: float | None = quantity(None, ge=0.0, doc="accepted +- around value, a fraction of it")
    min: float | None = quantity(None, doc="lower bound")
    max: float | None = quantity(None, doc="upper bound")
    description: str = quantity("", doc="what the value is")
    status: str = quantity("", doc="\"open\" (a known miss, with a reason) or \"reference\" (no band)")
    reason: str = quantity("", doc="why an open target is open")
    role: str = quantity("validation", choices=ROLES, doc="what the value does for the model")

    study: str = resolved("")
    """The study (``area/name``) whose targets file holds it."""

    def check(self) -> None:
        require(self.metric != "", "metric", self.metric, "must name a metric the study returns")
        require(self.source.strip() != "", "source", self.source, "every target needs a non-empty source")
        require(self.status in ("", *STATUSES), "status", self.status, f"one of {', '.join(STATUSES)} (or absent)")
        require(self.status != "open" or self.reason.strip() != "", "reason", self.reason,
                "an open target says why it is open")
        given = {k for k in ("value", "tolerance", "rel_tolerance", "min", "max") if getattr(self, k) is not None}
        if self.status == "reference":
            if given != {"value"}:
                raise InputError("", sorted(given), "a reference target has a value and no tolerance")
            return
        forms = [f for f in FORMS if set(f) <= given] + [(k,) for k in ("min", "max") if given == {k}]
        if len(forms) != 1 or given != set(forms[0]):
            raise InputError("", sorted(given), "give value + tolerance, value + rel_tolerance, or min/max")

    def band(self) -> tuple[float, float] | None:
        """The accepted interval, or None for a reference value."""
        if self.value is not None and self.tolerance is not None:
            return self.value - self.tolerance, self.value + self.tolerance
        if self.value is not None and self.rel_tolerance is not None:
            half = abs(self.value) * self.rel_tolerance
            return self.value - half, self.value + half
        if self.min is not None or self.max is not None:
            return (-math.inf if self.min is None else self.min, math.inf if self.max is None else self.max)
        return None

    def describe(self) -> str:
        """The target as printed on a page: ``0.75 +- 0.08``, ``218.3 +- 2 %``, ``>= 3``, ``60-90``."""
        unit = f" {self.unit}" if self.unit else ""
        if self.value is not None and self.tolerance is not None:
            return f"{self.value:g} +- {self.tolerance:g}{unit}"
        if self.value is not None and self.rel_tolerance is not None:
            return f"{self.value:g}{unit} +- {100 * self.rel_tolerance:g} %"
        if self.min is not None and self.max is not None:
            return f"{self.min:g} to {self.max:g}{unit}"
        if self.min is not None:
            return f">= {self.min:g}{unit}"
        if self.max is not None:
            return f"<= {self.max:g}{unit}"
        return f"{self.value:g}{unit}"


@dataclass(frozen=True, kw_only=True)
class TargetsFile(Table):
    """A targets file: only ``[[targets]]`` tables."""

    targets: tuple[Target, ...] = quantity((), doc="the targets")
