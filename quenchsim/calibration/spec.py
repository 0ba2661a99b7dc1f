"""The calibration file (CAL.toml): which inputs are free, which measurements fix them, which cases make them.

::

    name = "ring_a_condition_1"
    inputs = ["material.SUJ3.mechanics.plastic.yield_Pa.per_phase.austenite",   # each needs a prior in
              "bath.jet_bath.htc_factor.od"]                                    # its data file (inputs.py)

    [cases.ring_a]                       # a label for the measurements
    file = "../cases/crb_outer_ring.toml"   # relative to this file
    mesh = 2.0                           # optional: element sizes x this for every design run (Case.refined)
    confirm_mesh = 1.0                   # optional: the nominal and the calibrated run again at this mesh (the
                                         # design's cheap fidelity against the full one, per observable)
    set = { "quench.time_s" = 900.0 }    # optional: case overrides for every run

    [[measurements]]                     # one datum; kinds value (shown), bound, order, curve, traverse:
    case = "ring_a"                      # quenchsim.calibration.data
    condition = "1"                      # a condition of that case file (omit for a case without conditions)
    quantity = "dimensions_mm.change.id" # a dotted path of summary.json
    value = -0.40
    uncertainty = 0.05                   # one standard deviation, in the quantity's unit (> 0)
    group = "dimensions"                 # optional: its model-discrepancy group (default: the quantity's table)
    source = "reference report, Table 3"

    [discrepancy]                        # optional: a model discrepancy per group (quenchsim.calibration.likelihood)
    dimensions = { scale = 0.15, unit = "mm", reason = "..." }   # half-normal prior of that scale on its sd

    [[predictions]]                      # optional: quantities of other cases/conditions to predict with a
    case = "ring_a"                      # band from the same design (the surrogate is trained on them too)
    condition = "2"
    quantity = "dimensions_mm.change.id"

    [design]                             # all optional
    screening_trajectories = 4           # Morris trajectories on the full chain: r (d + 1) runs
    training_runs = 16                   # Latin-hypercube runs added to the screening runs for the surrogate
    holdout_runs = 6                     # runs never trained on: the surrogate's own error
    seed = 19

    [sampler]                            # emcee, all optional
    walkers = 32
    steps = 3000
    burn = 1000

Every error is one :class:`~quenchsim.errors.InputError` naming the field, raised before any run.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from quenchsim.calibration.data import (Measurement, Observable, Prediction, check_quantity,
                                        parse_measurement)
from quenchsim.calibration.inputs import FreeInput, free_input, used_by
from quenchsim.case import Case, load_case
from quenchsim.errors import InputError, require
from quenchsim.inputs.reader import read_toml, reading

DESIGN_DEFAULTS = {"screening_trajectories": 4, "training_runs": 16, "holdout_runs": 6, "seed": 19}
SAMPLER_DEFAULTS = {"walkers": 32, "steps": 3000, "burn": 1000}
TOP_KEYS = {"name", "description", "inputs", "cases", "measurements", "predictions", "discrepancy", "design", "sampler"}
DISCREPANCY_KEYS = ("scale", "unit", "reason")


@dataclass(frozen=True)
class CaseSpec:
    """A case file of the calibration: its label, path, mesh factor and fixed overrides."""

    label: str
    path: Path
    mesh: float
    overrides: Mapping[str, Any]
    confirm_mesh: float | None = None

    def load(self, condition: str | None, extra: Mapping[str, Any] | None = None, mesh: float | None = None) -> Case:
        """The checked case at ``condition``, refined (by ``mesh``, default the design's), with the fixed and
        ``extra`` overrides."""
        factor = self.mesh if mesh is None else mesh
        case = load_case(self.path, condition, dict(self.overrides))
        case = case.refined(mesh=factor) if factor != 1.0 else case
        return case.with_overrides(dict(extra)) if extra else case


@dataclass(frozen=True)
class DiscrepancyGroup:
    """A model-discrepancy group: the half-normal prior scale of its standard deviation, in ``unit``, and why."""

    name: str
    scale: float
    unit: str
    reason: str


@dataclass(frozen=True)
class CalibrationSpec:
    name: str
    description: str
    path: Path | None
    inputs: tuple[FreeInput, ...]
    cases: Mapping[str, CaseSpec]
    measurements: tuple[Measurement, ...]
    predictions: tuple[Prediction, ...] = ()
    discrepancy: tuple[DiscrepancyGroup, ...] = ()
    design: Mapping[str, int] = field(default_factory=lambda: dict(DESIGN_DEFAULTS))
    sampler: Mapping[str, int] = field(default_factory=lambda: dict(SAMPLER_DEFAULTS))

    @property
    def observables(self) -> tuple[Observable, ...]:
        """Every measured observable, datum by datum (the likelihood's)."""
        return tuple(o for m in self.measurements for o in m.observables)

    @property
    def predicted(self) -> tuple[Observable, ...]:
        return tuple(p.observable() for p in self.predictions)

    def runs(self) -> list[tuple[str, str | None]]:
        """The (case label, condition) pairs the observables and predictions need, in order of first use."""
        out: list[tuple[str, str | None]] = []
        for o in (*self.observables, *self.predicted):
            for t in o.terms:
                if (t.case, t.condition) not in out:
                    out.append((t.case, t.condition))
        return out


def _number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _discrepancy(raw: Any, groups: set[str]) -> tuple[DiscrepancyGroup, ...]:
    require(isinstance(raw, Mapping), "discrepancy", raw, "must be a table of groups {scale, unit, reason}")
    out = []
    for name, spec in raw.items():
        where = f"discrepancy.{name}"
        require(isinstance(spec, Mapping), where, spec, "must be a table {scale, unit, reason}")
        unknown = sorted(set(spec) - set(DISCREPANCY_KEYS))
        require(not unknown, where, unknown, f"allowed keys: {', '.join(DISCREPANCY_KEYS)}")
        require(name in groups, where, name, f"no measurement is in this group; the groups: {', '.join(sorted(groups))}")
        scale = spec.get("scale")
        require(_number(scale) and scale > 0, f"{where}.scale", scale, "must be a number > 0 (the half-normal prior's "
                "scale of the group's discrepancy, in the group's unit)")
        require(isinstance(spec.get("reason"), str) and spec["reason"].strip(), f"{where}.reason", spec.get("reason"),
                "required: why the prior has that scale")
        out.append(DiscrepancyGroup(str(name), float(scale), str(spec.get("unit", "")), spec["reason"]))
    return tuple(out)


def _options(raw: Any, defaults: Mapping[str, int], table: str, minimum: Mapping[str, int]) -> dict[str, int]:
    require(isinstance(raw, Mapping), table, raw, "must be a table")
    unknown = set(raw) - set(defaults)
    require(not unknown, table, sorted(unknown), f"allowed keys: {', '.join(defaults)}")
    out = {**defaults, **raw}
    for key, low in minimum.items():
        require(isinstance(out[key], int) and not isinstance(out[key], bool) and out[key] >= low,
                f"{table}.{key}", out[key], f"must be an integer >= {low}")
    return out


def _case_spec(label: str, raw: Any, base_dir: Path) -> CaseSpec:
    where = f"cases.{label}"
    require(isinstance(raw, Mapping), where, raw, "must be a table with file = CASE.toml")
    unknown = set(raw) - {"file", "mesh", "confirm_mesh", "set"}
    require(not unknown, where, sorted(unknown), "allowed keys: file, mesh, confirm_mesh, set")
    require(isinstance(raw.get("file"), str), f"{where}.file", raw.get("file"), "required: a case file (relative to CAL.toml)")
    path = (base_dir / raw["file"]).resolve()
    require(path.is_file(), f"{where}.file", raw["file"], f"file not found ({path})")
    mesh = raw.get("mesh", 1.0)
    require(_number(mesh) and mesh > 0, f"{where}.mesh", mesh, "must be a number > 0 (element sizes x this)")
    confirm = raw.get("confirm_mesh")
    require(confirm is None or (_number(confirm) and confirm > 0), f"{where}.confirm_mesh", confirm,
            "must be a number > 0 (element sizes x this for the nominal and calibrated runs)")
    overrides = raw.get("set", {})
    require(isinstance(overrides, Mapping), f"{where}.set", overrides, "must be a table of dotted case fields")
    return CaseSpec(label=label, path=path, mesh=float(mesh), overrides=dict(overrides),
                    confirm_mesh=None if confirm is None else float(confirm))


def _prediction(where: str, raw: Any, cases: Mapping[str, CaseSpec]) -> Prediction:
    require(isinstance(raw, Mapping), where, raw, "must be a table")
    keys = ("case", "condition", "quantity")
    unknown = set(raw) - set(keys)
    require(not unknown, where, sorted(unknown), f"allowed keys: {', '.join(keys)}")
    require(raw.get("case") in cases, f"{where}.case", raw.get("case"),
            f"unknown case; the [cases] of this file: {', '.join(cases) or 'none'}")
    quantity = check_quantity(raw.get("quantity"), where)
    condition = raw.get("condition")
    return Prediction(case=raw["case"], condition=None if condition is None else str(condition), quantity=quantity)


def parse_calibration(raw: Mapping[str, Any], base_dir: Path, path: Path | None = None) -> CalibrationSpec:
    """Check a calibration table completely (inputs against their data files, cases loaded, measurements)."""
    unknown = set(raw) - TOP_KEYS
    require(not unknown, "calibration file", sorted(unknown), f"allowed keys: {', '.join(sorted(TOP_KEYS))}")
    paths: Any = raw.get("inputs")   # checked by require: a list of strings
    require(isinstance(paths, list) and paths and all(isinstance(p, str) for p in paths), "inputs", paths,
            "required: a list of free-input paths, e.g. [\"material.SUJ3.mechanics.trip.K_1_Pa\"]")
    require(len(set(paths)) == len(paths), "inputs", paths, "each input may appear once")
    inputs = tuple(free_input(p, f"inputs[{i}]") for i, p in enumerate(paths))
    raw_cases: Any = raw.get("cases")
    require(isinstance(raw_cases, Mapping) and raw_cases, "cases", raw_cases,
            "required: one [cases.LABEL] table per case file")
    cases = {label: _case_spec(label, spec, base_dir) for label, spec in raw_cases.items()}
    raw_meas: Any = raw.get("measurements")
    require(isinstance(raw_meas, list) and raw_meas, "measurements", raw_meas, "required: one [[measurements]] per datum")
    loaded: dict[tuple[str, str | None], Case] = {}

    def case_at(label: str, condition: str | None, where: str) -> Case:
        if (label, condition) not in loaded:
            try:
                loaded[(label, condition)] = cases[label].load(condition)
            except InputError as exc:
                raise InputError(f"{where} ({label}, condition {condition}): {exc.field}", exc.value,
                                 exc.allowed) from None
        return loaded[(label, condition)]

    measurements = []
    for i, m in enumerate(raw_meas):
        where = f"measurements[{i}]"

        def probes(label: str, cond: str | None, where: str = where) -> tuple[str, ...]:
            return tuple(p.name for p in case_at(label, cond, where).probes)

        measurements.append(parse_measurement(i, m, base_dir, cases, probes))
        for o in measurements[-1].observables:
            for t in o.terms:
                case_at(t.case, t.condition, where)
    raw_pred = raw.get("predictions", [])
    require(isinstance(raw_pred, list), "predictions", raw_pred, "must be a list of [[predictions]] tables")
    predictions = tuple(_prediction(f"predictions[{i}]", p, cases) for i, p in enumerate(raw_pred))
    for i, p in enumerate(predictions):
        case_at(p.case, p.condition, f"predictions[{i}]")
    labels = [o.label for m in measurements for o in m.observables] + [p.label for p in predictions]
    require(len(set(labels)) == len(labels), "measurements", sorted({x for x in labels if labels.count(x) > 1}),
            "each case/condition/quantity may appear once")
    groups = {m.group for m in measurements if m.group}
    discrepancy = _discrepancy(raw.get("discrepancy", {}), groups)
    for i, inp in enumerate(inputs):
        require(any(used_by(inp, c) for c in loaded.values()), f"inputs[{i}]", inp.path,
                "no case of the calibration reads that data file")
    return CalibrationSpec(name=str(raw.get("name", path.stem if path else "calibration")),
                           description=str(raw.get("description", "")), path=path, inputs=inputs, cases=cases,
                           measurements=tuple(measurements), predictions=predictions, discrepancy=discrepancy,
                           design=_options(raw.get("design", {}), DESIGN_DEFAULTS, "design",
                                           {"screening_trajectories": 2, "training_runs": 0, "holdout_runs": 1, "seed": 0}),
                           sampler=_options(raw.get("sampler", {}), SAMPLER_DEFAULTS, "sampler",
                                            {"walkers": 2 * (len(inputs) + len(discrepancy)) + 2, "steps": 100,
                                             "burn": 0}))


def load_calibration(path: str | Path) -> CalibrationSpec:
    """Read and check a calibration file (see the module docstring)."""
    path = Path(path)
    raw = read_toml(path, "calibration")
    with reading(path):
        return parse_calibration(raw, path.parent, path)
