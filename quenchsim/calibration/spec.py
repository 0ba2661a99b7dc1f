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
    refine_waves = 1                     # then this many waves of runs spread over the posterior so far,
    refine_runs = 60                     # this many points each (the surrogate sharpened where the posterior is)

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
from quenchsim.inputs.calibration import (CalibrationFile, CaseEntry, DesignOptions, DiscrepancyEntry,
                                          PredictionEntry, SamplerOptions)
from quenchsim.inputs.declare import declared_fields, from_table
from quenchsim.inputs.reader import read_toml, reading



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
    design: Mapping[str, int] = field(default_factory=lambda: asdict_of(DesignOptions()))
    sampler: Mapping[str, int] = field(default_factory=lambda: asdict_of(SamplerOptions()))

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


def _discrepancy(groups_given: Mapping[str, DiscrepancyEntry], groups: set[str]) -> tuple[DiscrepancyGroup, ...]:
    out = []
    for name, spec in groups_given.items():
        require(name in groups, f"discrepancy.{name}", name,
                f"no measurement is in this group; the groups: {', '.join(sorted(groups))}")
        out.append(DiscrepancyGroup(str(name), spec.scale, spec.unit, spec.reason))
    return tuple(out)


def _case_spec(label: str, entry: CaseEntry, base_dir: Path) -> CaseSpec:
    where = f"cases.{label}"
    path = (base_dir / entry.file).resolve()
    require(path.is_file(), f"{where}.file", entry.file, f"file not found ({path})")
    return CaseSpec(label=label, path=path, mesh=entry.mesh, overrides=dict(entry.set),
                    confirm_mesh=entry.confirm_mesh)


def _prediction(where: str, entry: PredictionEntry, cases: Mapping[str, CaseSpec]) -> Prediction:
    require(entry.case in cases, f"{where}.case", entry.case,
            f"unknown case; the [cases] of this file: {', '.join(cases) or 'none'}")
    quantity = check_quantity(entry.quantity, where)
    condition = entry.condition
    return Prediction(case=entry.case, condition=None if condition is None else str(condition), quantity=quantity)


def parse_calibration(raw: Mapping[str, Any], base_dir: Path, path: Path | None = None) -> CalibrationSpec:
    """Check a calibration table completely (read against its declaration, :mod:`quenchsim.inputs.calibration`;
    inputs against their data files, cases loaded, measurements)."""
    table = from_table(CalibrationFile, raw)
    inputs = tuple(free_input(p, f"inputs[{i}]") for i, p in enumerate(table.inputs))
    cases = {label: _case_spec(label, spec, base_dir) for label, spec in table.cases.items()}
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
    for i, m in enumerate(table.measurements):
        where = f"measurements[{i}]"

        def probes(label: str, cond: str | None, where: str = where) -> tuple[str, ...]:
            return tuple(p.name for p in case_at(label, cond, where).probes)

        measurements.append(parse_measurement(i, m, base_dir, cases, probes))
        for o in measurements[-1].observables:
            for t in o.terms:
                case_at(t.case, t.condition, where)
    predictions = tuple(_prediction(f"predictions[{i}]", p, cases) for i, p in enumerate(table.predictions))
    for i, p in enumerate(predictions):
        case_at(p.case, p.condition, f"predictions[{i}]")
    labels = [o.label for m in measurements for o in m.observables] + [p.label for p in predictions]
    require(len(set(labels)) == len(labels), "measurements", sorted({x for x in labels if labels.count(x) > 1}),
            "each case/condition/quantity may appear once")
    groups = {m.group for m in measurements if m.group}
    discrepancy = _discrepancy(table.discrepancy, groups)
    for i, inp in enumerate(inputs):
        require(any(used_by(inp, c) for c in loaded.values()), f"inputs[{i}]", inp.path,
                "no case of the calibration reads that data file")
    return CalibrationSpec(name=table.name if table.name is not None else (path.stem if path else "calibration"),
                           description=table.description, path=path, inputs=inputs, cases=cases,
                           measurements=tuple(measurements), predictions=predictions, discrepancy=discrepancy,
                           design=asdict_of(table.design), sampler=asdict_of(table.sampler))


def asdict_of(options: DesignOptions | SamplerOptions) -> dict[str, int]:
    """The design or sampler options as the calibration's code reads them (a mapping by key)."""
    return {f.name: getattr(options, f.name) for f in declared_fields(type(options))}


def load_calibration(path: str | Path) -> CalibrationSpec:
    """Read and check a calibration file (see the module docstring)."""
    path = Path(path)
    raw = read_toml(path, "calibration")
    with reading(path):
        return parse_calibration(raw, path.parent, path)
