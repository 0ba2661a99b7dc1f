"""A data file's material property (:mod:`quenchsim.materials.properties`: a number, ``{ value }``, ``{ T_C, value }``,
``{ poly_T_C }`` or ``{ per_phase }``) as a declared value type, its calibration priors checked."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from quenchsim.errors import require
from quenchsim.inputs.declare import CONVERTERS, PRIOR_KEYS, TYPE_NAMES, check_prior
from quenchsim.materials.properties import Property, parse_property


def check_priors(spec: Any, where: str) -> None:
    """Every ``range`` / ``range_factor`` in a data table (recursively), as :func:`check_prior` checks one entry."""
    if isinstance(spec, Mapping):
        check_prior(spec, where)
        for key, sub in spec.items():
            if key not in PRIOR_KEYS:
                check_priors(sub, f"{where}.{key}")


def read_property(value: Any, where: str) -> Property:
    """A property in one of its forms, its priors checked."""
    check_priors(value, where)
    return parse_property(value, where)


CONVERTERS[Property] = read_property
TYPE_NAMES[Property] = "a property (number, {value}, {T_C, value}, {poly_T_C} or {per_phase})"


ELEMENTS = ("C", "Si", "Mn", "Ni", "Cr", "Mo", "V", "Cu", "Co", "Al", "W", "P", "S")
"""Alloying elements a composition (wt %) may list."""
FORMULA_HELP = "must be a table {const = a0, C = a_C, Mn = a_Mn, sqrt_Mo = ...}"


def check_formula(formula: Mapping[str, float] | None, where: str) -> None:
    """A linear composition formula: terms ``const``, an element or ``sqrt_<element>``."""
    if formula is None:
        return
    require(bool(formula), where, dict(formula), FORMULA_HELP)
    for name, value in formula.items():
        base = name[5:] if name.startswith("sqrt_") else name
        require(name == "const" or base in ELEMENTS, f"{where}.{name}", value,
                f"term must be 'const', an element of {ELEMENTS} or sqrt_<element>")
