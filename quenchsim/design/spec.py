"""A design study file (TOML) parsed and checked before any run: the case, the variables, the objectives, the
constraints, the cheap fidelity and the confirmation.

    [study]
    case = "../cases/srb_outer_ring.toml"   # relative to the study file
    condition = "4"                         # the base condition (a case with conditions needs one)
    trials = 24                             # cheap-fidelity runs the optimiser asks for
    startup = 8                             # of them, the first ones: a Latin hypercube over the variables
    seed = 1
    sampler = "tpe"                         # tpe (default) | nsga2 | random
    map = ["quench.bath.id_jet_speed_mm_s", "quench.bath.od_jet_speed_mm_s"]   # the maps' two variables

    [set]                                   # fixed overrides of the case (dotted keys)
    quench.time_s = 900

    [variables]                             # any case field: [low, high] (a real number), or a table
    quench.bath.id_jet_speed_mm_s = [400, 2000]
    quench.bath.od_jet_speed_mm_s = { low = 1400, high = 10700, log = true }
    quench.bath.nozzles.id.count = { low = 4, high = 12, integer = true }
    quench.bath.quenchant = { choices = ["reference_quench_oil", "astm_d6200_fast_oil"] }

    [objectives]                            # summary quantities: "min", "max" or { target = value }
    "dimensions_mm.change.id" = { target = 0.0 }
    "shape_mm.change.bore_crown" = { target = 0.0 }

    [constraints]                           # "QUANTITY >= NUMBER" or "QUANTITY <= NUMBER"
    hardness = ["hardness.depth_mm.HRC58_bore_mid >= 16.8"]

    [fidelity]                              # the cheap runs: element size x mesh, step limits x step
    mesh = 2.0
    step = 2.0
    tolerance = { "dimensions_mm.change.id" = 0.02, "shape_mm.change.bore_crown" = 0.005,
                  "hardness.depth_mm.HRC58_bore_mid" = 0.3 }   # cheap vs full chain, per quantity

    [confirm]
    extra = 2                               # full-chain runs of front points besides the recommended one
    uncertainty = 0                         # N > 1: bands from N runs (the calibration's posterior, or the priors)
    posterior = "runs/cal"                  # optional: a `quenchsim calibrate` output folder

Every check uses the case's own: a variable's bounds (and each choice) are set on the case and the case is
checked, so an unknown key or a bound outside what the key allows is the case's one-line error, naming the
variable. Objectives and constraints must be numbers of this case's summary.json
(:func:`quenchsim.design.quantities.summary_quantities`); a constraint outside the range its quantity can take
(or two that contradict each other) is an error: no run could satisfy it.
"""

from __future__ import annotations

import hashlib
import json
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Literal, cast

from quenchsim.case import Case, load_case
from quenchsim.design.quantities import summary_quantities, unknown_quantity_hint
from quenchsim.errors import InputError, require
from quenchsim.inputs.declare import Spec, convert, from_table
from quenchsim.inputs.design import ObjectiveTarget, StudyFile, VariableTable
from quenchsim.inputs.reader import read_toml, reading

VARIABLE_KEYS = {"low", "high", "log", "integer", "step", "choices"}
"""The keys of a variable's table (a table holding any of them is a variable, not a table of dotted keys)."""
TOLERANCE = Spec(gt=0.0)
"""A fidelity tolerance: a number > 0."""
CONSTRAINT = re.compile(r"^\s*([A-Za-z0-9_.]+)\s*(>=|<=)\s*([-+0-9.eE]+)\s*$")


@dataclass(frozen=True)
class Variable:
    """A case field the optimiser sets: a real or integer range (``log``: sampled on a log scale) or choices."""

    key: str
    low: float | None = None
    high: float | None = None
    log: bool = False
    integer: bool = False
    step: float | None = None
    choices: tuple[Any, ...] = ()

    @property
    def numeric(self) -> bool:
        return not self.choices

    def bounds(self) -> tuple[float, float]:
        """(low, high) of a numeric variable (both given whenever there are no choices)."""
        return float(cast(float, self.low)), float(cast(float, self.high))

    def from_unit(self, u: float) -> Any:
        """The value at ``u`` in [0, 1] of the variable's range (log-scaled, rounded to integers or steps)."""
        if self.choices:
            return self.choices[min(int(u * len(self.choices)), len(self.choices) - 1)]
        lo, hi = self.bounds()
        x = math.exp(math.log(lo) + u * (math.log(hi) - math.log(lo))) if self.log else lo + u * (hi - lo)
        if self.integer:
            return int(min(max(round(x), lo), hi))
        if self.step:
            return float(min(lo + round((x - lo) / self.step) * self.step, hi))
        return float(x)

    def to_unit(self, x: Any) -> float:
        """Where ``x`` sits in the range, 0 at low and 1 at high (log-scaled where the variable is)."""
        if self.choices:
            return self.choices.index(x) / max(len(self.choices) - 1, 1)
        lo, hi = self.bounds()
        if self.log:
            return (math.log(x) - math.log(lo)) / (math.log(hi) - math.log(lo))
        return (float(x) - lo) / (hi - lo)


@dataclass(frozen=True)
class Objective:
    quantity: str
    goal: str                       # "min" | "max" | "target"
    target: float | None = None

    def score(self, value: float) -> float:
        """What the optimiser minimises or maximises: the value, or |value - target|."""
        # a "target" objective has its target
        return abs(value - cast(float, self.target)) if self.goal == "target" else value

    @property
    def direction(self) -> Literal["minimize", "maximize"]:
        return "maximize" if self.goal == "max" else "minimize"

    def label(self) -> str:
        return f"{self.quantity} -> {self.target:g}" if self.goal == "target" else f"{self.goal} {self.quantity}"


@dataclass(frozen=True)
class Constraint:
    quantity: str
    op: str                          # ">=" | "<="
    bound: float

    def violation(self, value: float) -> float:
        """Optuna's convention: <= 0 when met, else by how much it is missed (in the quantity's unit)."""
        return self.bound - value if self.op == ">=" else value - self.bound

    def label(self) -> str:
        return f"{self.quantity} {self.op} {self.bound:g}"


@dataclass(frozen=True)
class Fidelity:
    mesh: float = 1.0
    step: float = 1.0
    tolerance: dict[str, float] = field(default_factory=dict)

    @property
    def cheap(self) -> bool:
        return self.mesh != 1.0 or self.step != 1.0


@dataclass(frozen=True)
class Confirm:
    extra: int = 0
    uncertainty: int = 0
    posterior: Path | None = None


@dataclass(frozen=True)
class StudySpec:
    name: str
    case: Case                       # the base case with [set] applied, checked
    variables: tuple[Variable, ...]
    objectives: tuple[Objective, ...]
    constraints: tuple[Constraint, ...]
    fidelity: Fidelity
    confirm: Confirm
    trials: int
    startup: int
    seed: int
    sampler: str
    fixed: dict[str, Any]
    map_variables: tuple[str, ...] = ()

    def case_at(self, point: dict[str, Any], full: bool = False) -> Case:
        """The case of one point (the variables' values), at the cheap fidelity unless ``full``."""
        case = self.case.with_overrides(point)
        return case if full or not self.fidelity.cheap else case.refined(mesh=self.fidelity.mesh, step=self.fidelity.step)

    def quantities(self) -> list[str]:
        """The summary quantities the study reads: objectives, then constraints (each once)."""
        return list(dict.fromkeys([o.quantity for o in self.objectives] + [c.quantity for c in self.constraints]))

    def fingerprint(self) -> str:
        """A hash of what defines the study's trials (not ``trials``: a study may be extended)."""
        text = json.dumps([self.case.resolved(), [v.__dict__ for v in self.variables],
                           [o.__dict__ for o in self.objectives], [c.__dict__ for c in self.constraints],
                           [self.fidelity.mesh, self.fidelity.step], self.startup, self.seed, self.sampler],
                          sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()[:10]


def _flatten(table: dict[str, Any], leaf_keys: set[str], prefix: str = "") -> dict[str, Any]:
    """Dotted leaves of nested tables; a table holding any of ``leaf_keys`` is a leaf (a variable's spec)."""
    out: dict[str, Any] = {}
    for key, value in table.items():
        dotted = f"{prefix}{key}"
        if isinstance(value, dict) and not (set(value) & leaf_keys):
            out.update(_flatten(value, leaf_keys, dotted + "."))
        else:
            out[dotted] = value
    return out


def _variable(key: str, raw: Any) -> Variable:
    """The variable of ``[variables]`` key ``key``: ``[low, high]`` or a table (:class:`VariableTable`)."""
    name = f"variables.{key}"
    if isinstance(raw, list):
        require(len(raw) == 2, name, raw, "must be [low, high] or a table { low, high, log, integer, step } or "
                                          "{ choices = [...] }")
        raw = {"low": raw[0], "high": raw[1]}
    require(isinstance(raw, dict), name, raw, "must be [low, high] or a table { low, high, ... } or { choices = [...] }")
    table = from_table(VariableTable, raw, name)
    if table.choices is not None:
        return Variable(key, choices=table.choices)
    return Variable(key, low=table.low, high=table.high, log=table.log, integer=table.integer, step=table.step)


def _check_bounds(base: Case, var: Variable) -> None:
    """Set each bound (each choice) on the case: its own checks name what the key allows."""
    values = list(var.choices) if var.choices else [var.from_unit(0.0), var.from_unit(1.0)]
    for value in values:
        try:
            base.with_overrides({var.key: value})
        except InputError as exc:
            where = "" if exc.field == var.key else f" ({exc.field} = {exc.value!r})"
            raise InputError(f"variables.{var.key}", value, f"outside what the case allows{where}: {exc.allowed}") from None


def _objective(key: str, raw: Any) -> Objective:
    name = f"objectives.{key}"
    if raw in ("min", "max"):
        return Objective(key, raw)
    require(isinstance(raw, dict) and set(raw) == {"target"}, name, raw, 'must be "min", "max" or { target = NUMBER }')
    return Objective(key, "target", from_table(ObjectiveTarget, raw, name).target)


def _constraints(raw: Any) -> list[Constraint]:
    items: list[tuple[str, Any]] = []
    if isinstance(raw, (list, tuple)):
        items = [("constraints", c) for c in raw]
    else:
        require(isinstance(raw, dict), "constraints", raw, 'must be a table of lists of "QUANTITY >= NUMBER" strings')
        for key, value in raw.items():
            items += [(f"constraints.{key}", c) for c in (value if isinstance(value, list) else [value])]
    out = []
    for name, text in items:
        match = CONSTRAINT.match(text) if isinstance(text, str) else None
        require(match is not None, name, text, 'must read "QUANTITY >= NUMBER" or "QUANTITY <= NUMBER"')
        assert match is not None   # require raised otherwise
        try:
            bound = float(match.group(3))
        except ValueError:
            raise InputError(name, text, f"'{match.group(3)}' is not a number") from None
        out.append(Constraint(match.group(1), match.group(2), bound))
    return out


def _check_satisfiable(constraints: list[Constraint], known: dict[str, tuple[float, float]]) -> None:
    """A constraint outside the range of its quantity, or two on one quantity that leave nothing between them."""
    for c in constraints:
        low, high = known[c.quantity]
        if (c.op == ">=" and c.bound > high) or (c.op == "<=" and c.bound < low):
            limit = f"at most {high:g}" if c.op == ">=" else f"at least {low:g}"
            raise InputError("constraints", c.label(), f"no run can satisfy it: {c.quantity} is {limit} on this case")
    for q in {c.quantity for c in constraints}:
        lows = [c.bound for c in constraints if c.quantity == q and c.op == ">="]
        highs = [c.bound for c in constraints if c.quantity == q and c.op == "<="]
        if lows and highs and max(lows) > min(highs):
            raise InputError("constraints", f"{q} >= {max(lows):g} and <= {min(highs):g}",
                             "no run can satisfy both")


def parse_study(raw: dict[str, Any], base_dir: Path, name: str = "study") -> StudySpec:
    """Build and check a :class:`StudySpec` from a study table (as read from TOML, :class:`StudyFile`)."""
    spec = from_table(StudyFile, raw)
    head = spec.study
    case_path = (base_dir / head.case).resolve()
    require(case_path.is_file(), "study.case", head.case, f"file not found ({case_path})")
    fixed = _flatten(dict(spec.set), set())
    case = load_case(case_path, None if head.condition is None else str(head.condition), fixed)

    variables = [_variable(k, v) for k, v in _flatten(dict(spec.variables), VARIABLE_KEYS).items()]
    require(len(variables) > 0, "variables", None, "a study needs at least one variable")
    clash = sorted({v.key for v in variables} & set(fixed))
    require(not clash, "variables", clash, "a field may be either in [set] or in [variables]")
    for var in variables:
        _check_bounds(case, var)

    known = summary_quantities(case)
    objectives = [_objective(k, v) for k, v in _flatten(dict(spec.objectives), {"target"}).items()]
    require(len(objectives) > 0, "objectives", None, "a study needs at least one objective")
    constraints = _constraints(spec.constraints)
    goals: list[Objective | Constraint] = [*objectives, *constraints]
    for item in goals:
        section = "objectives" if isinstance(item, Objective) else "constraints"
        require(item.quantity in known, f"{section}.{item.quantity}", item.label(), unknown_quantity_hint(item.quantity, known))
    _check_satisfiable(constraints, known)

    f = spec.fidelity
    tolerance = {k: convert(v, float, f"fidelity.tolerance.{k}", TOLERANCE)
                 for k, v in _flatten(dict(f.tolerance), set()).items()}
    fidelity = Fidelity(mesh=f.mesh, step=f.step, tolerance=tolerance)
    quantities = list(dict.fromkeys(i.quantity for i in goals))
    if fidelity.cheap:
        missing = [q for q in quantities if q not in fidelity.tolerance]
        require(not missing, "fidelity.tolerance", missing,
                "a cheap fidelity needs the tolerance it must agree with the full chain within, for every objective "
                "and constraint quantity")
    for q in fidelity.tolerance:
        require(q in quantities, f"fidelity.tolerance.{q}", fidelity.tolerance[q], "is not an objective or constraint quantity")
    c = spec.confirm
    posterior = None if c.posterior is None else (base_dir / c.posterior).resolve()
    confirm = Confirm(extra=c.extra, uncertainty=c.uncertainty, posterior=posterior)
    if c.uncertainty:
        from quenchsim.calibration.propagate import uncertain_inputs

        uncertain_inputs(case, c.uncertainty, posterior)   # its own checks, before any run

    numeric = [v.key for v in variables if v.numeric]
    map_variables = list(head.map) if head.map is not None else (numeric[:2] if len(numeric) >= 2 else [])
    require(len(map_variables) == 2 and set(map_variables) <= set(numeric) or len(numeric) < 2 and not map_variables,
            "study.map", map_variables, f"must name two of the numeric variables ({', '.join(numeric)})")
    return StudySpec(name=head.name if head.name is not None else name, case=case, variables=tuple(variables),
                     objectives=tuple(objectives), constraints=tuple(constraints), fidelity=fidelity, confirm=confirm,
                     trials=head.trials, startup=head.first_trials, seed=head.seed, sampler=head.sampler,
                     fixed=fixed, map_variables=tuple(map_variables))


def load_study(path: str | Path) -> StudySpec:
    """Read and check a study file (see the module docstring)."""
    path = Path(path)
    raw = read_toml(path, "study")
    with reading(path):
        return parse_study(raw, path.parent, name=path.stem)
