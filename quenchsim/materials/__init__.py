"""Material and quenchant data files (materials/*.toml) and their property functions.

A steel is described by ``materials/NAME.toml`` (composition, thermal properties, latent heats,
kinetics, hardness) and optionally ``materials/NAME.mechanics.toml`` (elastic, plastic,
specific-volume and TRIP data); :func:`load_material` merges the second into the key
``"mechanics"``. Every number in those files carries a ``source``. The property spec forms are
described in :mod:`quenchsim.materials.properties`.
"""

from __future__ import annotations

import os
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from quenchsim.errors import InputError
from quenchsim.materials.properties import PHASES, Property, parse_property

__all__ = ["PHASES", "Property", "parse_property", "materials_dir", "load_material", "ThermalProperties",
           "thermal_properties", "load_data_file"]


def materials_dir() -> Path:
    """The data directory: ``$QUENCHSIM_MATERIALS``, else the checkout's ``materials/`` (source or editable
    install), else the copy an installed wheel carries in the package (``quenchsim/_data/materials``)."""
    env = os.environ.get("QUENCHSIM_MATERIALS")
    if env:
        return Path(env)
    package = Path(__file__).resolve().parents[1]
    checkout = package.parent / "materials"
    return checkout if checkout.is_dir() else package / "_data" / "materials"


def load_data_file(name: str, subdir: str = "", field: str = "material") -> dict[str, Any]:
    """Load ``materials/[subdir/]NAME.toml`` (or an explicit path ending in .toml)."""
    folder = materials_dir() / subdir
    path = Path(name) if name.endswith(".toml") else folder / f"{name}.toml"
    if not path.is_file():
        known = sorted(p.stem for p in folder.glob("*.toml") if ".mechanics" not in p.name)
        raise InputError(field, name, f"unknown; known: {', '.join(known) or 'none'}")
    with path.open("rb") as fh:
        try:
            return tomllib.load(fh)
        except tomllib.TOMLDecodeError as exc:
            raise InputError(field, str(path), f"is not valid TOML ({exc})") from None


def load_material(name: str, field: str = "material") -> dict[str, Any]:
    """The raw material table of steel ``name``, with ``NAME.mechanics.toml`` merged as ``"mechanics"``."""
    data = load_data_file(name, field=field)
    mech = (Path(name).with_suffix("") if name.endswith(".toml") else materials_dir() / name)
    mech_path = mech.parent / f"{mech.name}.mechanics.toml"
    if "mechanics" not in data and mech_path.is_file():
        with mech_path.open("rb") as fh:
            data["mechanics"] = tomllib.load(fh)
    data.setdefault("name", Path(name).stem)
    return data


TRANSFORMATIONS = ("austenite", "none")
"""``transformations`` of a material file: ``"austenite"`` (default: the austenite decomposes on cooling; the file
needs [kinetics], [hardness] and the martensite data) or ``"none"`` (nothing transforms, e.g. an austenitic or
nickel alloy: only [thermal] is needed, the run is thermal only and reports no phases and no hardness)."""


def transforms(material: dict[str, Any], field: str = "material") -> bool:
    """Whether the material's austenite transforms on cooling (its ``transformations`` key, checked)."""
    value = material.get("transformations", "austenite")
    name = material.get("name", field)
    if value not in TRANSFORMATIONS:
        raise InputError(f"{name}.transformations", value, f"must be one of {', '.join(TRANSFORMATIONS)}")
    if value == "none" and "mechanics" in material:
        raise InputError(f"{name}.transformations", value, "a non-transforming material is thermal only: remove its "
                                                           "mechanics table/file (the stress model needs the phases)")
    return value != "none"


@dataclass(frozen=True)
class ThermalProperties:
    """rho(T, X), k(T, X), c_p(T, X) and the latent heat L_i(T) (J/kg) released by austenite -> phase i."""

    density_kg_m3: Property
    conductivity_W_mK: Property
    specific_heat_J_kgK: Property
    latent_heat_J_kg: dict[str, Property]


def thermal_properties(material: dict[str, Any]) -> ThermalProperties:
    """Parse the ``[thermal]`` and ``[latent_heat]`` tables of a material."""
    name = material.get("name", "material")
    thermal = material.get("thermal")
    if not isinstance(thermal, dict):
        raise InputError(f"{name}.thermal", thermal, "the material needs a [thermal] table")
    props = {}
    for key in ("density_kg_m3", "conductivity_W_mK", "specific_heat_J_kgK"):
        if key not in thermal:
            raise InputError(f"{name}.thermal.{key}", None, "is required")
        props[key] = parse_property(thermal[key], f"{name}.thermal.{key}")
    latent = {}
    for phase in PHASES[1:]:
        spec = material.get("latent_heat", {}).get(f"{phase}_J_kg", 0.0)
        latent[phase] = parse_property(spec, f"{name}.latent_heat.{phase}_J_kg")
    return ThermalProperties(latent_heat_J_kg=latent, **props)
