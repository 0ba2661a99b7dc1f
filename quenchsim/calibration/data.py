"""The measured data of a ring, of every kind, and the scalar observables the calibration compares with the runs.

A ``[[measurements]]`` table of the calibration file is one datum; ``kind`` says what was measured:

``value`` (default)
    a number of summary.json: ``quantity`` (dotted path), ``value``, ``uncertainty`` (one standard deviation).
``bound``
    a statement such as "the centre is mostly pearlite": ``quantity``, ``min`` and/or ``max``, ``uncertainty`` (how
    soft the bound is: one standard deviation of the measured quantity at the bound).
``order``
    the order of the probes (thermocouples) in one probe quantity, fastest first: ``quantity`` (a probe quantity such
    as ``t_to_500C_s`` or ``t_to_C_s.600``), ``probes = ["P5", "P4", ...]``, ``tolerance`` (the standard deviation of
    each measured difference, in the quantity's unit). Each consecutive pair is a bound ``later - earlier >= 0``.
``curve``
    measured cooling curves: ``file`` (CSV: ``time_s`` and one column per probe, ``P2`` or ``P2_C``, as probes.csv
    of a run), optional ``probes`` (default every probe column) and ``temperatures_C`` (default those of
    :data:`~quenchsim.results.summary.PROBE_TEMPERATURES_C` each curve passes), ``uncertainty_K`` (the
    thermocouple's standard deviation). Each curve becomes the times it passes those temperatures, each time's
    standard deviation that of the temperature over the curve's slope there (plus its sampling interval's).
``depth``
    a hardness depth, "HRC ``hardness_HRC`` (default 58) is reached ``value`` +- ``tolerance`` mm below the surface":
    ``side = "bore"`` or ``"od"`` (mid-width), ``value`` and ``tolerance`` (mm; the stated range's half-width),
    ``uncertainty`` (HRC: the hardness's standard deviation at the threshold). Becomes two bounds on the run's
    traverse, HRC(value - tolerance) >= threshold >= HRC(value + tolerance): smooth in the inputs, where the depth
    itself jumps from a case of a few mm to a through-hardened wall.
``traverse``
    a hardness traverse at mid-width: ``file`` (CSV: ``depth_mm`` and ``HRC``), ``side = "bore"`` or ``"od"``,
    ``uncertainty`` (HRC). Each point becomes the run's HRC at that depth (hardness_traverse.csv of the run).

Every datum has ``case``, ``condition`` (of that case file), ``source`` (required) and optionally ``group`` (its
model-discrepancy group, :mod:`quenchsim.calibration.likelihood`; default the quantity's table, e.g.
``dimensions_mm``). A ``value`` or ``bound`` datum may compare two conditions: ``relative_to = "1"`` with
``relation = "ratio"`` (this condition's quantity over that condition's) or ``"difference"`` (this minus that).
"""

from __future__ import annotations

import csv
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.errors import InputError, require
from quenchsim.inputs.calibration import (BoundDatum, CurveDatum, DepthDatum, Measured, OrderDatum, RelatedDatum,
                                          TraverseDatum, ValueDatum)
from quenchsim.results.postprocess import time_to_temperature
from quenchsim.results.summary import PROBE_TEMPERATURES_C

KINDS = ("value", "bound", "order", "curve", "depth", "traverse")
MEASURABLE_TABLES = ("probes", "hardness", "phases_final", "dimensions_mm", "distortion_budget_mm",
                     "residual_stress_MPa")
"""The tables of summary.json that hold measurable results (probe times, phases and hardness, hardness depths,
phase fractions, dimensions, residual stresses). A path into them is checked again against the first finished run."""
TRAVERSE_PREFIX = "traverse."
"""An observable path ``traverse.<side>@<depth_mm>``: the HRC at that depth of the run's hardness_traverse.csv."""
@dataclass(frozen=True)
class Term:
    """One number of one run: the run's case label and condition, and the path of the number (a dotted path of
    summary.json, or ``traverse.<side>@<depth_mm>``)."""

    case: str
    condition: str | None
    path: str


@dataclass(frozen=True)
class Observable:
    """A scalar the calibration compares: a number of a run (``relation = "value"``), or the ratio or difference
    of two (``terms[0]`` over / minus ``terms[1]``); measured as ``value`` +- ``sd`` or bounded by ``lower`` /
    ``upper`` (soft by ``sd``); a prediction has neither. ``group``: its model-discrepancy group."""

    label: str
    terms: tuple[Term, ...]
    relation: str = "value"
    value: float | None = None
    lower: float | None = None
    upper: float | None = None
    sd: float = 0.0
    group: str | None = None

    @property
    def is_bound(self) -> bool:
        return self.value is None and (self.lower is not None or self.upper is not None)

    @property
    def is_measured(self) -> bool:
        return self.value is not None or self.is_bound

    def model_value(self, read: Callable[[Term], float | None]) -> float | None:
        """The run's value of this observable (``read`` gives a term's number), None when a term is missing."""
        values = [read(t) for t in self.terms]
        if any(v is None for v in values):
            return None
        a = float(values[0])   # type: ignore[arg-type]
        if self.relation == "value":
            return a
        b = float(values[1])   # type: ignore[arg-type]
        if self.relation == "difference":
            return a - b
        return a / b if b != 0.0 else None

    def target_text(self) -> str:
        if self.value is not None:
            return f"{self.value:.4g} +- {self.sd:.3g}"
        parts = []
        if self.lower is not None:
            parts.append(f">= {self.lower:.4g}")
        if self.upper is not None:
            parts.append(f"<= {self.upper:.4g}")
        return " and ".join(parts) + f" (soft by {self.sd:.3g})"


@dataclass(frozen=True)
class Prediction:
    """A quantity of summary.json (dotted path) of one case and condition, predicted with a band."""

    case: str
    condition: str | None
    quantity: str

    @property
    def label(self) -> str:
        return f"{self.case}/{self.condition or '-'}:{self.quantity}"

    def observable(self) -> Observable:
        return Observable(label=self.label, terms=(Term(self.case, self.condition, self.quantity),))


@dataclass(frozen=True)
class Measurement:
    """One datum of the calibration file (see the module docstring): its kind, where it was measured, its source,
    its discrepancy group and the observables it becomes. ``quantity``, ``value`` and ``uncertainty`` are those of a
    plain ``value`` datum (None otherwise)."""

    kind: str
    case: str
    condition: str | None
    label: str
    source: str
    group: str | None
    observables: tuple[Observable, ...]
    quantity: str | None = None
    value: float | None = None
    uncertainty: float | None = None


def check_quantity(quantity: Any, where: str) -> str:
    """A dotted path of summary.json under one of :data:`MEASURABLE_TABLES`."""
    require(isinstance(quantity, str) and "." in quantity and quantity.split(".")[0] in MEASURABLE_TABLES,
            f"{where}.quantity", quantity, f"must be a dotted path of summary.json under {', '.join(MEASURABLE_TABLES)}")
    return str(quantity)


def default_group(quantity: str) -> str:
    """The discrepancy group of a quantity when its datum names none: its summary table (``probes`` split into the
    probe times and the probe phases / hardness)."""
    parts = quantity.split(".")
    if parts[0] == "probes" and len(parts) > 2 and parts[2] in ("phases", "HRC"):
        return "probe_phases" if parts[2] == "phases" else "probe_hardness"
    return parts[0]


def read_columns(path: Path, where: str, required: tuple[str, ...]) -> dict[str, np.ndarray]:
    """The numeric columns of a CSV file with a header row; one-line errors name the file, row and column."""
    require(path.is_file(), f"{where}.file", str(path), "file not found")
    with path.open(newline="") as fh:
        rows = list(csv.reader(line for line in fh if line.strip() and not line.lstrip().startswith("#")))
    require(len(rows) >= 3, f"{where}.file", str(path), "needs a header row and at least two rows of numbers")
    header = [h.strip() for h in rows[0]]
    missing = [c for c in required if c not in header]
    require(not missing, f"{where}.file", path.name, f"has no column {', '.join(missing)} (header: {', '.join(header)})")
    data: dict[str, list[float]] = {h: [] for h in header}
    for i, row in enumerate(rows[1:], start=2):
        require(len(row) == len(header), f"{where}.file", f"{path.name} row {i}", f"has {len(row)} fields, the header "
                f"{len(header)}")
        for h, cell in zip(header, row):
            try:
                x = float(cell)
            except ValueError:
                raise InputError(f"{where}.file", f"{path.name} row {i} column {h}", f"{cell!r} is not a number") from None
            require(math.isfinite(x), f"{where}.file", f"{path.name} row {i} column {h}", "must be a finite number")
            data[h].append(x)
    return {h: np.array(v) for h, v in data.items()}


def _relation(datum: RelatedDatum, where: str, condition: str | None) -> tuple[str, str | None]:
    if datum.relative_to is None:
        return "value", None
    other = str(datum.relative_to)
    require(other != condition, f"{where}.relative_to", other, "must be another condition than the datum's own")
    return str(datum.relation), other


def _scalar(datum: ValueDatum | BoundDatum, where: str, case: str, condition: str | None, group: str | None
            ) -> tuple[str, Observable, str]:
    quantity = check_quantity(datum.quantity, where)
    relation, other = _relation(datum, where, condition)
    terms = (Term(case, condition, quantity),) + ((Term(case, other, quantity),) if other is not None else ())
    sd = datum.uncertainty
    symbol = {"value": "", "ratio": f" / condition {other}", "difference": f" - condition {other}"}[relation]
    label = f"{case}/{condition or '-'}:{quantity}{symbol}"
    group = group or default_group(quantity) + ("" if relation == "value" else f"_{relation}")
    if isinstance(datum, ValueDatum):
        return label, Observable(label, terms, relation, value=datum.value, sd=sd, group=group), quantity
    return label, Observable(label, terms, relation, lower=datum.min, upper=datum.max, sd=sd, group=group), quantity


def _probe_names(names: tuple[str, ...], where: str, probes: tuple[str, ...], minimum: int) -> list[str]:
    require(len(names) >= minimum, f"{where}.probes", list(names), f"must be a list of at least {minimum} probe names")
    unknown = [p for p in names if p not in probes]
    require(not unknown, f"{where}.probes", unknown, f"not probes of the case; its probes: {', '.join(probes) or 'none'}")
    require(len(set(names)) == len(names), f"{where}.probes", list(names), "each probe may appear once")
    return list(names)


def _order(datum: OrderDatum, where: str, case: str, condition: str | None, group: str | None,
           probes: tuple[str, ...]) -> tuple[str, tuple[Observable, ...]]:
    q = datum.quantity
    require(q != "" and not q.startswith("probes."), f"{where}.quantity", q,
            "must be a probe quantity such as t_to_500C_s or t_to_C_s.600 (without probes.NAME.)")
    names = _probe_names(datum.probes, where, probes, 2)
    tol = datum.tolerance
    out = []
    for early, late in zip(names, names[1:]):
        terms = (Term(case, condition, f"probes.{late}.{q}"), Term(case, condition, f"probes.{early}.{q}"))
        label = f"{case}/{condition or '-'}:probes.{late}.{q} - probes.{early}.{q}"
        out.append(Observable(label, terms, "difference", lower=0.0, sd=tol * math.sqrt(2.0), group=group or "probes"))
    return f"{case}/{condition or '-'}:order {' < '.join(names)} ({q})", tuple(out)


def _crossing_sd(time_s: np.ndarray, T: np.ndarray, t: float, uncertainty_K: float) -> float:
    """The standard deviation of a crossing time: the temperature's over the curve's slope there, with the sampling
    interval's (uniform: dt / sqrt 12)."""
    i = int(np.clip(np.searchsorted(time_s, t), 1, len(time_s) - 1))
    lo, hi = max(i - 2, 0), min(i + 1, len(time_s) - 1)
    slope = abs((T[hi] - T[lo]) / (time_s[hi] - time_s[lo])) if time_s[hi] > time_s[lo] else 0.0
    dt = float(time_s[i] - time_s[i - 1])
    return math.hypot(uncertainty_K / max(slope, 1e-9), dt / math.sqrt(12.0))


def _curve(datum: CurveDatum, where: str, base_dir: Path, case: str, condition: str | None, group: str | None,
           probes: tuple[str, ...]) -> tuple[str, tuple[Observable, ...]]:
    path = (base_dir / datum.file).resolve()
    cols = read_columns(path, where, ("time_s",))
    time_s = cols["time_s"]
    require(bool(np.all(np.diff(time_s) > 0)), f"{where}.file", path.name, "time_s must increase row by row")
    by_probe = {c[:-2] if c.endswith("_C") else c: c for c in cols if c != "time_s"}
    names = _probe_names(datum.probes if datum.probes is not None else tuple(by_probe), where, probes, 1)
    absent = [p for p in names if p not in by_probe]
    require(not absent, f"{where}.probes", absent, f"no column in {path.name} (columns: {', '.join(cols)})")
    allowed = tuple(float(t) for t in PROBE_TEMPERATURES_C)
    temps = datum.temperatures_C
    if temps is not None:
        require(len(temps) > 0 and all(t in allowed for t in temps), f"{where}.temperatures_C", list(temps),
                f"must be a list of some of {', '.join(f'{t:g}' for t in allowed)} (C)")
    uK = datum.uncertainty_K
    out = []
    for p in names:
        T = cols[by_probe[p]]
        require(T[0] > 500.0 and float(np.min(T)) < T[0], f"{where}.file", f"{path.name} column {by_probe[p]}",
                "must be a cooling curve in C from above 500 C (a curve in K? subtract 273.15)")
        wanted = list(temps) if temps is not None else [t for t in allowed if T[0] > t >= float(np.min(T))]
        for Tc in wanted:
            t = time_to_temperature(time_s, T, Tc)
            require(t is not None and T[0] > Tc, f"{where}.temperatures_C", Tc, f"probe {p}'s measured curve never "
                    "passes it")
            assert t is not None
            label = f"{case}/{condition or '-'}:probes.{p}.t_to_C_s.{int(Tc)}"
            out.append(Observable(label, (Term(case, condition, f"probes.{p}.t_to_C_s.{int(Tc)}"),), value=t,
                                  sd=_crossing_sd(time_s, T, t, uK), group=group or "probes"))
    return f"{case}/{condition or '-'}:curves {', '.join(names)} ({path.name})", tuple(out)


def _traverse(datum: TraverseDatum, where: str, base_dir: Path, case: str, condition: str | None,
              group: str | None) -> tuple[str, tuple[Observable, ...]]:
    side = datum.side
    path = (base_dir / datum.file).resolve()
    cols = read_columns(path, where, ("depth_mm", "HRC"))
    require(bool(np.all(cols["depth_mm"] >= 0)), f"{where}.file", path.name, "depth_mm must be >= 0")
    require(bool(np.all((cols["HRC"] > 0) & (cols["HRC"] < 75))), f"{where}.file", path.name,
            "HRC must lie in 0-75 (a column in HV? convert it)")
    sd = datum.uncertainty
    out = []
    for depth, hrc in zip(cols["depth_mm"], cols["HRC"]):
        label = f"{case}/{condition or '-'}:traverse.{side}@{depth:g}"
        out.append(Observable(label, (Term(case, condition, f"{TRAVERSE_PREFIX}{side}@{depth:g}"),), value=float(hrc),
                              sd=sd, group=group or "traverse"))
    return f"{case}/{condition or '-'}:traverse {side} ({path.name})", tuple(out)


def _depth(datum: DepthDatum, case: str, condition: str | None, group: str | None
           ) -> tuple[str, tuple[Observable, ...]]:
    side, hrc, depth, tol, sd = datum.side, datum.hardness_HRC, datum.value, datum.tolerance, datum.uncertainty
    out = []
    for at, lower, upper in ((depth - tol, float(hrc), None), (depth + tol, None, float(hrc))):
        path = f"{TRAVERSE_PREFIX}{side}@{at:g}"
        out.append(Observable(f"{case}/{condition or '-'}:{path}", (Term(case, condition, path),), lower=lower,
                              upper=upper, sd=sd, group=group or "hardness_depth"))
    return (f"{case}/{condition or '-'}:HRC{hrc:g} depth {side} {depth:g} +- {tol:g} mm", tuple(out))


def parse_measurement(i: int, datum: Measured, base_dir: Path, cases: Mapping[str, Any],
                      probes: Callable[[str, str | None], tuple[str, ...]]) -> Measurement:
    """One ``[[measurements]]`` table, read against its declaration (:mod:`quenchsim.inputs.calibration`; see the
    module docstring); ``probes(case, condition)`` gives the probe names of a case at a condition (loading it: a
    condition not in the case is refused there)."""
    where = f"measurements[{i}]"
    require(datum.case in cases, f"{where}.case", datum.case,
            f"unknown case; the [cases] of this file: {', '.join(cases) or 'none'}")
    case, condition, group = datum.case, datum.condition_name, datum.group
    names = probes(case, condition)
    if isinstance(datum, (ValueDatum, BoundDatum)):
        label, obs, quantity = _scalar(datum, where, case, condition, group)
        if quantity.startswith("probes."):
            probe = quantity.split(".")[1]
            require(probe in names, f"{where}.quantity", quantity, f"no probe {probe!r}; the case's probes: "
                    f"{', '.join(names) or 'none'}")
        plain = isinstance(datum, ValueDatum) and obs.relation == "value"
        return Measurement(datum.kind, case, condition, label, datum.source, obs.group, (obs,),
                           quantity=quantity if plain else None, value=obs.value if plain else None,
                           uncertainty=obs.sd if plain else None)
    if isinstance(datum, OrderDatum):
        label, observables = _order(datum, where, case, condition, group, names)
    elif isinstance(datum, CurveDatum):
        label, observables = _curve(datum, where, base_dir, case, condition, group, names)
    elif isinstance(datum, DepthDatum):
        label, observables = _depth(datum, case, condition, group)
    else:
        label, observables = _traverse(datum, where, base_dir, case, condition, group)
    return Measurement(datum.kind, case, condition, label, datum.source, observables[0].group, observables)


def read_term(summary: Mapping[str, Any] | None, folder: Path | None, path: str) -> float | None:
    """A term's number in a finished run: a dotted path of its summary, or ``traverse.<side>@<depth_mm>`` read from its
    hardness_traverse.csv (linear interpolation); None when absent."""
    if summary is None:
        return None
    if path.startswith(TRAVERSE_PREFIX):
        if folder is None:
            return None
        from quenchsim.results import files

        side, depth = path[len(TRAVERSE_PREFIX):].split("@")
        csv_path = folder / files.HARDNESS_TRAVERSE_CSV
        if not csv_path.is_file():
            return None
        table = np.genfromtxt(csv_path, delimiter=",", names=True)
        return float(np.interp(float(depth), table["depth_mm"], table[f"HRC_from_{side}"]))
    return quantity(summary, path)


def quantity(summary: Mapping[str, Any] | None, dotted: str) -> float | None:
    """A number of summary.json by its dotted path, None when absent or not a number."""
    node: Any = summary
    for key in dotted.split("."):
        if not isinstance(node, Mapping) or key not in node:
            return None
        node = node[key]
    return float(node) if isinstance(node, (int, float)) and not isinstance(node, bool) else None
