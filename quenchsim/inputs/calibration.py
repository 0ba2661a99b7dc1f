"""A calibration file (``quenchsim calibrate CAL.toml``), declared once: the free inputs, the case files, the
measured data of every kind, the predictions, the model-discrepancy groups and the design and sampler options. What
each does, with a complete example: :mod:`quenchsim.calibration.spec` and :mod:`quenchsim.calibration.data`, which
check what ties the tables together (cases, probes, quantities, data files) and build the observables."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, Literal

from quenchsim.errors import require
from quenchsim.inputs.declare import REQUIRED, Table
from quenchsim.inputs.declare import quantity as entry   # a key named "quantity" is declared here

RELATIONS = ("ratio", "difference")
TRAVERSE_SIDES = ("bore", "od")
SD = "one standard deviation, in the quantity's unit"


@dataclass(frozen=True, kw_only=True)
class CaseEntry(Table):
    """``[cases.LABEL]``: a case file of the calibration."""

    file: str = entry(REQUIRED, doc="the case file, relative to the calibration file",
                         allowed="required: a case file (relative to CAL.toml)")
    mesh: float = entry(1.0, gt=0.0, doc="element sizes x this for every design run",
                           allowed="element sizes x this")
    confirm_mesh: float | None = entry(None, gt=0.0, doc="the nominal and the calibrated run again at this mesh",
                                          allowed="element sizes x this for the nominal and calibrated runs")
    set: Mapping[str, Any] = entry({}, doc="case overrides for every run (dotted keys)",
                                      allowed="must be a table of dotted case fields")


@dataclass(frozen=True, kw_only=True)
class Datum(Table):
    """The keys of every ``[[measurements]]`` table."""

    UNKNOWN = "unknown key (the allowed keys depend on the kind)"

    case: str = entry(REQUIRED, doc="the label of its [cases] entry")
    condition: str | int | None = entry(None, doc="a condition of that case file")
    source: str = entry(REQUIRED, doc="where the measured value comes from",
                           allowed="required: where the measured value comes from")
    group: str | None = entry(None, doc="its model-discrepancy group (default: the quantity's table)")

    def check(self) -> None:
        require(self.source.strip() != "", "source", self.source, "required: where the measured value comes from")
        require(self.group is None or self.group != "", "group", self.group, "must be a group name")

    @property
    def condition_name(self) -> str | None:
        return None if self.condition is None else str(self.condition)


@dataclass(frozen=True, kw_only=True)
class RelatedDatum(Datum):
    """A number of summary.json, alone or compared with another condition's (``relative_to`` with ``relation``)."""

    quantity: str = entry(REQUIRED, doc="a dotted path of summary.json")
    uncertainty: float = entry(REQUIRED, gt=0.0, doc=SD, allowed=SD)
    relative_to: str | int | None = entry(None, doc="another condition: compare with its quantity")
    relation: str | None = entry(None, choices=RELATIONS, doc="\"ratio\" (this over that) or \"difference\"")

    def check(self) -> None:
        super().check()
        require(self.relation is None or self.relative_to is not None, "relation", self.relation,
                "needs relative_to = CONDITION")
        require(self.relative_to is None or self.relation is not None, "relation", self.relation,
                f"must be one of {', '.join(RELATIONS)}")


@dataclass(frozen=True, kw_only=True)
class ValueDatum(RelatedDatum):
    """``kind = "value"`` (the default): a measured number of summary.json."""

    kind: Literal["value"] = entry("value", doc="the kind of datum")
    value: float = entry(REQUIRED, doc="the measured number", allowed="required: the measured number")


@dataclass(frozen=True, kw_only=True)
class BoundDatum(RelatedDatum):
    """``kind = "bound"``: a statement such as "the centre is mostly pearlite", soft by ``uncertainty``."""

    kind: Literal["bound"] = entry(REQUIRED, doc="the kind of datum")
    min: float | None = entry(None, doc="lower bound")
    max: float | None = entry(None, doc="upper bound")

    def check(self) -> None:
        super().check()
        require(self.min is not None or self.max is not None, "min", None, "a bound needs min and/or max")
        require(self.min is None or self.max is None or self.min < self.max, "max", self.max,
                f"must exceed min = {self.min}")


@dataclass(frozen=True, kw_only=True)
class OrderDatum(Datum):
    """``kind = "order"``: the order of the probes in one probe quantity, fastest first."""

    kind: Literal["order"] = entry(REQUIRED, doc="the kind of datum")
    quantity: str = entry(REQUIRED, doc="a probe quantity such as t_to_500C_s or t_to_C_s.600")
    probes: tuple[str, ...] = entry(REQUIRED, doc="probe names, fastest first (>= 2)",
                                       allowed="must be a list of at least 2 probe names")
    tolerance: float = entry(REQUIRED, gt=0.0, doc="the standard deviation of each measured difference",
                                allowed="the standard deviation of each measured difference")


@dataclass(frozen=True, kw_only=True)
class CurveDatum(Datum):
    """``kind = "curve"``: measured cooling curves (a CSV as a run's probes.csv)."""

    kind: Literal["curve"] = entry(REQUIRED, doc="the kind of datum")
    file: str = entry(REQUIRED, doc="CSV: time_s and one column per probe",
                         allowed="required: a CSV of measured curves")
    probes: tuple[str, ...] | None = entry(None, doc="the probes (default: every probe column)",
                                              allowed="must be a list of at least 1 probe names")
    temperatures_C: tuple[float, ...] | None = entry(None, unit="C", doc="the temperatures whose passing times "
                                                        "count (default: those each curve passes)")
    uncertainty_K: float = entry(REQUIRED, unit="K", gt=0.0, doc="the thermocouple's standard deviation",
                                    allowed="the thermocouple's standard deviation in K")


@dataclass(frozen=True, kw_only=True)
class DepthDatum(Datum):
    """``kind = "depth"``: HRC ``hardness_HRC`` is reached ``value`` +- ``tolerance`` mm below the surface."""

    kind: Literal["depth"] = entry(REQUIRED, doc="the kind of datum")
    side: str = entry(REQUIRED, choices=TRAVERSE_SIDES, doc="\"bore\" or \"od\" (mid-width)")
    hardness_HRC: float = entry(58.0, unit="HRC", ge=20.0, le=70.0, doc="the threshold",
                                   allowed="must be a hardness in 20-70 HRC")
    value: float = entry(REQUIRED, unit="mm", gt=0.0, doc="the depth", allowed="the depth in mm")
    tolerance: float = entry(REQUIRED, unit="mm", gt=0.0, doc="the half-width of the stated depth range",
                                allowed="the half-width of the stated depth range, mm")
    uncertainty: float = entry(REQUIRED, unit="HRC", gt=0.0, doc="the hardness's standard deviation at the "
                                  "threshold", allowed="the hardness's standard deviation at the threshold, HRC")

    def check(self) -> None:
        super().check()
        require(self.tolerance < self.value, "tolerance", self.tolerance, f"must be below the depth {self.value:g} mm")


@dataclass(frozen=True, kw_only=True)
class TraverseDatum(Datum):
    """``kind = "traverse"``: a hardness traverse at mid-width (a CSV ``depth_mm``, ``HRC``)."""

    kind: Literal["traverse"] = entry(REQUIRED, doc="the kind of datum")
    file: str = entry(REQUIRED, doc="CSV: depth_mm, HRC", allowed="required: a CSV depth_mm, HRC")
    side: str = entry(REQUIRED, choices=TRAVERSE_SIDES, doc="\"bore\" or \"od\" (mid-width)",
                         allowed="must be one of bore, od (mid-width)")
    uncertainty: float = entry(REQUIRED, unit="HRC", gt=0.0, doc="the hardness's standard deviation",
                                  allowed="the hardness's standard deviation in HRC")


Measured = ValueDatum | BoundDatum | OrderDatum | CurveDatum | DepthDatum | TraverseDatum
"""A ``[[measurements]]`` table, by its ``kind``."""


@dataclass(frozen=True, kw_only=True)
class PredictionEntry(Table):
    """``[[predictions]]``: a quantity of another case or condition to predict with a band."""

    case: str = entry(REQUIRED, doc="the label of its [cases] entry")
    condition: str | int | None = entry(None, doc="a condition of that case file")
    quantity: str = entry(REQUIRED, doc="a dotted path of summary.json")


@dataclass(frozen=True, kw_only=True)
class DiscrepancyEntry(Table):
    """``[discrepancy] GROUP = { scale, unit, reason }``: the half-normal prior of a group's model discrepancy."""

    scale: float = entry(REQUIRED, gt=0.0, doc="the prior's scale, in the group's unit",
                            allowed="the half-normal prior's scale of the group's discrepancy, in the group's unit")
    unit: str = entry("", doc="the group's unit")
    reason: str = entry(REQUIRED, doc="why the prior has that scale",
                           allowed="required: why the prior has that scale")

    def check(self) -> None:
        require(self.reason.strip() != "", "reason", self.reason, "required: why the prior has that scale")


@dataclass(frozen=True, kw_only=True)
class DesignOptions(Table):
    """``[design]``: the runs of the calibration."""

    screening_trajectories: int = entry(4, ge=2, doc="Morris trajectories on the full chain: r (d + 1) runs",
                                           allowed="must be an integer >= 2")
    training_runs: int = entry(16, ge=0, doc="Latin-hypercube runs added for the surrogate",
                                  allowed="must be an integer >= 0")
    holdout_runs: int = entry(6, ge=1, doc="runs never trained on", allowed="must be an integer >= 1")
    seed: int = entry(19, ge=0, doc="random seed", allowed="must be an integer >= 0")
    refine_waves: int = entry(0, ge=0, doc="waves of runs spread over the posterior so far",
                                 allowed="must be an integer >= 0")
    refine_runs: int = entry(0, ge=0, doc="points per refinement wave", allowed="must be an integer >= 0")


@dataclass(frozen=True, kw_only=True)
class SamplerOptions(Table):
    """``[sampler]``: emcee's ensemble (at least 2 (inputs + discrepancy groups) + 2 walkers)."""

    walkers: int = entry(32, ge=1, doc="walkers", allowed="must be an integer")
    steps: int = entry(3000, ge=100, doc="steps per walker", allowed="must be an integer >= 100")
    burn: int = entry(1000, ge=0, doc="steps dropped at the start", allowed="must be an integer >= 0")


@dataclass(frozen=True, kw_only=True)
class CalibrationFile(Table):
    """A calibration file."""

    name: str | None = entry(None, doc="the calibration's name (default: the file stem)")
    description: str = entry("", doc="one line")
    inputs: tuple[str, ...] = entry(REQUIRED, doc="the free inputs' paths (each with a prior in its data file)",
                                       allowed="required: a list of free-input paths, e.g. "
                                               "[\"material.SUJ3.mechanics.trip.K_1_Pa\"]")
    cases: Mapping[str, CaseEntry] = entry(REQUIRED, doc="one [cases.LABEL] table per case file",
                                              allowed="required: one [cases.LABEL] table per case file")
    measurements: tuple[Measured, ...] = entry(REQUIRED, doc="one [[measurements]] per datum",
                                                  allowed="required: one [[measurements]] per datum")
    predictions: tuple[PredictionEntry, ...] = entry((), doc="quantities to predict with a band",
                                                        allowed="must be a list of [[predictions]] tables")
    discrepancy: Mapping[str, DiscrepancyEntry] = entry({}, doc="model-discrepancy groups",
                                                           allowed="must be a table of groups {scale, unit, reason}")
    design: DesignOptions = entry(DesignOptions(), doc="the runs")
    sampler: SamplerOptions = entry(SamplerOptions(), doc="the sampler")

    def check(self) -> None:
        require(len(self.inputs) > 0, "inputs", list(self.inputs), "required: a list of free-input paths, e.g. "
                "[\"material.SUJ3.mechanics.trip.K_1_Pa\"]")
        require(len(set(self.inputs)) == len(self.inputs), "inputs", list(self.inputs), "each input may appear once")
        require(len(self.cases) > 0, "cases", {}, "required: one [cases.LABEL] table per case file")
        require(len(self.measurements) > 0, "measurements", [], "required: one [[measurements]] per datum")
        walkers = 2 * (len(self.inputs) + len(self.discrepancy)) + 2
        require(self.sampler.walkers >= walkers, "sampler.walkers", self.sampler.walkers,
                f"must be an integer >= {walkers}")
