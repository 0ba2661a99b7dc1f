"""Material and quenchant data files (materials/*.toml), where they are found, and their property functions.

A steel is described by ``NAME.toml`` (composition, thermal properties, latent heats, kinetics, hardness) and
optionally ``NAME.mechanics.toml`` beside it (elastic, plastic, specific-volume and TRIP data);
:func:`load_material` merges the second into the key ``"mechanics"``. Quenchants are ``quenchants/NAME.toml``,
bath layouts ``baths/NAME.toml``. Every number in those files carries a ``source``. The property spec forms are
described in :mod:`quenchsim.materials.properties`.

**Where a name is found** (:func:`find_data_file`, the one place that resolves names; docs/guide/run_a_ring.md,
"Your own data"): a name is looked up in these data folders, first match wins, each laid out like the shipped
``materials/`` (steels at the top, ``quenchants/``, ``baths/``):

1. the folders of ``--data DIR`` (run, sweep, calibrate, optimise, bath, cct, material fit, quenchant), in the
   order given;
2. the folders of the environment variable ``QUENCHSIM_DATA`` (``os.pathsep``-separated);
3. ``./materials`` of the current directory (where the fitters write by default);
4. the shipped data (:func:`materials_dir`: the checkout's ``materials/``, or the wheel's copy), read-only.

So a user's file shadows a shipped one of the same name in the user's runs. A name ending in ``.toml`` is a path
and is read as it is. The validation studies run with the shipped data only (:func:`shipped_data_only`, used by
``quenchsim validate``): a user's folder never changes which steel or oil a study loads, nor its fingerprint.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from quenchsim.errors import InputError
from quenchsim.inputs.reader import read_toml
from quenchsim.materials.properties import PHASES, Property, parse_property
from quenchsim.shipped import shipped_dir

__all__ = ["PHASES", "Property", "parse_property", "materials_dir", "load_material", "ThermalProperties",
           "thermal_properties", "load_data_file", "find_data_file", "data_folders", "use_data_folders",
           "shipped_data_only", "USER_DATA_FOLDER", "DATA_ENV"]

DATA_ENV = "QUENCHSIM_DATA"
"""Environment variable: the user's data folders, ``os.pathsep``-separated, searched before the shipped data
(``--data DIR`` puts its folders in front of it, so that Dask workers started by the command inherit them)."""

SHIPPED_ONLY_ENV = "QUENCHSIM_SHIPPED_DATA_ONLY"
"""Set (to "1") by :func:`shipped_data_only`: names resolve in the shipped data only."""

USER_DATA_FOLDER = "materials"
"""The current directory's data folder, searched after the ``--data`` / ``QUENCHSIM_DATA`` folders and written by
the fitters by default (``./materials/NAME.toml``, ``./materials/quenchants/NAME.toml``)."""


def materials_dir() -> Path:
    """The shipped data folder (read-only): the checkout's ``materials/`` (source or editable install), else the
    copy an installed wheel carries in the package (``quenchsim/_data/materials``)."""
    return shipped_dir("materials")


def data_folders() -> list[Path]:
    """The data folders a name is looked up in, first match wins: the ``--data`` / ``QUENCHSIM_DATA`` folders,
    ``./materials``, then the shipped folder (each once; the shipped one only inside :func:`shipped_data_only`)."""
    shipped = materials_dir()
    folders: list[Path] = []
    if not os.environ.get(SHIPPED_ONLY_ENV):
        folders += [Path(p).expanduser() for p in os.environ.get(DATA_ENV, "").split(os.pathsep) if p]
        folders.append(Path.cwd() / USER_DATA_FOLDER)
    out: list[Path] = []
    for folder in [*folders, shipped]:
        if folder.resolve() not in [f.resolve() for f in out]:
            out.append(shipped if folder.resolve() == shipped.resolve() else folder)
    return out


def use_data_folders(folders: Iterable[str | Path]) -> None:
    """Put ``folders`` (``--data DIR``) in front of the search path of this process and the processes it starts. A
    folder that does not exist is an :class:`InputError`."""
    paths = [Path(f).expanduser().resolve() for f in folders]
    for folder in paths:
        if not folder.is_dir():
            raise InputError("--data", str(folder), "is not a folder (a data folder laid out like materials/: "
                                                    "NAME.toml, quenchants/NAME.toml)")
    old = [p for p in os.environ.get(DATA_ENV, "").split(os.pathsep) if p]
    os.environ[DATA_ENV] = os.pathsep.join([*map(str, paths), *old])


@contextlib.contextmanager
def shipped_data_only() -> Iterator[None]:
    """Within the block (and in processes started in it) names resolve in the shipped data only: the validation
    studies and their cached runs never depend on a user's folders."""
    old = os.environ.get(SHIPPED_ONLY_ENV)
    os.environ[SHIPPED_ONLY_ENV] = "1"
    try:
        yield
    finally:
        if old is None:
            os.environ.pop(SHIPPED_ONLY_ENV, None)
        else:
            os.environ[SHIPPED_ONLY_ENV] = old


def _known(subdirs: tuple[str, ...]) -> list[str]:
    return sorted({p.stem for f in data_folders() for s in subdirs for p in (f / s).glob("*.toml")
                   if ".mechanics" not in p.name})


def find_data_file(name: str, subdir: str | tuple[str, ...] = "", field: str = "material") -> Path:
    """The file of data name ``name`` in ``subdir`` ("" for steels, "quenchants", "baths", "data" for CCT/TTT data
    files; a tuple: each in turn) on the search path (:func:`data_folders`, first match wins), or the path ``name``
    when it ends in ``.toml``. An unknown name is an :class:`InputError` that lists the folders searched and the
    names known there."""
    if name.endswith(".toml"):
        path = Path(name).expanduser()
        if not path.is_file():
            raise InputError(field, name, "no such file")
        return path
    subdirs = (subdir,) if isinstance(subdir, str) else subdir
    for folder in data_folders():
        for sub in subdirs:
            path = folder / sub / f"{name}.toml"
            if path.is_file():
                return path
    searched = ", ".join(str(f / s) for f in data_folders() for s in subdirs)
    raise InputError(field, name, f"unknown; known: {', '.join(_known(subdirs)) or 'none'} (searched {searched})")


def load_data_file(name: str, subdir: str | tuple[str, ...] = "", field: str = "material") -> dict[str, Any]:
    """The table of data file ``name`` (:func:`find_data_file`)."""
    return read_toml(find_data_file(name, subdir, field), field)


def load_material(name: str, field: str = "material") -> dict[str, Any]:
    """The raw material table of steel ``name``, with ``NAME.mechanics.toml`` (beside the steel's file) merged as
    ``"mechanics"`` and the file its ``tempering`` key names (relative to it) as ``"tempering"``."""
    path = find_data_file(name, field=field)
    data = load_data_file(str(path), field=field)
    mech_path = path.with_name(f"{path.stem}.mechanics.toml")
    if "mechanics" not in data and mech_path.is_file():
        data["mechanics"] = read_toml(mech_path, f"{field} mechanics")
    if isinstance(data.get("tempering"), str):
        # a tempering data file, relative to the steel's file or to a data folder (a steel copied elsewhere keeps
        # the shipped data); not found, the steel has none (a [temper] is then refused, naming the file)
        found = [p for p in (path.parent / data["tempering"], *(f / data["tempering"] for f in data_folders()))
                 if p.is_file()]
        if found:
            data["tempering"] = load_data_file(str(found[0]), field=f"{Path(name).stem}.tempering")
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
