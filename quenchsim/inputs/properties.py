"""A data file's material property (:mod:`quenchsim.materials.properties`: a number, ``{ value }``, ``{ T_C, value }``,
``{ poly_T_C }`` or ``{ per_phase }``) as a declared value type, its calibration priors checked."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

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
