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
from collections.abc import Iterable, Iterator, Mapping
from dataclasses import dataclass, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

from quenchsim.errors import InputError
from quenchsim.inputs.reader import read_toml, reading
from quenchsim.materials.properties import PHASES, Property, parse_property
from quenchsim.shipped import shipped_dir

if TYPE_CHECKING:   # the steel's declarations (quenchsim.inputs.steel) read the property forms defined here
    from quenchsim.inputs.steel import LatentHeat, Steel, Thermal

__all__ = ["PHASES", "Property", "parse_property", "materials_dir", "load_material", "load_steel", "as_steel",
           "ThermalProperties",
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
    ``"mechanics"`` and the file its ``tempering`` key names (relative to it) as ``"tempering"`` (the table the
    calibration scales; the checked steel is :func:`load_steel`)."""
    path = find_data_file(name, field=field)
    data = load_data_file(str(path), field=field)
    mech_path = _mechanics_file(path)
    if "mechanics" not in data and mech_path.is_file():
        data["mechanics"] = read_toml(mech_path, f"{field} mechanics")
    tempering = _tempering_file(path, data)
    if tempering is not None:
        data["tempering"] = load_data_file(str(tempering), field=f"{Path(name).stem}.tempering")
    data.setdefault("name", Path(name).stem)
    return data


def _mechanics_file(path: Path) -> Path:
    return path.with_name(f"{path.stem}.mechanics.toml")


def _tempering_file(path: Path, data: Mapping[str, Any]) -> Path | None:
    """The tempering data file the steel file ``path`` names (its ``tempering`` key), relative to the steel's file or
    to a data folder (a steel copied elsewhere keeps the shipped data); None when it names none or it is not found
    (the steel then has none, and a [temper] is refused naming the file)."""
    name = data.get("tempering")
    if not isinstance(name, str):
        return None
    found = [p for p in (path.parent / name, *(f / name for f in data_folders())) if p.is_file()]
    return found[0] if found else None


def load_steel(name: str, field: str = "material") -> Steel:
    """The checked steel ``name`` (:func:`find_data_file`): its file read against its declaration
    (:class:`quenchsim.inputs.steel.Steel`), its mechanics file beside it and its tempering data resolved. An error
    names the file at fault (the steel's or its mechanics file)."""
    from quenchsim.inputs.declare import from_table
    from quenchsim.inputs.steel import Steel
    from quenchsim.inputs.steel_mechanics import SteelMechanics
    from quenchsim.inputs.tempering import TemperingData

    path = find_data_file(name, field=field)
    table = load_material(name, field)
    own_file = read_toml(path, field)
    resolved: dict[str, Any] = {}   # the tables of other files, each read against its declaration in its file
    mech_path = _mechanics_file(path)
    if isinstance(table.get("mechanics"), Mapping) and mech_path.is_file() and "mechanics" not in own_file:
        with reading(mech_path):
            resolved["mechanics"] = from_table(SteelMechanics, table["mechanics"])
    tempering_path = _tempering_file(path, own_file)
    if tempering_path is not None:
        with reading(tempering_path):
            resolved["tempering"] = from_table(TemperingData, table["tempering"])
    own = {k: v for k, v in table.items() if k not in resolved}
    with reading(path):
        steel = from_table(Steel, own, path=path, table=table, **resolved)
    return steel if steel.name else replace(steel, name=path.stem)


def as_steel(material: Steel | Mapping[str, Any]) -> Steel:
    """A steel: ``material`` itself, or the steel of a table built in code (:func:`load_material`'s form, its keys
    named under its ``name``)."""
    from quenchsim.inputs.steel import Steel, steel_from_table

    if isinstance(material, Steel):
        return material
    return steel_from_table(material, str(material.get("name", "material")))


def transforms(material: Steel | Mapping[str, Any], field: str = "material") -> bool:
    """Whether the material's austenite transforms on cooling (its ``transformations`` key, checked)."""
    return as_steel(material).transforms


@dataclass(frozen=True)
class ThermalProperties:
    """rho(T, X), k(T, X), c_p(T, X) and the latent heat L_i(T) (J/kg) released by austenite -> phase i."""

    density_kg_m3: Property
    conductivity_W_mK: Property
    specific_heat_J_kgK: Property
    latent_heat_J_kg: dict[str, Property]


def thermal_properties(material: Steel | Mapping[str, Any]) -> ThermalProperties:
    """The thermal properties of a steel's ``[thermal]`` and ``[latent_heat]`` tables."""
    steel = as_steel(material)
    if steel.thermal is None:
        raise InputError(f"{steel.name}.thermal", None, "the material needs a [thermal] table")
    return thermal_properties_of(steel.thermal, steel.latent_heat)


def thermal_properties_of(thermal: Thermal, latent: LatentHeat | None = None) -> ThermalProperties:
    """The thermal properties of a declared ``[thermal]`` table (a steel's, or the ISO 9950 probe's) and latent
    heats (none by default)."""
    if latent is None:
        from quenchsim.inputs.steel import LatentHeat

        latent = LatentHeat()
    return ThermalProperties(density_kg_m3=thermal.density_kg_m3, conductivity_W_mK=thermal.conductivity_W_mK,
                             specific_heat_J_kgK=thermal.specific_heat_J_kgK,
                             latent_heat_J_kg={phase: getattr(latent, f"{phase}_J_kg") for phase in PHASES[1:]})
