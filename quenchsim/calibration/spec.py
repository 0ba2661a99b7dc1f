"""The calibration file (CAL.toml): which inputs are free, which measurements fix them, which cases make them.

::

    name = "ring_a_condition_1"
    inputs = ["material.SUJ3.mechanics.plastic.yield_Pa.per_phase.austenite",   # each needs a prior in
              "material.SUJ3.mechanics.trip.K_1_Pa.per_phase.martensite"]       # its data file (inputs.py)

    [cases.ring_a]                       # a label for the measurements
    file = "../cases/crb_outer_ring.toml"   # relative to this file
    mesh = 2.0                           # optional: element sizes x this for every run (Case.refined)
    set = { "quench.time_s" = 900.0 }    # optional: case overrides for every run

    [[measurements]]
    case = "ring_a"
    condition = "1"                      # a condition of that case file (omit for a case without conditions)
    quantity = "dimensions_mm.change.id" # a dotted path of summary.json
    value = -0.40
    uncertainty = 0.05                   # one standard deviation, in the quantity's unit (> 0)
    source = "reference report, Table 3"

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

import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from quenchsim.calibration.inputs import FreeInput, free_input, used_by
from quenchsim.case import Case, load_case
from quenchsim.errors import InputError, require

MEASURABLE_TABLES = ("probes", "hardness", "phases_final", "dimensions_mm", "distortion_budget_mm",
                     "residual_stress_MPa")
"""The tables of summary.json that hold measurable results (probe times, hardness depths, phase fractions,
dimensions, residual stresses). A path into them is checked again against the first finished run."""
DESIGN_DEFAULTS = {"screening_trajectories": 4, "training_runs": 16, "holdout_runs": 6, "seed": 19}
SAMPLER_DEFAULTS = {"walkers": 32, "steps": 3000, "burn": 1000}
TOP_KEYS = {"name", "description", "inputs", "cases", "measurements", "predictions", "design", "sampler"}


@dataclass(frozen=True)
class CaseSpec:
    """A case file of the calibration: its label, path, mesh factor and fixed overrides."""

    label: str
    path: Path
    mesh: float
    overrides: Mapping[str, Any]

    def load(self, condition: str | None, extra: Mapping[str, Any] | None = None) -> Case:
        """The checked case at ``condition``, refined, with the fixed and ``extra`` overrides."""
        case = load_case(self.path, condition, dict(self.overrides))
        case = case.refined(mesh=self.mesh) if self.mesh != 1.0 else case
        return case.with_overrides(dict(extra)) if extra else case


@dataclass(frozen=True)
class Prediction:
    """A quantity of summary.json (dotted path) of one case and condition."""

    case: str
    condition: str | None
    quantity: str

    @property
    def label(self) -> str:
        return f"{self.case}/{self.condition or '-'}:{self.quantity}"


@dataclass(frozen=True)
class Measurement(Prediction):
    """A measured quantity: its value, standard deviation and source."""

    value: float
    uncertainty: float
    source: str


@dataclass(frozen=True)
class CalibrationSpec:
    name: str
    description: str
    path: Path | None
    inputs: tuple[FreeInput, ...]
    cases: Mapping[str, CaseSpec]
    measurements: tuple[Measurement, ...]
    predictions: tuple[Prediction, ...] = ()
    design: Mapping[str, int] = field(default_factory=lambda: dict(DESIGN_DEFAULTS))
    sampler: Mapping[str, int] = field(default_factory=lambda: dict(SAMPLER_DEFAULTS))

    def runs(self) -> list[tuple[str, str | None]]:
        """The (case label, condition) pairs the measurements and predictions need, in order of first use."""
        out: list[tuple[str, str | None]] = []
        for m in (*self.measurements, *self.predictions):
            if (m.case, m.condition) not in out:
                out.append((m.case, m.condition))
        return out


def _number(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool)


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
    unknown = set(raw) - {"file", "mesh", "set"}
    require(not unknown, where, sorted(unknown), "allowed keys: file, mesh, set")
    require(isinstance(raw.get("file"), str), f"{where}.file", raw.get("file"), "required: a case file (relative to CAL.toml)")
    path = (base_dir / raw["file"]).resolve()
    require(path.is_file(), f"{where}.file", raw["file"], f"file not found ({path})")
    mesh = raw.get("mesh", 1.0)
    require(_number(mesh) and mesh > 0, f"{where}.mesh", mesh, "must be a number > 0 (element sizes x this)")
    overrides = raw.get("set", {})
    require(isinstance(overrides, Mapping), f"{where}.set", overrides, "must be a table of dotted case fields")
    return CaseSpec(label=label, path=path, mesh=float(mesh), overrides=dict(overrides))


def _prediction(where: str, raw: Any, cases: Mapping[str, CaseSpec], keys: tuple[str, ...]) -> Prediction:
    require(isinstance(raw, Mapping), where, raw, "must be a table")
    unknown = set(raw) - set(keys)
    require(not unknown, where, sorted(unknown), f"allowed keys: {', '.join(keys)}")
    require(raw.get("case") in cases, f"{where}.case", raw.get("case"),
            f"unknown case; the [cases] of this file: {', '.join(cases) or 'none'}")
    quantity = raw.get("quantity")
    require(isinstance(quantity, str) and quantity.split(".")[0] in MEASURABLE_TABLES and "." in quantity,
            f"{where}.quantity", quantity, f"must be a dotted path of summary.json under {', '.join(MEASURABLE_TABLES)}")
    condition = raw.get("condition")
    return Prediction(case=raw["case"], condition=None if condition is None else str(condition), quantity=quantity)


def _measurement(i: int, raw: Any, cases: Mapping[str, CaseSpec]) -> Measurement:
    where = f"measurements[{i}]"
    target = _prediction(where, raw, cases, ("case", "condition", "quantity", "value", "uncertainty", "source"))
    require(_number(raw.get("value")), f"{where}.value", raw.get("value"), "required: the measured number")
    require("uncertainty" in raw, f"{where}.uncertainty", None,
            "required: the measurement's standard deviation (> 0), in the quantity's unit")
    require(_number(raw["uncertainty"]) and raw["uncertainty"] > 0, f"{where}.uncertainty", raw["uncertainty"],
            "must be a number > 0 (one standard deviation)")
    require(isinstance(raw.get("source"), str) and raw["source"].strip(), f"{where}.source", raw.get("source"),
            "required: where the measured value comes from")
    return Measurement(case=target.case, condition=target.condition, quantity=target.quantity,
                       value=float(raw["value"]), uncertainty=float(raw["uncertainty"]), source=raw["source"])


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
    require(isinstance(raw_meas, list) and raw_meas, "measurements", raw_meas, "required: one [[measurements]] per value")
    measurements = tuple(_measurement(i, m, cases) for i, m in enumerate(raw_meas))
    raw_pred = raw.get("predictions", [])
    require(isinstance(raw_pred, list), "predictions", raw_pred, "must be a list of [[predictions]] tables")
    predictions = tuple(_prediction(f"predictions[{i}]", p, cases, ("case", "condition", "quantity"))
                        for i, p in enumerate(raw_pred))
    labels = [m.label for m in (*measurements, *predictions)]
    require(len(set(labels)) == len(labels), "measurements", labels, "each case/condition/quantity may appear once")
    loaded: dict[tuple[str, str | None], Case] = {}
    targets: list[tuple[str, Measurement | Prediction]] = [(f"measurements[{i}]", m) for i, m in enumerate(measurements)]
    targets += [(f"predictions[{i}]", p) for i, p in enumerate(predictions)]
    for where, m in targets:
        key = (m.case, m.condition)
        if key not in loaded:
            try:
                loaded[key] = cases[m.case].load(m.condition)
            except InputError as exc:
                raise InputError(f"{where} ({m.case}, condition {m.condition}): {exc.field}", exc.value,
                                 exc.allowed) from None
        if m.quantity.startswith("probes."):
            probe = m.quantity.split(".")[1]
            names = [p.name for p in loaded[key].probes]
            require(probe in names, f"{where}.quantity", m.quantity, f"no probe {probe!r}; the case's probes: "
                    f"{', '.join(names) or 'none'}")
    for i, inp in enumerate(inputs):
        require(any(used_by(inp, c) for c in loaded.values()), f"inputs[{i}]", inp.path,
                "no case of the calibration reads that data file")
    return CalibrationSpec(name=str(raw.get("name", path.stem if path else "calibration")),
                           description=str(raw.get("description", "")), path=path, inputs=inputs, cases=cases,
                           measurements=measurements, predictions=predictions,
                           design=_options(raw.get("design", {}), DESIGN_DEFAULTS, "design",
                                           {"screening_trajectories": 2, "training_runs": 0, "holdout_runs": 1, "seed": 0}),
                           sampler=_options(raw.get("sampler", {}), SAMPLER_DEFAULTS, "sampler",
                                            {"walkers": 2 * len(inputs) + 2, "steps": 100, "burn": 0}))


def load_calibration(path: str | Path) -> CalibrationSpec:
    """Read and check a calibration file (see the module docstring)."""
    path = Path(path)
    require(path.is_file(), "calibration", str(path), "file not found")
    try:
        raw = tomllib.loads(path.read_text())
    except tomllib.TOMLDecodeError as exc:
        raise InputError("calibration", str(path), f"is not valid TOML ({exc})") from None
    return parse_calibration(raw, path.parent, path)
