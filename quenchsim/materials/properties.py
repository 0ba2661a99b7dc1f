"""Temperature- and phase-dependent material properties parsed from TOML specs.

A property spec in a materials/*.toml file takes one of these forms (T in degrees C)::

    density_kg_m3 = 7850                                          # constant
    specific_heat_J_kgK = { value = 419, source = "..." }         # constant with source
    conductivity_W_mK = { T_C = [30, 300, 600, 800],               # table, linear in T,
                          value = [25.2, 31.5, 31.5, 25.2], source = "..." }   # clamped at the ends
    E_Pa = { poly_T_C = [2.12e11, -5.27e7], source = "..." }      # polynomial a0 + a1 T + a2 T^2 ...
    conductivity_W_mK = { per_phase = { austenite = { poly_T_C = [16.8, 0.0119] },
                                        martensite = 39.3 }, source = "..." }

A per-phase property is mixed linearly by the phase fractions (rule of mixtures),
``p(T, X) = sum_i X_i p_i(T)``; phases missing from ``per_phase`` use the ``default`` entry if
present. Every spec is parsed once into a :class:`Property`, a callable vectorised over arrays.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, cast

import numpy as np

from quenchsim.errors import InputError

PHASES: tuple[str, ...] = ("austenite", "pearlite", "bainite", "martensite")
"""Phase names used everywhere (fractions sum to one; undissolved carbide belongs to the matrix)."""


@dataclass(frozen=True)
class Property:
    """A property p(T_C) or p(T_C, phase fractions); call it with arrays of any shape."""

    kind: str
    constant: float = 0.0
    T_C: np.ndarray | None = None
    values: np.ndarray | None = None
    coefficients: np.ndarray | None = None
    phases: Mapping[str, "Property"] = field(default_factory=dict)
    source: str = ""

    def __call__(self, T_C: Any, fractions: Mapping[str, np.ndarray] | None = None) -> np.ndarray:
        T = np.asarray(T_C, dtype=float)
        if self.kind == "constant":
            return np.full_like(T, self.constant)
        # a "table" property always carries T_C and values, a "poly" one its coefficients (see parse_property)
        if self.kind == "table":
            return np.interp(T, cast(np.ndarray, self.T_C), cast(np.ndarray, self.values))
        if self.kind == "poly":
            return np.polynomial.polynomial.polyval(T, cast(np.ndarray, self.coefficients))
        # per-phase mixture
        if fractions is None:
            raise ValueError("a per-phase property needs the phase fractions")
        out = np.zeros(np.broadcast_shapes(T.shape, np.shape(next(iter(fractions.values())))))
        for phase, X in fractions.items():
            out += X * self.for_phase(phase)(T)
        return out

    @property
    def phase_dependent(self) -> bool:
        return self.kind == "per_phase"

    def for_phase(self, phase: str) -> "Property":
        """The property of one phase (the property itself when it is not phase dependent)."""
        if self.kind != "per_phase":
            return self
        if phase in self.phases:
            return self.phases[phase]
        if "default" in self.phases:
            return self.phases["default"]
        raise KeyError(phase)


def parse_property(spec: Any, field_name: str) -> Property:
    """Parse one property spec (see module docstring); errors name ``field_name``."""
    if isinstance(spec, bool):
        raise InputError(field_name, spec, "must be a number or a table {value|T_C+value|poly_T_C|per_phase}")
    if isinstance(spec, (int, float)):
        return Property("constant", constant=float(spec))
    if not isinstance(spec, Mapping):
        raise InputError(field_name, spec, "must be a number or a table {value|T_C+value|poly_T_C|per_phase}")
    source = str(spec.get("source", ""))
    if "per_phase" in spec:
        phases_spec = spec["per_phase"]
        if not isinstance(phases_spec, Mapping) or not phases_spec:
            raise InputError(f"{field_name}.per_phase", phases_spec, "must be a table phase -> property")
        phases = {}
        for phase, sub in phases_spec.items():
            if phase not in PHASES and phase != "default":
                raise InputError(f"{field_name}.per_phase.{phase}", phase, f"phase must be one of {PHASES} or 'default'")
            phases[phase] = parse_property(sub, f"{field_name}.per_phase.{phase}")
        missing = [p for p in PHASES if p not in phases]
        if missing and "default" not in phases:
            raise InputError(f"{field_name}.per_phase", sorted(phases), f"missing phases {missing} (or give 'default')")
        return Property("per_phase", phases=phases, source=source)
    if "T_C" in spec:
        T = np.asarray(spec["T_C"], dtype=float)
        v = np.asarray(spec.get("value", []), dtype=float)
        if T.ndim != 1 or T.size < 1 or v.shape != T.shape:
            raise InputError(f"{field_name}.value", spec.get("value"), f"must be a list as long as T_C ({T.size})")
        if np.any(np.diff(T) <= 0):
            raise InputError(f"{field_name}.T_C", spec["T_C"], "temperatures must be strictly increasing")
        return Property("table", T_C=T, values=v, source=source)
    if "poly_T_C" in spec:
        c = np.asarray(spec["poly_T_C"], dtype=float)
        if c.ndim != 1 or c.size < 1:
            raise InputError(f"{field_name}.poly_T_C", spec["poly_T_C"], "must be a list of coefficients a0, a1, ...")
        return Property("poly", coefficients=c, source=source)
    if "value" in spec:
        value = spec["value"]
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise InputError(f"{field_name}.value", value, "must be a number")
        return Property("constant", constant=float(value), source=source)
    raise InputError(field_name, dict(spec), "needs one of: value, T_C + value, poly_T_C, per_phase")
