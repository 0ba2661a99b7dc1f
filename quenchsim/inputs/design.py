"""A design study file (``quenchsim optimise STUDY.toml``): the case, the variables, the objectives, the constraints,
the cheap fidelity and the confirmation, declared once; what a study does and its full example:
:mod:`quenchsim.design.spec`."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from quenchsim.errors import require
from quenchsim.inputs.declare import REQUIRED, Table, quantity

SAMPLERS = ("tpe", "nsga2", "random")


@dataclass(frozen=True, kw_only=True)
class StudyHead(Table):
    """``[study]``: the case and the optimiser's budget."""

    case: str = quantity(REQUIRED, doc="the case file, relative to the study file",
                         allowed="required: the case file (relative to the study file)")
    condition: str | int | None = quantity(None, doc="the base condition (a case with conditions needs one)")
    name: str | None = quantity(None, doc="the study's name (default: the file stem)")
    trials: int = quantity(24, ge=1, doc="cheap-fidelity runs the optimiser asks for",
                           allowed="must be an integer >= 1")
    startup: int | None = quantity(None, ge=0, doc="of them, the first ones: a Latin hypercube (default min(8, "
                                   "trials))", allowed="must be an integer >= 0")
    seed: int = quantity(0, ge=0, doc="random seed", allowed="must be an integer >= 0")
    sampler: str = quantity("tpe", choices=SAMPLERS, doc="the optimiser's sampler")
    map: tuple[str, ...] | None = quantity(None, doc="the maps' two variables (default: the first two numeric)")

    def check(self) -> None:
        startup = self.first_trials
        require(startup <= self.trials, "startup", startup, f"must be <= study.trials ({self.trials})")

    @property
    def first_trials(self) -> int:
        """The Latin-hypercube trials."""
        return min(8, self.trials) if self.startup is None else self.startup


@dataclass(frozen=True, kw_only=True)
class VariableTable(Table):
    """A variable's table: a real range ``{ low, high }`` (``log``: sampled on a log scale; ``integer``: whole
    numbers; ``step``: rounded to steps) or ``{ choices = [...] }`` (two or more different values)."""

    low: float | None = quantity(None, doc="lower bound")
    high: float | None = quantity(None, doc="upper bound")
    log: bool = quantity(False, doc="sample on a log scale (low > 0)")
    integer: bool = quantity(False, doc="whole numbers only")
    step: float | None = quantity(None, gt=0.0, doc="round to multiples of step from low")
    choices: tuple[Any, ...] | None = quantity(None, doc="the values to choose from (instead of a range)")

    def check(self) -> None:
        if self.choices is not None:
            require(len(self.choices) >= 2 and len(set(map(repr, self.choices))) == len(self.choices), "choices",
                    list(self.choices), "must be a list of two or more different values")
            given = set(self._given) - {"choices"}
            require(not given, "", sorted(given), "a choice variable takes only 'choices'")
            return
        require(self.low is not None, "low", None, "must be a finite number")
        require(self.high is not None, "high", None, "must be a finite number")
        low, high = float(self.low or 0.0), float(self.high or 0.0)
        require(low < high, "", [low, high], "low must be below high")
        require(not self.log or low > 0, "low", low, "must be > 0 for a log-scaled variable")
        require(self.step is None or not self.log, "", dict(self._given), "a stepped variable cannot be log-scaled")
        require(not self.integer or (low.is_integer() and high.is_integer()), "", [low, high],
                "an integer variable needs whole-number bounds")


@dataclass(frozen=True, kw_only=True)
class ObjectiveTarget(Table):
    """An objective ``{ target = NUMBER }``: bring the quantity to the number."""

    target: float = quantity(REQUIRED, doc="the value to reach")


@dataclass(frozen=True, kw_only=True)
class FidelityTable(Table):
    """``[fidelity]``: the cheap runs -- element size times ``mesh``, step limits times ``step`` -- and how closely
    each objective and constraint quantity must agree with the full chain there."""

    mesh: float = quantity(1.0, gt=0.0, doc="factor on the element sizes")
    step: float = quantity(1.0, gt=0.0, doc="factor on the step limits")
    tolerance: Mapping[str, Any] = quantity({}, doc="quantity -> tolerance, > 0 (dotted keys or nested tables)")

    @property
    def cheap(self) -> bool:
        return self.mesh != 1.0 or self.step != 1.0


@dataclass(frozen=True, kw_only=True)
class ConfirmTable(Table):
    """``[confirm]``: the full-chain runs after the search."""

    extra: int = quantity(0, ge=0, doc="full-chain runs of front points besides the recommended one",
                          allowed="must be an integer >= 0")
    uncertainty: int = quantity(0, ge=0, doc="N >= 2: bands from N runs (the posterior's, or the priors')",
                                allowed="must be an integer >= 0")
    posterior: str | None = quantity(None, doc="a `quenchsim calibrate` output folder (needs uncertainty >= 2)",
                                     allowed="must be a folder path")

    def check(self) -> None:
        require(self.uncertainty != 1, "uncertainty", 1, "must be 0 (no bands) or >= 2")
        require(self.posterior is None or self.uncertainty >= 2, "posterior", self.posterior,
                "needs confirm.uncertainty >= 2")


@dataclass(frozen=True, kw_only=True)
class StudyFile(Table):
    """A design study file."""

    UNKNOWN = "unknown table"

    study: StudyHead = quantity(REQUIRED, doc="the case and the budget")
    set: Mapping[str, Any] = quantity({}, doc="case keys fixed for every run (dotted, or nested tables)")
    variables: Mapping[str, Any] = quantity({}, doc="case keys the optimiser sets: [low, high] or a variable table")
    objectives: Mapping[str, Any] = quantity({}, doc="summary quantities: \"min\", \"max\" or { target = NUMBER }")
    constraints: tuple[str, ...] | Mapping[str, Any] = quantity((), doc="\"QUANTITY >= NUMBER\" or \"QUANTITY <= "
                                                               "NUMBER\" (a list, or a table of lists)")
    fidelity: FidelityTable = quantity(FidelityTable(), doc="the cheap runs")
    confirm: ConfirmTable = quantity(ConfirmTable(), doc="the full-chain runs")
