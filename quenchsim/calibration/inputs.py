"""Uncertain inputs: a data-file entry with a declared prior, addressed by a path, and scaled by a factor.

A free input is named by a dotted path ``KIND.NAME.KEY...``:

``material.SUJ3.mechanics.plastic.yield_Pa.per_phase.austenite``
    ``KIND`` the data-file family (``material``: ``materials/NAME.toml`` with ``NAME.mechanics.toml`` merged
    under ``mechanics``, :func:`quenchsim.materials.load_material`; ``quenchant``: ``materials/quenchants/NAME.toml``;
    ``bath``: the bath model's declared flow constants ``materials/baths/NAME.toml`` named by ``quench.bath.constants``,
    e.g. ``bath.jet_bath.flow.corner_carryover``; ``layout``: a nozzle layout ``materials/baths/NAME.toml`` named by
    ``quench.bath.layout``, e.g. ``layout.reference_nozzles.nozzles.id.standoff_mm``),
    ``NAME`` the file (or ``.toml`` path stem), ``KEY...`` the dotted keys of an entry in it.

The entry, or the nearest table above it, must carry a prior (:data:`quenchsim.mechanics.model.PRIOR_KEYS`):
``range_factor = f`` (the value times a factor in [1/f, f]) or ``range = [lo, hi]`` (a factor in
[lo/v, hi/v], v the entry's value, or the first value of a table; for a negative quantity, with bounds of its sign,
the same factors in order). The input is that factor, applied to
every number of the entry (``value``, ``poly_T_C``, ``per_phase`` entries; temperatures and the prior itself
are kept), with a log-uniform prior between its bounds: every band in the data files is a factor band on a
positive quantity, and a log-uniform prior is the one that treats x f and / f alike.

A run with inputs set is an ordinary run: :func:`derived_files` writes the changed data files (complete,
with their priors) and returns the case overrides (``material``, ``quench.bath.quenchant``, ``quench.bath.constants``,
``quench.bath.layout``) that point the
case at them. No run code knows about calibration.
"""

from __future__ import annotations

import copy
import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

import numpy as np
import tomli_w

from quenchsim.case import Case
from quenchsim.errors import InputError
from quenchsim.materials import load_data_file, load_material

_Unit = TypeVar("_Unit", float, np.ndarray)
"""A point of the unit interval, or an array of them (:meth:`FreeInput.factor` maps either)."""

PRIOR_KEYS = ("range", "range_factor")
"""The prior keys of a data-file entry (as checked by quenchsim.mechanics.model.check_priors)."""
SCALED_KEYS = ("value", "poly_T_C")
"""The keys of a property table whose numbers a factor scales (temperatures ``T_C`` and the prior are kept)."""


@dataclass(frozen=True)
class DataKind:
    """A data-file family: how to load one file by name and which case field names it."""

    case_field: str
    subdir: str
    default: str | None = None
    """The file a bath-model case reads when its field is not given (``quench.bath.constants``: jet_bath)."""


KINDS: dict[str, DataKind] = {
    "material": DataKind(case_field="material", subdir=""),
    "quenchant": DataKind(case_field="quench.bath.quenchant", subdir="quenchants"),
    "bath": DataKind(case_field="quench.bath.constants", subdir="baths", default="jet_bath"),
    "layout": DataKind(case_field="quench.bath.layout", subdir="baths"),
}


def load_data(kind: str, name: str) -> dict[str, Any]:
    """The complete table of a data file (a material with its mechanics merged)."""
    if kind == "material":
        return load_material(name)
    return load_data_file(name, subdir=KINDS[kind].subdir, field=kind)


@dataclass(frozen=True)
class FreeInput:
    """One free input: ``path`` (see the module docstring), its factor bounds, the entry's nominal value and
    the prior's source text."""

    path: str
    kind: str
    data_name: str
    keys: tuple[str, ...]
    factor_bounds: tuple[float, float]
    nominal: Any
    prior: str
    source: str

    @property
    def label(self) -> str:
        """A short name: the last two keys (``per_phase.austenite`` -> ``yield_Pa.austenite``)."""
        keys = [k for k in self.keys if k != "per_phase"]
        return ".".join(keys[-2:])

    def factor(self, u: _Unit) -> _Unit:
        """The factor at ``u`` in [0, 1] (log-uniform prior: u = 0 the lower, 1 the upper bound)."""
        lo, hi = self.factor_bounds
        return lo * (hi / lo) ** u

    def unit(self, factor: float) -> float:
        """The inverse of :meth:`factor`."""
        lo, hi = self.factor_bounds
        return math.log(factor / lo) / math.log(hi / lo)


def first_value(spec: Any) -> float | None:
    """The entry's value, or the first value of its table (the number a range applies to)."""
    value = spec.get("value") if isinstance(spec, Mapping) else spec
    if isinstance(value, list) and value:
        value = value[0]
    return float(value) if isinstance(value, (int, float)) and not isinstance(value, bool) else None


def _scaled(spec: Any, factor: float) -> tuple[Any, int]:
    """``spec`` with its numbers times ``factor`` and how many were scaled; a ``range`` still holds the value."""
    if isinstance(spec, bool) or spec is None:
        return spec, 0
    if isinstance(spec, (int, float)):
        return spec * factor, 1
    if isinstance(spec, list):
        if all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in spec):
            return [x * factor for x in spec], len(spec)
        return spec, 0
    if not isinstance(spec, Mapping):
        return spec, 0
    out, count = dict(spec), 0
    for key in (*SCALED_KEYS, "per_phase"):
        if key not in out:
            continue
        if key == "per_phase" and isinstance(out[key], Mapping):
            phases = {}
            for phase, sub in out[key].items():
                phases[phase], n = _scaled(sub, factor)
                count += n
            out[key] = phases
        else:
            out[key], n = _scaled(out[key], factor)
            count += n
    rng = out.get("range")
    if isinstance(rng, list) and isinstance(out.get("value"), (int, float)):
        out["value"] = min(max(out["value"], rng[0]), rng[1])   # a factor at its bound, to round-off
    return out, count


def _walk(table: Mapping[str, Any], keys: tuple[str, ...], path: str) -> list[Any]:
    """The nodes from the table down to the entry (every node on the way)."""
    nodes: list[Any] = [table]
    for i, key in enumerate(keys):
        node = nodes[-1]
        if not isinstance(node, Mapping) or key not in node:
            known = sorted(k for k in node if k not in PRIOR_KEYS and k != "source") if isinstance(node, Mapping) else []
            raise InputError(path, ".".join(keys[: i + 1]),
                             f"is not an entry of the data file; keys here: {', '.join(known) or 'none'}")
        nodes.append(node[key])
    return nodes


def free_input(path: str, field: str = "inputs") -> FreeInput:
    """Parse and check one free-input path against its data file: the entry exists, holds numbers, and it
    (or a table above it) declares a prior."""
    if not isinstance(path, str) or path.count(".") < 2:
        raise InputError(field, path, "must be a path KIND.NAME.KEY... e.g. material.SUJ3.mechanics.trip.K_1_Pa")
    kind, rest = path.split(".", 1)
    if kind not in KINDS:
        raise InputError(field, path, f"unknown data kind {kind!r}; allowed: {', '.join(KINDS)}")
    name, _, tail = rest.partition(".")
    if name.endswith(".toml") or not tail:
        raise InputError(field, path, "must be KIND.NAME.KEY... with NAME a data file name (no .toml)")
    table = load_data(kind, name)
    keys = tuple(tail.split("."))
    nodes = _walk(table, keys, field)
    entry = nodes[-1]
    if _scaled(entry, 1.0)[1] == 0:
        raise InputError(field, path, "holds no number to scale (a value, poly_T_C or per_phase entries)")
    holder = next((n for n in reversed(nodes[1:]) if isinstance(n, Mapping) and any(k in n for k in PRIOR_KEYS)), None)
    if holder is None:
        raise InputError(field, path, "has no prior in its data file: add range = [lo, hi] or range_factor = f "
                                      "(with its source) to the entry or its table")
    if "range_factor" in holder:
        f = float(holder["range_factor"])
        bounds, prior = (1.0 / f, f), f"range_factor {f:g}"
    else:
        lo, hi = (float(x) for x in holder["range"])
        v = first_value(holder)
        if v is None or v == 0.0 or lo * v <= 0.0 or hi * v <= 0.0:
            raise InputError(field, path, f"range {holder['range']} needs a value of the same sign as both bounds (not "
                                          "0) to be a factor band")
        a, b = lo / v, hi / v   # a negative quantity: its factor band is the bounds over it, in order
        bounds, prior = (min(a, b), max(a, b)), f"range [{lo:g}, {hi:g}]"
    if not bounds[0] < bounds[1]:
        raise InputError(field, path, f"its prior {prior} has zero width: nothing to calibrate")
    source = holder.get("source") or (entry.get("source", "") if isinstance(entry, Mapping) else "")
    return FreeInput(path=path, kind=kind, data_name=name, keys=keys, factor_bounds=bounds,
                     nominal=copy.deepcopy(entry), prior=prior, source=str(source))


def declared_priors(kind: str, name: str) -> list[FreeInput]:
    """Every entry of a data file that declares a prior, as free inputs (the priors' propagation when nothing
    was calibrated). A table with a prior counts once (its entries are scaled together)."""
    found: list[FreeInput] = []

    def visit(node: Any, keys: tuple[str, ...]) -> None:
        if not isinstance(node, Mapping):
            return
        if keys and any(k in node for k in PRIOR_KEYS) and _scaled(node, 1.0)[1] > 0:
            found.append(free_input(".".join((kind, name, *keys))))
            return
        for key, sub in node.items():
            if key not in PRIOR_KEYS:
                visit(sub, (*keys, key))

    visit(load_data(kind, name), ())
    return found


def with_factors(table: dict[str, Any], inputs: list[FreeInput], factors: list[float]) -> dict[str, Any]:
    """A deep copy of ``table`` with each input's entry scaled by its factor."""
    out = copy.deepcopy(table)
    for inp, factor in zip(inputs, factors):
        parent = out
        for key in inp.keys[:-1]:
            parent = parent[key]
        parent[inp.keys[-1]] = _scaled(parent[inp.keys[-1]], factor)[0]
    return out


def derived_files(inputs: list[FreeInput], factors: list[float], folder: Path,
                  note: str | None = None) -> dict[str, str]:
    """Write each data file that an input changes, scaled, into ``folder`` as ``NAME.toml`` (complete: a
    material with its mechanics) and return the case overrides that point a case at them. ``note`` is
    appended to every changed entry's ``source`` (e.g. how a calibration fixed it)."""
    overrides: dict[str, str] = {}
    files: dict[tuple[str, str], list[int]] = {}
    for i, inp in enumerate(inputs):
        files.setdefault((inp.kind, inp.data_name), []).append(i)
    folder.mkdir(parents=True, exist_ok=True)
    for (kind, name), index in files.items():
        chosen = [inputs[i] for i in index]
        table = with_factors(load_data(kind, name), chosen, [factors[i] for i in index])
        if note:
            for inp, i in zip(chosen, index):
                entry = table
                for key in inp.keys:
                    entry = entry[key]
                if isinstance(entry, dict):
                    entry["source"] = f"{entry.get('source', '')} | {note}: factor {factors[i]:.4g} on the prior's value".strip(" |")
        path = folder / f"{name}.toml"
        text = tomli_w.dumps(table)
        if not path.is_file() or path.read_text() != text:
            path.write_text(text)
        overrides[KINDS[kind].case_field] = str(path.resolve())
    return overrides


def data_name(kind: str, case: Case) -> Any:
    """The data file of family ``kind`` a case reads (its field's value, or the family's default for a bath-model
    case), or None."""
    spec = KINDS[kind]
    return case.get(spec.case_field, spec.default if case.get("quench.htc_model") == "bath" else None)


def used_by(inp: FreeInput, case: Case) -> bool:
    """Whether a case reads the input's data file."""
    name = data_name(inp.kind, case)
    return isinstance(name, str) and Path(name).stem == inp.data_name
