"""Loading a case file and checking every field before any work starts (one place, one error type).

Every check a run needs is done here: the material and its mechanics options, the geometry (the
profile is built), the probes (inside the section), the bath model or the HTC tables (against the
section's segment names), the step control and the output. A case that passes can be meshed and run.
"""

from __future__ import annotations

import copy
import math
import tomllib
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.case.model import (AirStage, Case, MechanicsOptions, MeshSpec, OutputSpec, Probe, ProcessSpec,
                                  QuenchStage, TemperStage, TimeControl, TransferStage)
from quenchsim.errors import InputError, did_you_mean, require, require_known_keys
from quenchsim.geometry.profile import MM, Profile, profile_from_case

DEFAULTS: dict[str, Any] = {
    "mesh": {"size_mm": 5.0, "surface_size_mm": 1.2, "surface_layer_mm": 10.0},
    "process": {"austenitising_temperature_C": 845.0, "room_temperature_C": 25.0},
    # emissivity 0.80: oxidised iron and steel at 200-600 C, total (FLIR T8xx user's manual, emissivity Table 38.1,
    # after Bramson, Infrared Radiation: A Handbook for Applications; 0.89 at 1227 C)
    "transfer": {"time_s": 0.0, "temperature_C": 25.0, "emissivity": 0.8},
    "air": {"temperature_C": 25.0, "until_max_C": 40.0, "time_s": 20000.0, "htc_model": "natural",
            "emissivity": 0.8},
    "time": {"dt_initial_s": 0.02, "dt_min_s": 1e-3, "dt_max_s": 120.0, "max_dT_K": 30.0, "max_dX": 0.02,
             "growth": 1.5, "mechanics_max_dT_K": 30.0, "mechanics_max_dX": 0.02},
    "output": {"frames": 40, "checkpoint_minutes": 5.0},
    "mechanics": {"enabled": True, "plasticity": True, "trip": True},
}

TABLE_KEYS: dict[str, tuple[str, ...]] = {
    "": ("name", "description", "material", "geometry", "mesh", "process", "transfer", "quench", "air", "temper",
         "time", "output", "mechanics", "probes", "measured", "peer", "conditions"),
    "mesh": ("size_mm", "surface_size_mm", "surface_layer_mm"),
    "process": ("austenitising_temperature_C", "room_temperature_C"),
    "transfer": ("time_s", "temperature_C", "emissivity"),
    "quench": ("time_s", "htc_model", "bath", "htc_table", "immersion_speed_mm_s"),
    "air": ("temperature_C", "until_max_C", "time_s", "htc_model", "emissivity", "htc_table"),
    "temper": ("temperature_C", "time_s", "htc_model", "emissivity", "htc_table", "cool_until_max_C", "cool_time_s"),
    "time": ("dt_initial_s", "dt_min_s", "dt_max_s", "max_dT_K", "max_dX", "growth", "mechanics_max_dT_K",
             "mechanics_max_dX"),
    "output": ("frames", "checkpoint_minutes"),
}
"""Known keys of each table (a key not listed is an error: a misspelt key must not be ignored)."""

TEMPER_DEFAULTS: dict[str, Any] = {"htc_model": "natural", "emissivity": 0.8, "cool_time_s": 20000.0}
"""Defaults of a ``[temper]`` table, merged only into a case that has one (a case without a temper keeps its resolved
inputs, hence its case_sha256); ``cool_until_max_C`` defaults to ``air.until_max_C``. Emissivity 0.80 as the
transfer's (oxidised steel)."""
TEMPER_MAX_C = 400.0
"""Highest tempering temperature of the tempering data (its third stage ends at 350 C after 1 h; the fourth stage,
carbide coarsening and recovery, is not modelled)."""


def deep_merge(base: Mapping[str, Any], override: Mapping[str, Any]) -> dict[str, Any]:
    """Recursively merge ``override`` into a copy of ``base`` (tables merge, other values replace)."""
    out = copy.deepcopy(dict(base))
    for key, value in override.items():
        if isinstance(value, Mapping) and isinstance(out.get(key), Mapping):
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


def _unset_dotted(data: dict[str, Any], dotted: str) -> None:
    """Remove the key at ``dotted`` (if present), so that its default applies."""
    *tables, key = dotted.split(".")
    node: Any = data
    for name in tables:
        node = node.get(name) if isinstance(node, dict) else None
    if isinstance(node, dict):
        node.pop(key, None)


def _number(table: Mapping[str, Any], key: str, field: str, *, positive: bool = False,
            minimum: float | None = None, maximum: float | None = None) -> float:
    if key not in table:
        raise InputError(field, None, "is required")
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InputError(field, value, "must be a finite number")
    if positive:
        require(value > 0, field, value, "must be > 0")
    if minimum is not None:
        require(value >= minimum, field, value, f"must be >= {minimum:g}")
    if maximum is not None:
        require(value <= maximum, field, value, f"must be <= {maximum:g}")
    return float(value)


def _table(data: Mapping[str, Any], name: str) -> Mapping[str, Any]:
    table = data.get(name, {})
    require(isinstance(table, Mapping), name, table, "must be a table")
    require_known_keys(table, TABLE_KEYS[name], name)
    return table


def _mechanics_keys() -> tuple[str, ...]:
    """The keys of a case's [mechanics]: the solver options less the austenitising temperature, which a case sets
    once, as process.austenitising_temperature_C (the run hands it to the mechanics)."""
    from quenchsim.mechanics import OPTION_KEYS

    return ("enabled", "fixed_point_mm", *(k for k in OPTION_KEYS if k != "austenitizing_T_C"))


def _no_second_austenitising_temperature(m: Mapping[str, Any], where: str) -> None:
    for key in ("austenitizing_T_C", "austenitising_T_C", "austenitising_temperature_C"):
        if key in m:
            raise InputError(f"{where}.{key}", m[key], "is not a mechanics option: a case has one austenitising "
                             "temperature, process.austenitising_temperature_C (the stress-free state too); set that")


def _condition_keys(name: str, condition: Any) -> None:
    """The key names of ``[conditions.<name>]`` and of the tables in it (the bath's and its nozzle rows
    included), checked whichever condition runs; their values are checked when the condition is run."""
    from quenchsim.bath import check_bath_keys

    where = f"conditions.{name}"
    require(isinstance(condition, Mapping), where, condition, "must be a table")
    for key in condition:
        require(key in TABLE_KEYS[""] and key != "conditions", f"{where}.{key}", condition[key],
                f"unknown table or key; [{where}] takes {', '.join(k for k in TABLE_KEYS[''] if k != 'conditions')}")
    if isinstance(condition.get("mechanics"), Mapping):
        _no_second_austenitising_temperature(condition["mechanics"], f"{where}.mechanics")
    for table, allowed in (*((k, v) for k, v in TABLE_KEYS.items() if k), ("mechanics", _mechanics_keys())):
        if isinstance(condition.get(table), Mapping):
            require_known_keys(condition[table], allowed, f"{where}.{table}")
    quench = condition.get("quench")
    if isinstance(quench, Mapping) and "bath" in quench:
        check_bath_keys(quench["bath"], f"{where}.quench.bath")


def load_case(path: str | Path, condition: str | None = None,
              overrides: Mapping[str, Any] | None = None) -> Case:
    """Load a case file, merge ``[conditions.<condition>]`` and dotted ``overrides``, check everything."""
    path = Path(path)
    if not path.is_file():
        raise InputError("case", str(path), "file not found")
    with path.open("rb") as fh:
        try:
            raw = tomllib.load(fh)
        except tomllib.TOMLDecodeError as exc:
            raise InputError("case", str(path), f"is not valid TOML ({exc})") from None
    require(raw, "case", str(path), "the file is empty (no keys, no tables): is it the case file you meant, or was "
                                    "it cut short?")
    return case_from_dict(raw, condition, overrides, path=path)


def case_from_dict(raw: Mapping[str, Any], condition: str | None = None,
                   overrides: Mapping[str, Any] | None = None, path: Path | None = None) -> Case:
    """Build and check a case from a dict (as read from TOML); see :func:`load_case`."""
    conditions = raw.get("conditions", {})
    require(isinstance(conditions, Mapping), "conditions", conditions, "must be a table of [conditions.NAME] tables")
    for key, table in conditions.items():
        _condition_keys(key, table)
    data = deep_merge(DEFAULTS, {k: v for k, v in raw.items() if k != "conditions"})
    if condition is not None:
        condition = str(condition)
        if not conditions:
            where = path.name if path is not None else "this case"
            raise InputError("--condition", condition, f"not in this case: {where} has no [conditions.NAME] tables at all "
                                                       "(is the file complete, not truncated?)")
        if condition not in conditions:
            raise InputError("--condition", condition, f"not in this case; available: {', '.join(sorted(conditions))}")
        data = deep_merge(data, conditions[condition])
    elif conditions:
        raise InputError("--condition", None, f"required; available: {', '.join(sorted(conditions))}")
    name = str(raw.get("name", path.stem if path else "case"))
    return build_case(data, name, condition, path, overrides)


def build_case(data: Mapping[str, Any], name: str, condition: str | None, path: Path | None,
               overrides: Mapping[str, Any] | None = None) -> Case:
    """Parse the merged table ``data`` (plus dotted ``overrides``) into a checked :class:`Case`."""
    data = deep_merge(data, {})
    for dotted, value in (overrides or {}).items():
        require(dotted.split(".")[0] != "conditions", dotted, value, "sets the case as run, its condition merged: "
                "give the key without conditions.<name>. and choose the condition")
        if value is None:
            _unset_dotted(data, dotted)
        else:
            set_dotted(data, dotted, value)
    data = deep_merge(DEFAULTS, data)   # a removed key falls back to its default
    for key in data:
        require(key in TABLE_KEYS[""], key, data[key],
                f"unknown table or key; a case takes {', '.join(TABLE_KEYS[''])}{did_you_mean(key, TABLE_KEYS[''])}")

    material = _material(data, path)
    data["material"] = material
    geometry = data.get("geometry", {})
    require(isinstance(geometry, Mapping), "geometry", geometry, "must be a table")
    profile = profile_from_case(dict(geometry))
    reference_state = geometry.get("reference_state", "annealed")
    require(reference_state in ("annealed", "austenitised"), "geometry.reference_state", reference_state,
            "must be 'annealed' or 'austenitised'")
    segments = sorted({s.name for s in profile.segments} - {"axis"})

    mesh = _mesh(_table(data, "mesh"), profile)
    p = _table(data, "process")
    process = ProcessSpec(
        austenitising_temperature_C=_number(p, "austenitising_temperature_C", "process.austenitising_temperature_C",
                                            minimum=600.0, maximum=1200.0),
        room_temperature_C=_number(p, "room_temperature_C", "process.room_temperature_C", minimum=-50.0, maximum=100.0))
    _austenitising_in_range(material, process.austenitising_temperature_C)
    t = _table(data, "transfer")
    transfer = TransferStage(time_s=_number(t, "time_s", "transfer.time_s", minimum=0.0),
                             temperature_C=_number(t, "temperature_C", "transfer.temperature_C", minimum=-50.0,
                                                   maximum=200.0),
                             emissivity=_number(t, "emissivity", "transfer.emissivity", positive=True, maximum=1.0))
    quench = _quench(data, segments, process)
    air = _air(data, segments)
    time = _time(data)
    o = _table(data, "output")
    frames: Any = o.get("frames")   # checked by require: an integer
    require(isinstance(frames, int) and not isinstance(frames, bool) and frames >= 2, "output.frames", frames,
            "must be an integer >= 2")
    checkpoint_minutes = _number(o, "checkpoint_minutes", "output.checkpoint_minutes", minimum=0.0, maximum=1440.0)
    mechanics = _mechanics(data, material, process)
    probes = _probes(data, profile)
    temper = _temper(data, segments, process, air, material) if "temper" in data else None
    return Case(name=name, condition=condition, path=path, data=data, material=material, profile=profile,
                reference_state=reference_state, mesh=mesh, process=process, transfer=transfer, quench=quench,
                air=air, time=time,
                output=OutputSpec(frames=frames, checkpoint_minutes=checkpoint_minutes), mechanics=mechanics,
                probes=probes, temper=temper)


def _mesh(m: Mapping[str, Any], profile: Profile) -> MeshSpec:
    """The element sizes: positive and no larger than the section's larger extent (a coarser mesh cannot
    represent the section: `--mesh-size 1000` ran the whole quench, then failed in the traverses)."""
    r0, r1, z0, z1 = profile.bounds()
    largest_mm = max(r1 - r0, z1 - z0) / MM
    sizes = {}
    for key in ("size_mm", "surface_size_mm"):
        value = _number(m, key, f"mesh.{key}", positive=True)
        require(value <= largest_mm, f"mesh.{key}", value, f"must be > 0 and at most {largest_mm:g} mm, the larger "
                f"extent of the section (radial {(r1 - r0) / MM:g} mm, axial {(z1 - z0) / MM:g} mm)")
        sizes[key] = value
    return MeshSpec(**sizes, surface_layer_mm=_number(m, "surface_layer_mm", "mesh.surface_layer_mm", minimum=0.0))


def _material(data: Mapping[str, Any], case_path: Path | None) -> str:
    """The material's name in materials/, or the path of a steel file (``*.toml``); a relative path is taken from
    the case file's folder (from the working directory for a case built from a table), and returned absolute."""
    from quenchsim.materials import load_material, transforms  # data lookup only

    if "material" not in data:
        raise InputError("material", None, "is required (a name in materials/)")
    name = data["material"]
    require(isinstance(name, str) and name != "", "material", name, "must be a material name or a path")
    if name.endswith(".toml"):
        file = Path(name).expanduser()
        if not file.is_absolute():
            file = (case_path.parent if case_path is not None else Path.cwd()) / file
        require(file.is_file(), "material", name, f"no such file ({file})")
        name = str(file.resolve())
    transforms(load_material(name))
    return name


def _austenitising_in_range(material: str, T_aust_C: float) -> None:
    """The austenitising temperature within the steel's tabulated range (a transforming steel's dissolved carbon, Ms
    and kinetics are known there only; outside it a run failed later, after writing its first files)."""
    from quenchsim.materials import load_material, transforms
    from quenchsim.metallurgy.kinetics import check_austenitising_temperature

    steel = load_material(material)
    if transforms(steel):
        check_austenitising_temperature(steel, T_aust_C, "process.austenitising_temperature_C")


def _htc_tables(spec: Any, field: str, segments: list[str]) -> Mapping[str, Any]:
    """Check an HTC table against the section's segment names (the point labels of the run)."""
    from quenchsim.thermal import parse_htc_table

    require(isinstance(spec, Mapping), field, spec, "required (a table) when the htc_model is 'table'")
    parse_htc_table(dict(spec), np.array(segments), field)
    return spec


def _quench(data: Mapping[str, Any], segments: list[str], process: ProcessSpec) -> QuenchStage:
    q = _table(data, "quench")
    time_s = _number(q, "time_s", "quench.time_s", positive=True)
    model = q.get("htc_model", "table")
    require(model in ("bath", "table"), "quench.htc_model", model, "must be 'bath' or 'table'")
    bath = table = None
    if "bath" in q:  # key names checked with either model: a misspelt key must not be ignored
        from quenchsim.bath import check_bath_keys

        check_bath_keys(q["bath"], "quench.bath")
    if model == "bath":
        from quenchsim.bath import parse_bath

        bath = parse_bath(dict(q.get("bath", {})), "quench.bath")
        ambients = [bath.oil_temperature_C]
    else:
        table = _htc_tables(q.get("htc_table"), "quench.htc_table", segments)
        ambients = [table.get("ambient_C")] + [s.get("ambient_C") for s in table.get("segments", {}).values()]
    T_aust = process.austenitising_temperature_C
    for T in ambients:
        if isinstance(T, (int, float)) and T >= T_aust:
            field = "quench.bath.oil_temperature_C" if model == "bath" else "quench.htc_table.ambient_C"
            raise InputError(field, T, f"the quench medium must be colder than the austenitising temperature {T_aust:g} C")
    speed = None
    if "immersion_speed_mm_s" in q:
        speed = _number(q, "immersion_speed_mm_s", "quench.immersion_speed_mm_s")
        require(speed > 0, "quench.immersion_speed_mm_s", speed,
                "must be > 0 mm/s (leave it out for a part immersed all at once)")
    return QuenchStage(time_s=time_s, htc_model=model, bath=bath, htc_table=table, immersion_speed_mm_s=speed)


def _air(data: Mapping[str, Any], segments: list[str]) -> AirStage:
    a = _table(data, "air")
    model: Any = a.get("htc_model")   # checked by require: one of the names
    require(model in ("natural", "table"), "air.htc_model", model, "must be 'natural' or 'table'")
    temperature = _number(a, "temperature_C", "air.temperature_C", minimum=-50.0, maximum=200.0)
    return AirStage(temperature_C=temperature,
                    until_max_C=_number(a, "until_max_C", "air.until_max_C", minimum=temperature),
                    time_s=_number(a, "time_s", "air.time_s", minimum=0.0),
                    htc_model=model,
                    emissivity=_number(a, "emissivity", "air.emissivity", minimum=0.0, maximum=1.0),
                    htc_table=_htc_tables(a.get("htc_table"), "air.htc_table", segments) if model == "table" else None)


def _temper(data: dict[str, Any], segments: list[str], process: ProcessSpec, air: AirStage, material: str
            ) -> TemperStage:
    """The ``[temper]`` stage (its defaults merged into ``data``): below the austenitising temperature and the
    tempering data's range, a positive time, a steel with tempering data."""
    from quenchsim.materials import load_material
    from quenchsim.metallurgy.tempering import has_tempering

    require(isinstance(data["temper"], Mapping), "temper", data["temper"], "must be a table")
    data["temper"] = deep_merge({"cool_until_max_C": air.until_max_C, **TEMPER_DEFAULTS}, data["temper"])
    t = _table(data, "temper")
    T_aust = process.austenitising_temperature_C
    temperature = _number(t, "temperature_C", "temper.temperature_C")
    require(temperature < T_aust, "temper.temperature_C", temperature,
            f"must be below the austenitising temperature {T_aust:g} C (a temper is a reheat of the quenched part)")
    require(process.room_temperature_C < temperature <= TEMPER_MAX_C, "temper.temperature_C", temperature,
            f"must lie above the room temperature {process.room_temperature_C:g} C and at most {TEMPER_MAX_C:g} C "
            "(the range of the tempering data)")
    time_s = _number(t, "time_s", "temper.time_s")
    require(time_s > 0.0, "temper.time_s", time_s, "must be > 0 s (the time in the furnace)")
    model: Any = t.get("htc_model")
    require(model in ("natural", "table"), "temper.htc_model", model, "must be 'natural' or 'table'")
    steel = load_material(material)
    if not has_tempering(steel):
        named = f" (its file names {steel['tempering']!r}, not found)" if isinstance(steel.get("tempering"), str) else ""
        raise InputError("temper", material, f"this steel has no tempering data{named}: a `tempering` file named in "
                         "its material file, as materials/SUJ3.toml names data/tempering_1C_Cr.toml; remove [temper] "
                         "or add the data")
    return TemperStage(temperature_C=temperature, time_s=time_s, htc_model=model,
                       emissivity=_number(t, "emissivity", "temper.emissivity", positive=True, maximum=1.0),
                       htc_table=_htc_tables(t.get("htc_table"), "temper.htc_table", segments)
                       if model == "table" else None,
                       cool_until_max_C=_number(t, "cool_until_max_C", "temper.cool_until_max_C",
                                                minimum=air.temperature_C, maximum=temperature),
                       cool_time_s=_number(t, "cool_time_s", "temper.cool_time_s", minimum=0.0))


def _time(data: Mapping[str, Any]) -> TimeControl:
    t = _table(data, "time")
    values = {key: _number(t, key, f"time.{key}", positive=True)
              for key in ("dt_initial_s", "dt_min_s", "dt_max_s", "max_dT_K", "max_dX")}
    growth = _number(t, "growth", "time.growth")
    require(growth > 1.0, "time.growth", growth, "must be > 1")
    require(values["dt_min_s"] <= values["dt_max_s"], "time.dt_min_s", values["dt_min_s"],
            f"must not exceed time.dt_max_s = {values['dt_max_s']:g}")
    # 0 steps the mechanics with every thermal step
    mechanics_max_dT_K = _number(t, "mechanics_max_dT_K", "time.mechanics_max_dT_K", minimum=0.0, maximum=200.0)
    mechanics_max_dX = _number(t, "mechanics_max_dX", "time.mechanics_max_dX", minimum=0.0, maximum=1.0)
    return TimeControl(growth=growth, mechanics_max_dT_K=mechanics_max_dT_K, mechanics_max_dX=mechanics_max_dX,
                       **values)


def _mechanics(data: Mapping[str, Any], material: str, process: ProcessSpec) -> MechanicsOptions:
    from quenchsim.mechanics import solver_options

    m = data.get("mechanics", {})
    require(isinstance(m, Mapping), "mechanics", m, "must be a table")
    _no_second_austenitising_temperature(m, "mechanics")
    require_known_keys(m, _mechanics_keys(), "mechanics")
    enabled = m.get("enabled", True)
    require(isinstance(enabled, bool), "mechanics.enabled", enabled, "must be true or false")
    fixed = m.get("fixed_point_mm")
    if fixed is not None:
        require(isinstance(fixed, list) and len(fixed) == 2
                and all(isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v) for v in fixed),
                "mechanics.fixed_point_mm", fixed, "must be [r, z] in mm (case geometry)")
        fixed = (float(fixed[0]), float(fixed[1]))
    options = {k: v for k, v in m.items() if k not in ("enabled", "fixed_point_mm")}
    solver_options(options)  # the values too, before anything is written (the model is built with them at run)
    return MechanicsOptions(enabled=enabled, fixed_point_mm=fixed, solver_options=options)


def _probes(data: Mapping[str, Any], profile: Any) -> tuple[Probe, ...]:
    probes = data.get("probes", [])
    require(isinstance(probes, list), "probes", probes, "must be an array of tables [[probes]]")
    out: list[Probe] = []
    for i, probe in enumerate(probes):
        field = f"probes[{i}]"
        require(isinstance(probe, Mapping) and isinstance(probe.get("name"), str), f"{field}.name",
                probe.get("name") if isinstance(probe, Mapping) else probe, "must be a string")
        require(probe["name"] not in {p.name for p in out}, f"{field}.name", probe["name"], "must be unique")
        r = _number(probe, "r_mm", f"{field}.r_mm", minimum=0.0)
        z = _number(probe, "z_mm", f"{field}.z_mm")
        if not profile.contains(r * MM, z * MM) and profile.distance(r * MM, z * MM) > 1e-9:
            raise InputError(field, f"{probe['name']} at ({r:g}, {z:g}) mm", "lies outside the section")
        out.append(Probe(name=probe["name"], r_mm=r, z_mm=z))
    return tuple(out)
