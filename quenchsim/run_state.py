"""The state of a quench run as the modules around the time loop see it: the step counters, the position in the
stages, and the protocol through which closing (:mod:`quenchsim.closing`), checkpoints (:mod:`quenchsim.io.checkpoint`),
results (:mod:`quenchsim.results.assemble`) and progress (:mod:`quenchsim.progress.observer`) read a run
(:class:`quenchsim.pipeline.QuenchRun` is one). They read it; only the run changes it."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

if TYPE_CHECKING:   # the types the protocol names; the modules that use it import the run's pieces themselves
    import skfem

    from quenchsim.case import Case
    from quenchsim.geometry import SectionMesh
    from quenchsim.geometry.profile import Profile
    from quenchsim.mechanics import MechanicsModel, MechanicsSolver
    from quenchsim.mechanics.coupling import StressCoupling
    from quenchsim.metallurgy import Kinetics, Tempering
    from quenchsim.results import RunWriter
    from quenchsim.results.final_part import FinalPart
    from quenchsim.results.postprocess import NodalProjection
    from quenchsim.results.stream import RunRecord
    from quenchsim.results.timings import StageTimings
    from quenchsim.thermal import AxisymmetricP2, ThermalSolver


@dataclass
class StepCounts:
    """What the run has done so far: committed thermal steps, rejected (halved) steps, stress steps, and the heat
    taken out of the part and the latent heat released (J, over the whole section)."""

    steps: int = 0
    rejected: int = 0
    stress_steps: int = 0
    heat_out_J: float = 0.0
    latent_J: float = 0.0

    def as_dict(self) -> dict[str, Any]:
        """For a checkpoint's header (JSON)."""
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> StepCounts:
        """From a checkpoint's header."""
        return cls(**{k: data.get(k, 0) for k in ("steps", "rejected", "stress_steps", "heat_out_J", "latent_J")})


@dataclass
class Position:
    """Where the run is: the index of the stage it is in, the time that stage ends (s; None before it starts) and the
    next step's length (s)."""

    stage: int = 0
    stage_end_s: float | None = None
    dt_s: float = 0.0

    def as_dict(self) -> dict[str, Any]:
        """For a checkpoint's header (JSON)."""
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Position:
        """From a checkpoint's header."""
        return cls(stage=int(data["stage"]), stage_end_s=data["stage_end_s"], dt_s=float(data["dt_s"]))


class RunState(Protocol):
    """A quench run as closing, checkpoints, results and progress read it: its case, solvers and their state, its
    outputs, counters and position (read-only here), and the one thing they may ask of it: to bring the stresses up
    to the committed thermal state."""

    @property
    def case(self) -> Case: ...
    @property
    def thermal(self) -> ThermalSolver: ...
    @property
    def fe(self) -> AxisymmetricP2: ...
    @property
    def section(self) -> SectionMesh: ...
    @property
    def profile(self) -> Profile: ...
    @property
    def before_mesh(self) -> skfem.MeshTri: ...
    @property
    def case_to_hot(self) -> float: ...
    @property
    def T_aust(self) -> float: ...
    @property
    def T_room(self) -> float: ...
    @property
    def kin(self) -> Kinetics | None: ...
    @property
    def tempering(self) -> Tempering | None: ...
    @property
    def phase_model(self) -> Any: ...
    @property
    def mech(self) -> MechanicsSolver | None: ...
    @property
    def mech_model(self) -> MechanicsModel | None: ...
    @property
    def stress(self) -> StressCoupling | None: ...
    @property
    def projection(self) -> NodalProjection: ...
    @property
    def final_part(self) -> FinalPart: ...
    @property
    def record(self) -> RunRecord: ...
    @property
    def writer(self) -> RunWriter: ...
    @property
    def out(self) -> Path: ...
    @property
    def checkpoint_path(self) -> Path: ...
    @property
    def timings(self) -> StageTimings: ...
    @property
    def counts(self) -> StepCounts: ...
    @property
    def position(self) -> Position: ...
    @property
    def wall0(self) -> float: ...
    @property
    def as_quenched(self) -> dict[str, Any] | None: ...

    def catch_up_stresses(self) -> None:
        """Bring the stresses to the committed thermal state (nothing when the stress is not solved)."""

    def summary(self, time_s: np.ndarray, probe_T: dict[str, np.ndarray], wall0: float) -> dict[str, Any]:
        """summary.json of the finished run."""
