"""Case files: TOML loading, named conditions, defaults and validation.

A case file holds one ring, one steel and a process; ``[conditions.NAME]`` tables are deep-merged
over the base case to give each named condition (e.g. the nozzle speeds of conditions 1-3).
Lengths in the file are in mm (``*_mm``), times in s, temperatures in degrees C. Every error
names the field (dotted path), the value and what is allowed.

Top-level tables (see cases/crb_outer_ring.toml for a complete, commented example):

``material``       steel name (materials/NAME.toml)
``[geometry]``     ``type = "rectangular" | "spherical_outer" | "profile"`` and its dimensions
``[mesh]``         ``size_mm`` (core), ``surface_size_mm``, ``surface_layer_mm``
``[process]``      ``austenitising_temperature_C``, ``room_temperature_C``
``[quench]``       ``time_s``, ``htc_model = "bath" | "table"``, ``[quench.bath]`` (bath model) or
                   ``[quench.htc_table]`` (``T_C``, ``h_W_m2K``, ``ambient_C``; optional per-segment
                   ``[quench.htc_table.segments.NAME]``; ``time_s`` + ``h_W_m2K`` for HTC vs time)
``[air]``          ``temperature_C``, ``until_max_C`` (stop when the hottest point is below) or ``time_s``,
                   ``htc_model = "natural" | "table"`` with ``emissivity`` or ``[air.htc_table]``
``[[probes]]``     ``name``, ``r_mm``, ``z_mm``
``[time]``         step control: ``dt_initial_s``, ``dt_min_s``, ``dt_max_s``, ``max_dT_K``, ``max_dX``
``[output]``       ``frames`` (number of VTK frames)
``[mechanics]``    options passed to the stress solver (``enabled``, ``plasticity``, ``trip``)
``[measured]``     measured dimensions for the report (``before_mm``/``after_mm`` tables)
"""

from __future__ import annotations

import copy
import math
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from quenchsim.errors import InputError, require

DEFAULTS: dict[str, Any] = {
    "mesh": {"size_mm": 5.0, "surface_size_mm": 1.2, "surface_layer_mm": 10.0},
    "process": {"austenitising_temperature_C": 845.0, "room_temperature_C": 25.0},
    "air": {"temperature_C": 25.0, "until_max_C": 40.0, "time_s": 20000.0, "htc_model": "natural",
            "emissivity": 0.8},
    "time": {"dt_initial_s": 0.02, "dt_min_s": 1e-3, "dt_max_s": 120.0, "max_dT_K": 20.0, "max_dX": 0.1,
             "growth": 1.5},
    "output": {"frames": 40},
    "mechanics": {"enabled": True, "plasticity": True, "trip": True},
}


def deep_merge(base: dict[str, Any], override: dict[str, Any]) -> dict[str, Any]:
    """Recursively merge ``override`` into a copy of ``base`` (tables merge, other values replace)."""
    out = copy.deepcopy(base)
    for key, value in override.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = deep_merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def set_dotted(data: dict[str, Any], dotted: str, value: Any) -> None:
    """Set ``data["a"]["b"]["c"] = value`` for ``dotted = "a.b.c"`` (creating tables)."""
    keys = dotted.split(".")
    node = data
    for key in keys[:-1]:
        node = node.setdefault(key, {})
        if not isinstance(node, dict):
            raise InputError(dotted, value, f"'{key}' is not a table")
    node[keys[-1]] = value


def _number(data: dict[str, Any], key: str, field: str, *, positive: bool = False,
            minimum: float | None = None, maximum: float | None = None) -> float:
    if key not in data:
        raise InputError(field, None, "is required")
    value = data[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InputError(field, value, "must be a finite number")
    if positive:
        require(value > 0, field, value, "must be > 0")
    if minimum is not None:
        require(value >= minimum, field, value, f"must be >= {minimum}")
    if maximum is not None:
        require(value <= maximum, field, value, f"must be <= {maximum}")
    return float(value)


@dataclass
class Case:
    """A fully resolved case: the raw merged table plus where it came from."""

    name: str
    condition: str | None
    data: dict[str, Any]
    path: Path | None = None

    def get(self, dotted: str, default: Any = None) -> Any:
        node: Any = self.data
        for key in dotted.split("."):
            if not isinstance(node, dict) or key not in node:
                return default
            node = node[key]
        return node

    def resolved(self) -> dict[str, Any]:
        """The fully resolved inputs as written to a run's case.toml."""
        return {"name": self.name, "condition": self.condition or "", **self.data}

    def number(self, dotted: str, **kw: Any) -> float:
        table, _, key = dotted.rpartition(".")
        return _number(self.get(table, {}) if table else self.data, key, dotted, **kw)


def load_case(path: str | Path, condition: str | None = None,
              overrides: dict[str, Any] | None = None) -> Case:
    """Load a case file, merge ``[conditions.<condition>]`` and dotted ``overrides``, validate."""
    path = Path(path)
    if not path.is_file():
        raise InputError("case", str(path), "file not found")
    with path.open("rb") as fh:
        try:
            raw = tomllib.load(fh)
        except tomllib.TOMLDecodeError as exc:
            raise InputError("case", str(path), f"is not valid TOML ({exc})") from None
    return case_from_dict(raw, condition, overrides, path=path)


def case_from_dict(raw: dict[str, Any], condition: str | None = None,
                   overrides: dict[str, Any] | None = None, path: Path | None = None) -> Case:
    """Build and validate a case from a dict (as read from TOML); see :func:`load_case`."""
    conditions = raw.get("conditions", {})
    data = deep_merge(DEFAULTS, {k: v for k, v in raw.items() if k != "conditions"})
    if condition is not None:
        condition = str(condition)
        if condition not in conditions:
            raise InputError("--condition", condition,
                             f"not in this case; available: {', '.join(sorted(conditions)) or 'none'}")
        data = deep_merge(data, conditions[condition])
    elif conditions:
        raise InputError("--condition", None, f"required; available: {', '.join(sorted(conditions))}")
    for dotted, value in (overrides or {}).items():
        set_dotted(data, dotted, value)
    case = Case(name=str(raw.get("name", path.stem if path else "case")), condition=condition,
                data=data, path=path)
    validate(case)
    return case


def validate(case: Case) -> None:
    """Check the fields every stage needs; geometry and probes are checked by their builders."""
    from quenchsim.materials import load_material  # data lookup only

    if "material" not in case.data:
        raise InputError("material", None, "is required (a name in materials/)")
    load_material(str(case.data["material"]))
    case.number("process.austenitising_temperature_C", minimum=600.0, maximum=1200.0)
    case.number("process.room_temperature_C", minimum=-50.0, maximum=100.0)
    case.number("quench.time_s", positive=True)
    case.number("mesh.size_mm", positive=True)
    case.number("mesh.surface_size_mm", positive=True)
    case.number("mesh.surface_layer_mm", minimum=0.0)
    model = case.get("quench.htc_model", "table")
    require(model in ("bath", "table"), "quench.htc_model", model, "must be 'bath' or 'table'")
    if model == "table":
        require(isinstance(case.get("quench.htc_table"), dict), "quench.htc_table", case.get("quench.htc_table"),
                "required when quench.htc_model = 'table'")
    air_model = case.get("air.htc_model")
    require(air_model in ("natural", "table"), "air.htc_model", air_model, "must be 'natural' or 'table'")
    for key in ("dt_initial_s", "dt_min_s", "dt_max_s", "max_dT_K", "max_dX"):
        case.number(f"time.{key}", positive=True)
    require(case.number("time.growth") > 1.0, "time.growth", case.get("time.growth"), "must be > 1")
    frames = case.get("output.frames")
    require(isinstance(frames, int) and frames >= 2, "output.frames", frames, "must be an integer >= 2")
    probes = case.get("probes", [])
    require(isinstance(probes, list), "probes", probes, "must be an array of tables [[probes]]")
    names = set()
    for i, probe in enumerate(probes):
        field = f"probes[{i}]"
        require(isinstance(probe, dict) and isinstance(probe.get("name"), str), f"{field}.name",
                probe.get("name") if isinstance(probe, dict) else probe, "must be a string")
        require(probe["name"] not in names, f"{field}.name", probe["name"], "must be unique")
        names.add(probe["name"])
        _number(probe, "r_mm", f"{field}.r_mm", minimum=0.0)
        _number(probe, "z_mm", f"{field}.z_mm")
