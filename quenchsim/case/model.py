"""The typed case: a case file's tables (declared in :mod:`quenchsim.inputs.case`) with its steel, section and bath
resolved, every value and every rule that ties the tables together checked before any work starts.

Tables of a case file (every key: docs/reference/case_keys.md, generated from the declarations):

``name``, ``description``  the case's name (default: the file name) and a free text
``material``       steel name (materials/NAME.toml) or a path to a steel file -> ``steel`` (loaded)
``[geometry]``     ``type = "rectangular" | "spherical_outer" | "profile"`` and its dimensions -> ``profile``
``[mesh]``, ``[process]``, ``[transfer]``, ``[quench]`` (``[quench.bath]`` -> ``bath``, or ``[quench.htc_table]``),
``[air]``, ``[temper]`` (optional), ``[time]``, ``[output]``, ``[mechanics]``, ``[[probes]]``
``[measured]``, ``[peer]``  measured or published results of the case, for reports; not read by the run

A value is changed by a copy: ``dataclasses.replace(case, quench=replace(case.quench, time_s=600.0))`` checks the
new case like a file's (the tables' limits, the rules between them, the steel and bath resolved again);
:meth:`Case.with_overrides` does the same for dotted keys (``{"quench.time_s": 600}``, the command line's ``--set``).
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.bath import BathConfig
from quenchsim.bath.config import resolve_bath
from quenchsim.errors import InputError, require
from quenchsim.geometry.profile import MM, Profile, profile_from_geometry
from quenchsim.inputs.case import (TEMPER_MAX_C, Air, FreeTable, Geometry, MechanicsOptions, Mesh, Output, Probe,
                                   Process, Quench, Temper, TimeControl, Transfer)
from quenchsim.inputs.declare import REQUIRED, Table, quantity, resolved, to_table
from quenchsim.inputs.htc import HtcTable
from quenchsim.inputs.reader import reading
from quenchsim.inputs.steel import Steel
from quenchsim.materials import load_steel

TransferStage, QuenchStage, AirStage, TemperStage, ProcessSpec, MeshSpec, OutputSpec = (
    Transfer, Quench, Air, Temper, Process, Mesh, Output)
"""The tables under the names they had before the declarations (:mod:`quenchsim.inputs.case`)."""


@dataclass(frozen=True, kw_only=True)
class Case(Table):
    """A fully resolved, checked case: its tables as declared, the steel (``steel``, the material's data), the
    section (``profile``) and the bath (``bath``, with the bath model) resolved. Derive new cases with
    :func:`dataclasses.replace`, :meth:`with_overrides` or :meth:`refined`; :meth:`resolved` is the table they were
    read from (a run's case.toml)."""

    UNKNOWN = "unknown table or key"

    name: str = quantity("", doc="the case's name (default: the file stem); names the default output folder")
    description: str = quantity("", doc="free text")
    material: str = quantity(REQUIRED, doc="a steel's name (found in your data folders, then the shipped "
                             "materials/) or a path to a steel file (*.toml, relative to the case file)",
                             allowed="is required (a name in materials/)")
    geometry: Geometry = quantity(REQUIRED, doc="the section before the quench, dimensions in mm (below)")
    mesh: Mesh = quantity(Mesh(), written=True, doc="element sizes")
    process: Process = quantity(Process(), written=True, doc="austenitising and room temperatures")
    transfer: Transfer = quantity(Transfer(), written=True, doc="from the furnace to the bath")
    quench: Quench = quantity(REQUIRED, doc="the oil stage")
    air: Air = quantity(Air(), written=True, doc="cooling in air")
    temper: Temper | None = quantity(None, doc="optional temper after the air stage")
    time: TimeControl = quantity(TimeControl(), written=True, doc="step control")
    output: Output = quantity(Output(), written=True, doc="VTK frames and checkpoints")
    mechanics: MechanicsOptions = quantity(MechanicsOptions(), written=True, doc="the stress solver")
    probes: tuple[Probe, ...] = quantity((), doc="points whose temperature is recorded")
    measured: FreeTable | None = quantity(None, doc="measured dimensions for the report's comparison: source, "
                                          "before_mm = { id, od, width }, after_mm = { ... } (mm)")
    peer: FreeTable | None = quantity(None, doc="another code's results for the same case (documentation for the "
                                      "validation studies; not read by a run)")

    condition: str | None = resolved()
    """The condition merged over the file's tables (``--condition``), None for a case without conditions."""
    path: Path | None = resolved()
    """The case file (None for a case built from a table)."""
    profile: Profile = resolved(init=False)
    """The section (m), built from ``geometry``."""
    steel: Steel = resolved(init=False)
    """The steel (:func:`quenchsim.materials.load_steel`), its mechanics and tempering data resolved."""
    bath: BathConfig | None = resolved(init=False)
    """The bath the model runs on (``quench.htc_model = "bath"``), else None."""

    @property
    def reference_state(self) -> str:
        """What the geometry's dimensions are: the "annealed" part at room temperature or the "austenitised" one."""
        return self.geometry.reference_state

    def check(self) -> None:
        """Resolve the steel, section and bath and check what ties the tables together (the material and its
        austenitising range, sizes against the section, probes inside it, HTC tables against its surfaces, the
        media colder than the austenitised part, the temper)."""
        set_ = object.__setattr__
        set_(self, "material", _material_name(self.material, self.path))
        set_(self, "steel", load_steel(self.material))
        with reading(self.steel.path):
            self.steel.require_run_data()
        set_(self, "profile", profile_from_geometry(self.geometry))
        self._check_mesh()
        if self.steel.transforms:   # its dissolved carbon, Ms and kinetics are known within its tabulated range
            self.steel.check_austenitising_temperature(self.process.austenitising_temperature_C,
                                                       "process.austenitising_temperature_C")
        segments = sorted({s.name for s in self.profile.segments} - {"axis"})
        set_(self, "bath", resolve_bath(self.quench.bath, "quench.bath")
             if self.quench.htc_model == "bath" and self.quench.bath is not None else None)
        self._check_quench_media(segments)
        if self.air.htc_model == "table":
            _htc_tables(self.air.htc_table, "air.htc_table", segments)
        if self.temper is not None:
            self._check_temper(segments)
        self._check_probes()

    def _check_mesh(self) -> None:
        """The element sizes no larger than the section's larger extent (a coarser mesh cannot represent the
        section: `--mesh-size 1000` ran the whole quench, then failed in the traverses)."""
        r0, r1, z0, z1 = self.profile.bounds()
        largest_mm = max(r1 - r0, z1 - z0) / MM
        for key in ("size_mm", "surface_size_mm"):
            value = getattr(self.mesh, key)
            require(value <= largest_mm, f"mesh.{key}", value, f"must be > 0 and at most {largest_mm:g} mm, the "
                    f"larger extent of the section (radial {(r1 - r0) / MM:g} mm, axial {(z1 - z0) / MM:g} mm)")

    def _check_quench_media(self, segments: list[str]) -> None:
        """The quench's HTC tables against the section's surfaces; the quench medium colder than the austenitised
        part."""
        T_aust = self.process.austenitising_temperature_C
        if self.bath is not None:
            ambients: list[Any] = [self.bath.oil_temperature_C]
            field = "quench.bath.oil_temperature_C"
        else:
            table = self.quench.htc_table
            assert table is not None   # the "table" model requires its tables (Quench.check)
            _htc_tables(table, "quench.htc_table", segments)
            ambients = [table.ambient_C, *(s.ambient_C for s in table.segments.values())]
            field = "quench.htc_table.ambient_C"
        for T in ambients:
            if T is not None and T >= T_aust:
                raise InputError(field, T, f"the quench medium must be colder than the austenitising temperature "
                                           f"{T_aust:g} C")

    def _check_temper(self, segments: list[str]) -> None:
        """The ``[temper]`` stage: below the austenitising temperature and the tempering data's range, cooling to
        between the air's temperature and its own, a steel with tempering data; its cooling limit defaults to the air
        stage's."""
        from dataclasses import replace

        from quenchsim.metallurgy.tempering import has_tempering

        temper = self.temper
        assert temper is not None
        if temper.cool_until_max_C is None:
            temper = replace(temper, cool_until_max_C=self.air.until_max_C,
                             _given={**temper._given, "cool_until_max_C": self.air.until_max_C})
            object.__setattr__(self, "temper", temper)
        T_aust, room = self.process.austenitising_temperature_C, self.process.room_temperature_C
        require(temper.temperature_C < T_aust, "temper.temperature_C", temper.temperature_C,
                f"must be below the austenitising temperature {T_aust:g} C (a temper is a reheat of the quenched part)")
        require(room < temper.temperature_C <= TEMPER_MAX_C, "temper.temperature_C", temper.temperature_C,
                f"must lie above the room temperature {room:g} C and at most {TEMPER_MAX_C:g} C (the range of the "
                "tempering data)")
        cool = temper.cool_until_max_C
        require(cool is not None and self.air.temperature_C <= cool <= temper.temperature_C,
                "temper.cool_until_max_C", cool,
                f"must be >= {self.air.temperature_C:g} and <= {temper.temperature_C:g}")
        if temper.htc_model == "table":
            _htc_tables(temper.htc_table, "temper.htc_table", segments)
        if not has_tempering(self.steel):
            tempering = self.steel.tempering
            named = f" (its file names {tempering!r}, not found)" if isinstance(tempering, str) else ""
            raise InputError("temper", self.material, f"this steel has no tempering data{named}: a `tempering` file "
                             "named in its material file, as materials/SUJ3.toml names data/tempering_1C_Cr.toml; "
                             "remove [temper] or add the data")

    def _check_probes(self) -> None:
        names: set[str] = set()
        for i, probe in enumerate(self.probes):
            field = f"probes[{i}]"
            require(probe.name not in names, f"{field}.name", probe.name, "must be unique")
            names.add(probe.name)
            r, z = probe.r_mm, probe.z_mm
            if not self.profile.contains(r * MM, z * MM) and self.profile.distance(r * MM, z * MM) > 1e-9:
                raise InputError(field, f"{probe.name} at ({r:g}, {z:g}) mm", "lies outside the section")

    # -- the inputs as a table ---------------------------------------------------------------------------------
    @property
    def data(self) -> dict[str, Any]:
        """The case's tables as read (the file's, its condition merged, defaults the declarations write): what
        :meth:`resolved` holds besides the name and condition."""
        return to_table(self)

    def get(self, dotted: str, default: Any = None) -> Any:
        """The value at a dotted path of the case's tables as read (for reports; the run reads the typed fields)."""
        node: Any = self.data
        for key in dotted.split("."):
            if not isinstance(node, Mapping) or key not in node:
                return default
            node = node[key]
        return node

    def resolved(self) -> dict[str, Any]:
        """The fully resolved inputs as written to a run's case.toml."""
        return {**self.data, "name": self.name, "condition": self.condition or ""}

    def digest(self) -> str:
        """SHA-256 (first 16 hex digits) of :meth:`resolved`: the same inputs give the same value wherever the case
        file lies, so a summary.json names exactly what ran (the code's version is beside it)."""
        text = json.dumps(self.resolved(), sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    def with_overrides(self, overrides: Mapping[str, Any]) -> "Case":
        """A new case with dotted-path ``overrides`` applied to this one's tables (a value None removes the key, so
        its default applies), checked again."""
        from quenchsim.case.parse import build_case

        return build_case(self.data, self.name, self.condition, self.path, overrides)

    def refined(self, mesh: float = 1.0, step: float = 1.0) -> "Case":
        """The same case with element sizes times ``mesh`` and the step control (initial step, limits on the
        temperature and phase change per step) times ``step`` (e.g. ``mesh=0.5`` halves the element size)."""
        overrides: dict[str, Any] = {}
        if mesh != 1.0:
            overrides["mesh.size_mm"] = self.mesh.size_mm * mesh
            overrides["mesh.surface_size_mm"] = self.mesh.surface_size_mm * mesh
        if step != 1.0:
            for key in ("max_dT_K", "max_dX", "dt_initial_s", "mechanics_max_dT_K", "mechanics_max_dX"):
                overrides[f"time.{key}"] = getattr(self.time, key) * step
        return self.with_overrides(overrides)

    def with_mesh_size(self, size_mm: float) -> "Case":
        """The case with core element size ``size_mm`` and the surface size scaled in proportion, to 12 significant
        digits: ``--mesh-size 15`` on 5 / 1.2 mm is 3.6 mm at the surface, in the case and its case.toml, not the
        binary product 3.5999999999999996. (:meth:`refined` keeps the exact product: gmsh meshes differ at 1e-16, and
        the studies that refine their cases are not to move.)"""
        surface = float(f"{self.mesh.surface_size_mm * size_mm / self.mesh.size_mm:.12g}")
        return self.with_overrides({"mesh.size_mm": size_mm, "mesh.surface_size_mm": surface})


def _material_name(name: str, case_path: Path | None) -> str:
    """The material's name in the data folders, or the path of a steel file (``*.toml``); a relative path is taken
    from the case file's folder (from the working directory for a case built from a table), and returned absolute."""
    require(name != "", "material", name, "must be a material name or a path")
    if not name.endswith(".toml"):
        return name
    file = Path(name).expanduser()
    if not file.is_absolute():
        file = (case_path.parent if case_path is not None else Path.cwd()) / file
    require(file.is_file(), "material", name, f"no such file ({file})")
    return str(file.resolve())


def _htc_tables(table: HtcTable | None, field: str, segments: list[str]) -> None:
    """An HTC table checked against the section's segment names (the point labels of the run)."""
    from quenchsim.thermal import parse_htc_table

    require(table is not None, field, None, "required (a table) when the htc_model is 'table'")
    assert table is not None
    parse_htc_table(table, np.array(segments), field)
