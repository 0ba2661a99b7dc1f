"""Frozen dataclasses of a parsed case (built by :mod:`quenchsim.case.parse`; every value already checked).

Tables of a case file and the dataclass each becomes:

``name``, ``description``  the case's name (default: the file name) and a free text
``material``       steel name (materials/NAME.toml)
``[geometry]``     ``type = "rectangular" | "spherical_outer" | "profile"`` and its dimensions -> ``profile``
``[mesh]``         ``size_mm`` (core), ``surface_size_mm``, ``surface_layer_mm``      -> :class:`MeshSpec`
``[process]``      ``austenitising_temperature_C``, ``room_temperature_C``            -> :class:`ProcessSpec`
``[transfer]``     the move from the furnace to the bath in still air: ``time_s`` (0 = none), ``temperature_C``,
                   ``emissivity`` (natural convection + radiation, quenchsim.bath.air_htc)  -> :class:`TransferStage`
``[quench]``       ``time_s``, ``htc_model = "bath" | "table"``, ``[quench.bath]`` (bath model) or
                   ``[quench.htc_table]`` (``T_C``, ``h_W_m2K``, ``ambient_C``; optional per-segment
                   ``[quench.htc_table.segments.NAME]``; ``time_s`` + ``h_W_m2K`` for HTC vs time); optional
                   ``immersion_speed_mm_s`` (the part enters bottom face first at this speed: below the oil
                   level the quench HTC, above it the transfer air's)                  -> :class:`QuenchStage`
``[air]``          ``temperature_C``, ``until_max_C`` (stop when the hottest point is below) or ``time_s``,
                   ``htc_model = "natural" | "table"`` with ``emissivity`` or ``[air.htc_table]`` -> :class:`AirStage`
``[temper]``       optional, after the air stage: ``temperature_C``, ``time_s`` (in the furnace, from the part's
                   entry), ``htc_model = "natural" | "table"`` with ``emissivity`` or ``[temper.htc_table]``, then
                   cooling in air (the ``[air]`` stage's medium) until ``cool_until_max_C``    -> :class:`TemperStage`
``[[probes]]``     ``name``, ``r_mm``, ``z_mm``                                       -> :class:`Probe`
``[time]``         step control: ``dt_initial_s``, ``dt_min_s``, ``dt_max_s``, ``max_dT_K``, ``max_dX``,
                   ``growth``                                                        -> :class:`TimeControl`
``[output]``       ``frames`` (number of VTK frames), ``checkpoint_minutes`` (wall time between
                   checkpoints; 0: after every step)                                 -> :class:`OutputSpec`
``[mechanics]``    ``enabled``, ``fixed_point_mm`` and the stress solver's options (``plasticity``, ``trip``,
                   ``newton_rtol``, ...)                                            -> :class:`MechanicsOptions`
``[measured]``, ``[peer]``  measured or published results of the case, for reports; not read by the run
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from quenchsim.bath import BathConfig
from quenchsim.geometry.profile import Profile


@dataclass(frozen=True)
class MeshSpec:
    size_mm: float
    surface_size_mm: float
    surface_layer_mm: float


@dataclass(frozen=True)
class ProcessSpec:
    austenitising_temperature_C: float
    room_temperature_C: float


@dataclass(frozen=True)
class QuenchStage:
    """The oil stage: its length and either the bath model (``bath``) or HTC tables (``htc_table``)."""

    time_s: float
    htc_model: str
    bath: BathConfig | None
    htc_table: Mapping[str, Any] | None
    immersion_speed_mm_s: float | None = None


@dataclass(frozen=True)
class TransferStage:
    """The part's move from the furnace into the bath: ``time_s`` in still air at ``temperature_C`` (0 s: none),
    natural convection plus radiation with ``emissivity``."""

    time_s: float
    temperature_C: float
    emissivity: float


@dataclass(frozen=True)
class AirStage:
    """Cooling in air after the quench, until the hottest point is below ``until_max_C`` or ``time_s`` ends."""

    temperature_C: float
    until_max_C: float
    time_s: float
    htc_model: str
    emissivity: float
    htc_table: Mapping[str, Any] | None


@dataclass(frozen=True)
class TemperStage:
    """The temper after the quench: ``time_s`` in a furnace at ``temperature_C`` (still furnace air, natural
    convection plus radiation with ``emissivity``, or an HTC table), then air cooling until the hottest point is
    below ``cool_until_max_C`` or ``cool_time_s`` ends."""

    temperature_C: float
    time_s: float
    htc_model: str
    emissivity: float
    htc_table: Mapping[str, Any] | None
    cool_until_max_C: float
    cool_time_s: float


@dataclass(frozen=True)
class TimeControl:
    """Adaptive step control.

    A thermal step is limited by the largest nodal temperature change (``max_dT_K``, K) and the largest change
    of a diffusional product's fraction (``max_dX``: pearlite, bainite; martensite follows the temperature and
    is limited through ``max_dT_K``); it grows by at most ``growth`` per step between ``dt_min_s`` and
    ``dt_max_s``. The stress solver (rate-independent: its increments depend on the changes of temperature and
    phases, not on time) takes one step over as many thermal steps as keep the change since its last step
    within ``mechanics_max_dT_K`` (K, at any quadrature point) and ``mechanics_max_dX`` (any phase fraction,
    martensite included); 0 steps it with every thermal step. A thermal step beyond them is split into as many stress
    steps as keep each within them, along the step's own path (temperatures linear in time, phases as the kinetics
    form them on it). The thermal march is second order (BDF2); the stress update is first order in the temperature
    step (ring A condition 1's ID change moves by ~3e-5 mm per kelvin of ``mechanics_max_dT_K``, its stresses not
    measurably). The defaults (30 K and 0.02 for both) keep the time-discretisation error of ring A condition 1 within
    the project's tolerances (validation/quench/convergence)."""

    dt_initial_s: float
    dt_min_s: float
    dt_max_s: float
    max_dT_K: float
    max_dX: float
    growth: float
    mechanics_max_dT_K: float
    mechanics_max_dX: float


@dataclass(frozen=True)
class OutputSpec:
    frames: int
    checkpoint_minutes: float


@dataclass(frozen=True)
class MechanicsOptions:
    """Whether the stress is solved, the optional fixed point (case geometry, mm) and the solver options
    passed on to :func:`quenchsim.mechanics.load_mechanics` (names and values checked when the case loads, by
    :func:`quenchsim.mechanics.solver_options`)."""

    enabled: bool
    fixed_point_mm: tuple[float, float] | None
    solver_options: Mapping[str, Any]


@dataclass(frozen=True)
class Probe:
    name: str
    r_mm: float
    z_mm: float


@dataclass(frozen=True)
class Case:
    """A fully resolved, checked case. ``data`` is the merged table it was parsed from (written to a run's
    case.toml); derive new cases with :meth:`with_overrides` or :meth:`refined`, never by editing it."""

    name: str
    condition: str | None
    path: Path | None
    data: Mapping[str, Any]
    material: str
    profile: Profile
    reference_state: str
    mesh: MeshSpec
    process: ProcessSpec
    transfer: TransferStage
    quench: QuenchStage
    air: AirStage
    time: TimeControl
    output: OutputSpec
    mechanics: MechanicsOptions
    probes: tuple[Probe, ...]
    temper: TemperStage | None = None

    def get(self, dotted: str, default: Any = None) -> Any:
        """The raw value at a dotted path of the merged table (for reports; the run reads the typed fields)."""
        node: Any = self.data
        for key in dotted.split("."):
            if not isinstance(node, Mapping) or key not in node:
                return default
            node = node[key]
        return node

    def resolved(self) -> dict[str, Any]:
        """The fully resolved inputs as written to a run's case.toml."""
        return {"name": self.name, "condition": self.condition or "", **self.data}

    def digest(self) -> str:
        """SHA-256 (first 16 hex digits) of :meth:`resolved`: the same inputs give the same value wherever the case
        file lies, so a summary.json names exactly what ran (the code's version is beside it)."""
        text = json.dumps(self.resolved(), sort_keys=True, default=str)
        return hashlib.sha256(text.encode()).hexdigest()[:16]

    def with_overrides(self, overrides: Mapping[str, Any]) -> "Case":
        """A new case with dotted-path ``overrides`` applied to this one's table (a value None removes the
        key, so its default applies), checked again."""
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
