"""The staged quench, top to bottom: section -> boundary -> HTC -> stages -> results.

The ring is austenitised (uniform T, stress free), quenched, then cooled in air to room temperature.
Each time step solves the thermal problem with the phase kinetics inside its fixed-point iteration. The step
starts small, grows under limits on the temperature change and the diffusional (pearlite, bainite) phase change per
step, and is cut back and retried when an iteration does not converge (logged). The stress problem (when enabled;
rate-independent) takes one step over as many thermal steps as keep its change within ``time.mechanics_max_dT_K``
and ``time.mechanics_max_dX`` (multirate), and catches up at every VTK frame, stage end and the end of the run.
Probes and VTK frames are written as they are produced; a run that fails keeps them and records where it stopped
in ``summary.json``.
"""

from __future__ import annotations

import contextlib
import json
import logging
import math
import signal
import threading
import time
import zipfile
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import skfem
from quenchsim import __version__, mechanics, metallurgy
from quenchsim.case import Case
from quenchsim.errors import InputError, QuenchsimError, RunInterrupted, SolverError
from quenchsim.fem import INTORDER
from quenchsim.geometry import BoundaryPoints, SectionMesh, boundary_points, mesh_profile
from quenchsim.geometry.profile import MM, Profile
from quenchsim.io.checkpoint import FORMAT_VERSION as CHECKPOINT_FORMAT
from quenchsim.io.checkpoint import read_checkpoint, write_checkpoint
from quenchsim.materials import load_material, thermal_properties, transforms
from quenchsim.progress import CoolingProgress, RunProgress, StepState, film_collapse_temperatures
from quenchsim.results import RunWriter, files
from quenchsim.results.measured import compare_with_measured
from quenchsim.results.writer import claim_run_folder
from quenchsim.results.postprocess import NodalProjection, phase_statistics
from quenchsim.results.shape import shape_change
from quenchsim.results.summary import (FinalSection, hardness_summary, probe_times, residual_stress_summary,
                                       residual_traverse)
from quenchsim.thermal import AxisymmetricP2, ImmersionHTC, SurfaceTemperatureHTC, ThermalSolver, parse_htc_table

log = logging.getLogger("quenchsim")
MAX_STRESS_STEPS_PER_THERMAL_STEP = 64
"""Bound on the stress steps that one thermal step beyond the ``time.mechanics_*`` limits is split into."""


@dataclass
class RunResult:
    out_dir: Path
    summary: dict[str, Any]
    time_s: np.ndarray = field(repr=False, default_factory=lambda: np.zeros(0))
    probe_T_C: dict[str, np.ndarray] = field(repr=False, default_factory=dict)


def run(case: Case, out_dir: str | Path, progress: bool = True, resume: bool = False, force: bool = False
        ) -> RunResult:
    """Run ``case`` and write everything into ``out_dir`` (the output contract: :mod:`quenchsim.results`);
    ``resume`` continues the run of the same case in ``out_dir`` from its checkpoint. A new run clears the
    outputs of an earlier run in ``out_dir`` and refuses a non-empty folder that is not a run folder unless
    ``force`` (:func:`quenchsim.results.writer.claim_run_folder`)."""
    try:
        quench_run = QuenchRun(case, Path(out_dir), progress=progress, resume=resume, force=force)
    except KeyboardInterrupt:
        # Ctrl-C while meshing or building the solvers: nothing was computed; a fresh run's folder says so (a
        # resumed run keeps its earlier summary and checkpoint, both still valid)
        if not resume and Path(out_dir).is_dir():
            RunWriter(out_dir).summary({"case": case.name, "condition": case.condition, "status": "interrupted",
                                        "error": "interrupted during setup (meshing, boundary, solvers)",
                                        "stopped_at_s": 0.0})
        raise RunInterrupted(f"run interrupted during setup, before the first step ({out_dir})") from None
    return quench_run.run()


# -- section ------------------------------------------------------------------------------------
@dataclass
class Section:
    """The meshed section in the quench's (austenitised) geometry and in the "before" (case-file
    reference) geometry, the stress model when the stress is solved, and the scale between them."""

    hot: SectionMesh
    before_mesh: skfem.MeshTri
    profile_before: Profile
    case_to_hot: float
    mech_model: Any


def build_section(case: Case, material: dict[str, Any], msh_path: Path) -> Section:
    """Mesh the case's profile and move it to the austenitised geometry.

    The quench starts from the austenitised section whether or not the stress is solved; the "before"
    section is the room-temperature annealed one, smaller by the free strain between the two states.
    The case file gives one of them (``geometry.reference_state``)."""
    T_aust = case.process.austenitising_temperature_C
    section = mesh_profile(case.profile, case.mesh.size_mm * MM, case.mesh.surface_size_mm * MM,
                           case.mesh.surface_layer_mm * MM, msh_path=msh_path)
    if "mechanics" not in material:
        return Section(section, section.mesh, case.profile, 1.0, None)
    solve_stress = case.mechanics.enabled
    # a thermal-only run needs the free strains (for the hot section) but no flow or TRIP data
    options = dict(case.mechanics.solver_options) if solve_stress else {"plasticity": False, "trip": False}
    mech_model = mechanics.load_mechanics(material, {**options, "austenitizing_T_C": T_aust})
    scale = mechanics.austenitized_scale(mech_model)
    mesh = section.mesh
    if case.reference_state == "annealed":
        profile_before, profile, case_to_hot = case.profile, case.profile.scaled(scale), scale
        hot, before_mesh = skfem.MeshTri(mesh.p * scale, mesh.t), mesh
    else:
        profile_before, profile, case_to_hot = case.profile.scaled(1.0 / scale), case.profile, 1.0
        hot, before_mesh = mesh, skfem.MeshTri(mesh.p / scale, mesh.t)
    return Section(SectionMesh(mesh=hot, boundaries=section.boundaries, profile=profile), before_mesh, profile_before,
                   case_to_hot, mech_model if solve_stress else None)


# -- boundary and HTC ---------------------------------------------------------------------------
def cooled_surface_points(fe: AxisymmetricP2, section: SectionMesh) -> BoundaryPoints:
    """The facet quadrature points of the cooled surface (everything but the axis), labelled by segment."""
    return boundary_points(section, fe.facets, fe.facet_r, fe.facet_z, fe.facet_normals)


@dataclass(frozen=True)
class Stage:
    """One stage of the run: it lasts ``duration_s`` or ends once the hottest point is at or below
    ``until_max_C``; its boundary is :func:`stage_htc` of its ``name``."""

    name: str
    duration_s: float
    until_max_C: float = -math.inf


def stages(case: Case) -> list[Stage]:
    """The stages of a run in order (the progress bar and the checkpoints count them)."""
    return [Stage("transfer", case.transfer.time_s), Stage("quench", case.quench.time_s),
            Stage("air", case.air.time_s, case.air.until_max_C)]


def stage_htc(case: Case, stage: str, points: BoundaryPoints) -> Any:
    """The HTC of the transfer, quench or air stage as ``htc(T_surface, t)`` with ``ambient_C`` per point.

    The quench stage starts when the transfer ends (``transfer.time_s``); with ``quench.immersion_speed_mm_s`` the
    part enters the oil bottom face first and the points above the oil level keep the transfer air's HTC."""
    from quenchsim import bath

    if stage == "transfer":
        return SurfaceTemperatureHTC(bath.air_htc(points, case.transfer.temperature_C, case.transfer.emissivity))
    if stage == "quench":
        if case.quench.htc_model == "table":
            oil = parse_htc_table(dict(case.quench.htc_table), points.segment, "quench.htc_table")
        else:
            oil = SurfaceTemperatureHTC(bath.boundary_htc(case.quench.bath, points))
        if case.quench.immersion_speed_mm_s is None:
            return oil
        return ImmersionHTC(oil, stage_htc(case, "transfer", points), points.z_m, points.extent.z_min_m,
                            case.quench.immersion_speed_mm_s * MM, case.transfer.time_s)
    if case.air.htc_model == "table":
        return parse_htc_table(dict(case.air.htc_table), points.segment, "air.htc_table")
    return SurfaceTemperatureHTC(bath.air_htc(points, case.air.temperature_C, case.air.emissivity))


@dataclass
class _UntransformedState:
    fractions: dict[str, np.ndarray]


class _Untransformed:
    """Phase model of a material that does not transform (``transformations = "none"``): the phase it was heated to
    stays, no latent heat."""

    time_dependent_phases: tuple[str, ...] = ()

    @staticmethod
    def initial_state(shape: tuple[int, ...]) -> _UntransformedState:
        return _UntransformedState({"austenite": np.ones(shape)})

    def advance(self, state: Any, T_old_C: np.ndarray, T_new_C: np.ndarray, dt_s: float) -> Any:
        return state

    def fractions(self, state: Any) -> dict[str, np.ndarray]:
        return state.fractions

    def checkpoint_state(self, state: Any) -> dict[str, Any]:
        return {"fractions": state.fractions}

    def restore_state(self, arrays: dict[str, Any]) -> Any:
        return _UntransformedState({p: np.array(v) for p, v in arrays["fractions"].items()})


class _Kinetics:
    """Adapter: the metallurgy package as the thermal solver's phase model.

    ``time_dependent_phases``: the products of the diffusional reactions, whose fraction change per step
    ``time.max_dX`` limits; martensite is a function of the temperature alone (Koistinen-Marburger), so
    ``time.max_dT_K`` limits its steps."""

    def __init__(self, kin: Any) -> None:
        self.kin = kin
        self.time_dependent_phases = tuple(kin.reactions)

    def advance(self, state: Any, T_old_C: np.ndarray, T_new_C: np.ndarray, dt_s: float) -> Any:
        return metallurgy.advance(state, self.kin, T_old_C, T_new_C, dt_s)

    def fractions(self, state: Any) -> dict[str, np.ndarray]:
        return state.fractions

    def checkpoint_state(self, state: Any) -> dict[str, Any]:
        return {"fractions": state.fractions, "additivity": state.additivity, "T_min_C": state.T_min_C,
                "cooling_rate_700_C_s": state.cooling_rate_700_C_s}

    def restore_state(self, arrays: dict[str, Any]) -> Any:
        return metallurgy.PhaseState(fractions={p: np.array(v) for p, v in arrays["fractions"].items()},
                                     additivity={r: np.array(v) for r, v in arrays.get("additivity", {}).items()},
                                     T_min_C=np.array(arrays["T_min_C"]),
                                     cooling_rate_700_C_s=np.array(arrays["cooling_rate_700_C_s"]))


# -- the run ------------------------------------------------------------------------------------
class QuenchRun:
    """Everything of one run: section, solvers, output writer. Use :func:`run`."""

    def __init__(self, case: Case, out_dir: Path, progress: bool = True, resume: bool = False,
                 force: bool = False) -> None:
        self.case = case
        # a resumed run checks its case against the folder's before anything is written or meshed; a new one
        # checks the folder and clears an earlier run's outputs (stale frames, an earlier summary's status)
        self.checkpoint_path = Path(out_dir) / files.CHECKPOINT_NPZ
        checkpoint = read_resumable(case, Path(out_dir)) if resume else None
        if not resume:
            claim_run_folder(out_dir, force)
        self.writer = RunWriter(out_dir)
        self.out = self.writer.out
        self.writer.case(case.resolved())
        if not resume:
            self.checkpoint_path.unlink(missing_ok=True)   # another run's state: never to be resumed into this one
        self.bar = RunProgress(f"{case.name}[{case.condition}]" if case.condition else case.name,
                               sum(st.duration_s for st in stages(case)), enabled=progress)
        self.bar.phase("meshing")
        self.material = load_material(case.material)
        self.T_aust = case.process.austenitising_temperature_C
        self.T_room = case.process.room_temperature_C
        built = build_section(case, self.material, self.writer.mesh_path)
        self.section, self.before_mesh, self.profile_before = built.hot, built.before_mesh, built.profile_before
        self.profile, self.case_to_hot, self.mech_model = built.hot.profile, built.case_to_hot, built.mech_model
        cooled = np.concatenate([f for n, f in self.section.boundaries.items() if n != "axis"])
        self.fe = AxisymmetricP2(self.section.mesh, cooled, intorder=INTORDER)
        self.points = cooled_surface_points(self.fe, self.section)
        if transforms(self.material):
            self.kin = metallurgy.load_kinetics(self.material, self.T_aust)
            self.phase_model, start_state = _Kinetics(self.kin), metallurgy.initial_state(self.fe.r_qp.shape, self.kin)
        else:
            self.kin, self.phase_model = None, _Untransformed()
            start_state = _Untransformed.initial_state(self.fe.r_qp.shape)
        self.thermal = ThermalSolver(self.fe, thermal_properties(self.material), self.T_aust, self.phase_model,
                                     start_state)
        self.projection = NodalProjection(self.section.mesh, INTORDER)
        fixed = case.mechanics.fixed_point_mm
        fixed_m = None if fixed is None else (fixed[0] * MM * self.case_to_hot, fixed[1] * MM * self.case_to_hot)
        self.mech = mechanics.MechanicsSolver(self.section.mesh, self.mech_model, fixed_m) if self.mech_model else None
        self.mech_ref = (self.thermal.T_qp, self.thermal.fractions())  # the state of the last stress step
        # probe positions are given on the case's section; they move with it to the austenitised geometry
        self.probe_names = [p.name for p in case.probes]
        pts = np.array([[p.r_mm * MM, p.z_mm * MM] for p in case.probes]).reshape(-1, 2)
        self.probe_matrix = self.fe.basis.probes(pts.T * self.case_to_hot) if len(pts) else None
        self.timings: dict[str, float] = {}
        self.stop = _StopRequest()
        self.restored = None if checkpoint is None else self._restore(*checkpoint)

    def probe_temperatures(self) -> np.ndarray:
        return self.probe_matrix @ self.thermal.T if self.probe_matrix is not None else np.zeros(0)

    def _record_probes(self, probes: Any) -> None:
        """A row of probes.csv (and of the run's probe arrays) at the current time and temperatures. The closing
        step to room temperature (:meth:`_equilibrate_at_room_temperature`) takes no time: its row repeats the last
        step's time_s with the room-temperature state the last VTK frame shows."""
        self.times.append(self.thermal.time_s)
        self.probe_rows.append(self.probe_temperatures())
        probes.write(self.thermal.time_s, self.probe_rows[-1])

    def nodal_fields(self) -> dict[str, np.ndarray]:
        nv = self.section.mesh.p.shape[1]
        state = self.thermal.phase_state
        data = {"temperature_C": self.thermal.T[:nv].copy()}
        if self.kin is not None:  # a non-transforming material has no phases or hardness to show
            for phase, X in state.fractions.items():
                data[phase] = self.projection(X)
            hv = metallurgy.hardness_HV(state, self.kin)
            data["hardness_HV"] = self.projection(hv)
            data["hardness_HRC"] = metallurgy.hv_to_hrc(data["hardness_HV"])
        if self.mech is not None:
            data.update(self.mech.nodal_fields())
        return data

    def run(self) -> RunResult:
        case = self.case
        wall0 = time.perf_counter()
        vtk = self.writer.series(self.section.mesh.p, self.section.mesh.t)
        probes = self.writer.probes(self.probe_names)
        if self.restored is None:
            self.times, self.probe_rows = [0.0], [self.probe_temperatures()]
            probes.write(0.0, self.probe_rows[0])
            vtk.write(0.0, self.nodal_fields())
            self._last_frame_T = self.thermal.T.copy()
            self.counts = {"steps": 0, "rejected": 0, "heat_out_J": 0.0, "latent_J": 0.0}
            self.position = {"stage": 0, "stage_end_s": None, "dt_s": case.time.dt_initial_s}
        else:  # the probe rows and frames up to the checkpoint, as the interrupted run wrote them
            for t, row in zip(self.times, self.probe_rows):
                probes.write(t, row)
            vtk.resume(self.restored["frames"])
            wall0 -= self.restored["wall_time_s"]
        self.wall0 = wall0
        status, error = "ok", None
        try:
            with _signals_as_stop_request(self.stop):
                self._stages(vtk, probes)
                self.stop.check()
                end_state = self._end_state()
                if end_state["at_room_temperature"]:   # probes.csv ends, like the last frame, on the closing step
                    self._record_probes(probes)
        except (KeyboardInterrupt, RunInterrupted) as exc:
            status, error = "interrupted", str(exc) or "interrupted (Ctrl-C)"
            try:
                end_state = self._end_state(closing_step=False)
            except KeyboardInterrupt:   # Ctrl-C again while the stresses catch up: keep the last stress step's
                end_state = {"at_room_temperature": False, "time_s": float(self.thermal.time_s),
                             "note": "interrupted again while the stresses caught up with the last thermal step: "
                                     "stresses and dimensions are those of the last stress step"}
            log.error("run interrupted at t = %.4g s", self.thermal.time_s)
        except QuenchsimError as exc:
            status, error = "failed", str(exc)
            end_state = self._end_state(closing_step=False)
            log.error("run stopped at t = %.4g s: %s", self.thermal.time_s, exc)
        finally:
            probes.close()
        self.bar.phase("output")
        self.writer.final_3d(self._final_frame(vtk))
        time_arr = np.asarray(self.times)
        probe_T = {n: np.array([row[i] for row in self.probe_rows]) for i, n in enumerate(self.probe_names)}
        try:
            summary = self.summary(time_arr, probe_T, wall0)
        except KeyboardInterrupt:  # the stages are done and checkpointed: say so, and how to finish
            self.writer.summary({"case": case.name, "condition": case.condition, "status": "interrupted",
                                 "error": "interrupted during post-processing (finish it with --resume)",
                                 "stopped_at_s": self.thermal.time_s})
            raise RunInterrupted(f"run interrupted during post-processing; finish it with --resume ({self.out})") \
                from None
        except Exception as exc:  # keep what was computed: record the failure, then re-raise
            self.writer.summary({"case": case.name, "condition": case.condition, "status": "failed",
                                 "error": f"post-processing: {exc!r}"})
            raise
        summary["end_state"] = end_state
        if status == "ok" and not end_state["at_room_temperature"]:
            status = "hot"      # the stages ended before the part cooled: its results are not the finished part's
        summary["status"] = status
        if error:
            summary["error"] = error
            summary["stopped_at_s"] = self.thermal.time_s
        self.writer.summary(summary)
        self.bar.close()
        if status in files.FINISHED_STATUSES:
            self.checkpoint_path.unlink(missing_ok=True)   # the run is complete: nothing to resume
        if status == "interrupted":
            raise RunInterrupted(f"run interrupted at t = {self.thermal.time_s:.4g} s; results up to there are in "
                                 f"{self.out} (summary.json status 'interrupted'; continue it with --resume)")
        if error:
            raise SolverError(f"{error} (results up to t = {self.thermal.time_s:.4g} s are in {self.out})")
        return RunResult(self.out, summary, time_arr, probe_T)

    def _stages(self, vtk: Any, probes: Any) -> None:
        """March the stages with adaptive steps (see the module docstring), from the checkpoint when resumed.

        A checkpoint is written at each stage end, every ``output.checkpoint_minutes`` of wall time and when a
        signal asks the run to stop; each holds the state after a committed step, so the run continues from it
        to the same result."""
        case, ctl, counts, position = self.case, self.case.time, self.counts, self.position
        frame_dT = (self.T_aust - self.T_room) / case.output.frames
        every_s = 60.0 * case.output.checkpoint_minutes
        last_checkpoint = time.perf_counter()
        plan = stages(case)
        estimate = CoolingProgress(self.T_aust, case.air.until_max_C, case.air.temperature_C, ctl.dt_max_s,
                                   ctl.max_dT_K, ctl.max_dX, ctl.growth, ctl.mechanics_max_dT_K, ctl.mechanics_max_dX)
        for index in range(position["stage"], len(plan)):
            stage = plan[index]
            if stage.duration_s <= 0.0:     # a stage the case leaves out (no transfer, no air cooling)
                position["stage"] = index + 1
                continue
            self.bar.phase(f"{stage.name}: boundary HTC")
            with self.timer("bath_htc_s"):
                htc = stage_htc(case, stage.name, self.points)
            bath_C = float(np.mean(htc.ambient_C))
            if position["stage_end_s"] is None:  # the stage starts (not resumed within it)
                position["stage_end_s"] = self.thermal.time_s + stage.duration_s
                self.thermal.restart()
            t_end = position["stage_end_s"]
            later = [(st.duration_s, self._newton_rate_per_s(st) if math.isfinite(st.until_max_C) else None)
                     for st in plan[index + 1:]]
            collapse_C = self._film_collapse_C(htc, t_end)
            filmed = np.isfinite(collapse_C)
            self.bar.phase(stage.name)
            while self.thermal.time_s < t_end - 1e-9 and float(np.max(self.thermal.T)) > stage.until_max_C:
                if self.stop.requested or time.perf_counter() - last_checkpoint >= every_s:
                    self._checkpoint(vtk)
                    last_checkpoint = time.perf_counter()
                    self.stop.check()
                dt = min(position["dt_s"], t_end - self.thermal.time_s)
                try:
                    with self.timer("thermal_metallurgy_s"):
                        step = self.thermal.try_step(dt, htc)
                except SolverError as exc:
                    if dt / 2 < ctl.dt_min_s:
                        raise
                    log.warning("%s; cutting the step to %.3g s", exc, dt / 2)
                    position["dt_s"], counts["rejected"] = dt / 2, counts["rejected"] + 1
                    continue
                dX = max((step.max_dX_by_phase.get(p, 0.0) for p in self.phase_model.time_dependent_phases),
                         default=0.0)
                limit = max(step.max_dT_K / ctl.max_dT_K, dX / ctl.max_dX)
                if limit > 2.0 and dt / 2 >= ctl.dt_min_s:
                    position["dt_s"], counts["rejected"] = dt / 2, counts["rejected"] + 1
                    continue
                converged = self._mechanics_with(step)
                if not converged:
                    if dt / 2 < ctl.dt_min_s:
                        raise SolverError(f"the stress solver did not converge at t = {self.thermal.time_s:.4g} s "
                                          f"even with the smallest step {dt:.3g} s")
                    log.warning("stress Newton did not converge (dt = %.3g s at t = %.4g s); cutting the step",
                                dt, self.thermal.time_s)
                    position["dt_s"], counts["rejected"] = dt / 2, counts["rejected"] + 1
                    continue
                T_qp_before = self.thermal.T_qp
                self.thermal.commit(step)
                counts["steps"] += 1
                counts["heat_out_J"] += step.heat_out_J
                counts["latent_J"] += step.latent_J
                self._record_probes(probes)
                # a frame per 1/frames of the whole cooling, measured by the mean nodal change (the
                # max-norm counted the fast surface swings: ~260 frames for 40 requested)
                if float(np.mean(np.abs(self.thermal.T - self._last_frame_T))) >= frame_dT:
                    self._mechanics_catch_up()
                    with self.timer("output_s"):
                        vtk.write(self.thermal.time_s, self.nodal_fields())
                    self._last_frame_T = self.thermal.T.copy()
                grow = ctl.growth if limit < 1e-12 else min(ctl.growth, 0.9 / limit)
                position["dt_s"] = float(np.clip(dt * grow, ctl.dt_min_s, ctl.dt_max_s))
                T_surface_C = self.fe.at_facet_qp(self.thermal.T).reshape(-1)
                fractions = self.thermal.fractions() if self.kin is not None else {}
                now = StepState(counts["steps"], self.thermal.time_s, self.thermal.T, position["dt_s"],
                                t_end - self.thermal.time_s, math.isfinite(stage.until_max_C), later,
                                float(np.mean(T_surface_C)), float(np.max(T_surface_C - collapse_C)),
                                float(np.mean(T_surface_C[filmed] < collapse_C[filmed])) if filmed.any() else 0.0,
                                float(np.mean(fractions.get("austenite", 0.0))),
                                dX / ctl.max_dX > step.max_dT_K / ctl.max_dT_K,
                                0.0 if self.kin is None else metallurgy.incubation_share(
                                    self.thermal.phase_state, self.kin, self.thermal.T_qp),
                                float(np.mean(sum(fractions.get(r, 0.0) for r in self.kin.reactions)))
                                if self.kin is not None else 0.0,
                                None if self.kin is None else self._diffusional_to_come(T_qp_before, dt),
                                stage_ambient_C=bath_C,
                                martensite_fraction=float(np.mean(fractions.get("martensite", 0.0))),
                                martensite_limit_steps=None if self.kin is None else self._martensite_limit_steps(
                                    T_qp_before, dt, bath_C),
                                stress_steps_done=counts.get("stress_steps", 0))
                steps_left = estimate.steps_left(now)
                stress_s, solve_s = self.timings.get("mechanics_s", 0.0), self.timings.get("thermal_metallurgy_s", 0.0)
                self.bar.update(self.thermal.time_s, estimate.fraction(self.thermal.T), counts["steps"], steps_left,
                                counts.get("stress_steps", 0), estimate.stress_steps_left(now, steps_left),
                                stress_s, solve_s)
            self._mechanics_catch_up()
            position["stage"], position["stage_end_s"] = index + 1, None
            self._checkpoint(vtk)
            last_checkpoint = time.perf_counter()
        self.bar.finish(self.thermal.time_s)

    def _diffusional_to_come(self, T_qp_before: np.ndarray, dt_s: float) -> Callable[[], float]:
        """The forecast of the pearlite + bainite still to form for the progress estimate, from each point's
        cooling rate over the step just taken (asked only when the estimate needs it)."""
        state, T_qp = self.thermal.phase_state, self.thermal.T_qp
        return lambda: metallurgy.diffusional_fraction_to_come(state, self.kin, T_qp, (T_qp_before - T_qp) / dt_s,
                                                               self.case.air.temperature_C)

    def _martensite_limit_steps(self, T_qp_before: np.ndarray, dt_s: float, bath_C: float) -> Callable[[], float]:
        """The forecast of the stress steps the martensite still needs (``time.mechanics_max_dX`` on it) for the
        progress estimate, from the section's cooling rate over the step just taken towards the stage's ambient
        ``bath_C``, then the air's (asked only when needed)."""
        state, T_qp = self.thermal.phase_state, self.thermal.T_qp
        return lambda: metallurgy.martensite_limit_steps_to_come(state, self.kin, T_qp, (T_qp_before - T_qp) / dt_s,
                                                                 bath_C, self.case.air.temperature_C,
                                                                 self.case.time.mechanics_max_dX)

    def _newton_rate_per_s(self, stage: Stage) -> float:
        """The rate ``h A / C`` at which the part would cool in ``stage`` as one lump (Newton's law: the
        stage's HTC at its end temperature integrated over the cooled surface, over the heat capacity of the
        part as it is now), for the progress bar's estimate of a later stage's length."""
        fe, props = self.thermal.fe, self.thermal.props
        htc = stage_htc(self.case, stage.name, self.points)
        T_surface = np.full(fe.facet_r_ds.shape, stage.until_max_C)
        hA = fe.integrate_boundary(htc(T_surface.reshape(-1), self.thermal.time_s).reshape(T_surface.shape))
        T_qp, X = self.thermal.T_qp, self.thermal.fractions()
        C = fe.integrate(props.density_kg_m3(T_qp, X) * props.specific_heat_J_kgK(T_qp, X))
        return hA / C

    def _film_collapse_C(self, htc: Any, time_s: float) -> np.ndarray:
        """Per cooled-surface quadrature point, the temperature above which ``htc`` (at ``time_s``) is in film
        boiling (:func:`quenchsim.progress.film_collapse_temperatures`; +inf without a film), for the progress
        bar's estimate."""
        n = self.fe.facet_r_ds.size
        T_grid_C = np.arange(self.T_room, self.T_aust + 10.0, 10.0)
        return film_collapse_temperatures(T_grid_C, np.array([htc(np.full(n, T), time_s) for T in T_grid_C]))

    # -- checkpoints ----------------------------------------------------------------------------
    def _checkpoint(self, vtk: Any) -> None:
        """Write the whole state after the last committed step to the run folder (atomically)."""
        with self.timer("checkpoint_s"):
            state = {"thermal": self.thermal.checkpoint_state(),
                     "phases": self.phase_model.checkpoint_state(self.thermal.phase_state),
                     "run": {"times": np.asarray(self.times), "probe_rows": np.asarray(self.probe_rows),
                             "last_frame_T": self._last_frame_T, "mesh_p": self.section.mesh.p}}
            if self.mech is not None:
                state["mechanics"] = self.mech.checkpoint_state()
                state["mechanics_ref"] = {"T_qp": self.mech_ref[0], "fractions": self.mech_ref[1]}
            header = {"case": self.case.resolved(), "position": self.position, "counts": self.counts,
                      "frames": vtk.frames, "wall_time_s": time.perf_counter() - self.wall0,
                      "timings_s": self.timings, "time_s": self.thermal.time_s}
            write_checkpoint(self.checkpoint_path, state, header)

    def _restore(self, header: dict[str, Any], state: dict[str, Any]) -> dict[str, Any]:
        """Put the checkpoint's state into the freshly built solvers; returns what :meth:`run` needs."""
        mesh_p = state["run"]["mesh_p"]
        p = self.section.mesh.p
        if mesh_p.shape != p.shape or not np.allclose(mesh_p, p, rtol=0.0, atol=1e-12):
            raise InputError("--resume", str(self.checkpoint_path), "the checkpoint's mesh differs from the one "
                             "built now (another gmsh version?); run without --resume")
        self.thermal.restore_state(state["thermal"], self.phase_model.restore_state(state["phases"]))
        if self.mech is not None:
            self.mech.restore_state(state["mechanics"])
            ref = state["mechanics_ref"]
            self.mech_ref = (np.array(ref["T_qp"]), {p: np.array(v) for p, v in ref["fractions"].items()})
        self.times = [float(t) for t in state["run"]["times"]]
        self.probe_rows = list(np.asarray(state["run"]["probe_rows"]).reshape(len(self.times), -1))
        self._last_frame_T = np.array(state["run"]["last_frame_T"])
        self.counts, self.position = header["counts"], header["position"]
        self.timings.update(header["timings_s"])
        log.warning("resuming %s from its checkpoint at t = %.6g s", self.out, self.thermal.time_s)
        return {"frames": [tuple(f) for f in header["frames"]], "wall_time_s": float(header["wall_time_s"])}

    def _end_state(self, closing_step: bool = True) -> dict[str, Any]:
        """Close the run at room temperature when the part has cooled to within ``air.until_max_C``;
        otherwise (a stage that ended early, a failed or interrupted run) report the hot state as it is."""
        T_max, T_min = float(np.max(self.thermal.T)), float(np.min(self.thermal.T))
        cooled = T_max <= self.case.air.until_max_C + 1e-9
        if closing_step and cooled:
            self._equilibrate_at_room_temperature()
            return {"at_room_temperature": True, "time_s": float(self.thermal.time_s),
                    "max_temperature_before_closing_C": T_max}
        try:   # the stresses of the last thermal state (a failed or interrupted run; the checkpoint is written)
            self._mechanics_catch_up()
        except SolverError as exc:
            log.error("stresses and dimensions are those at the last stress step before t = %.4g s: %s",
                      self.thermal.time_s, exc)
        note = ("the part is still hot: temperatures, phases, hardness, dimensions and stresses are those at the "
                "end of the last stage, not of the cooled part")
        if closing_step:
            log.warning("the air stage ended at t = %.4g s with the part at up to %.0f C (air.until_max_C = %g C): %s",
                        self.thermal.time_s, T_max, self.case.air.until_max_C, note)
        return {"at_room_temperature": False, "time_s": float(self.thermal.time_s), "max_temperature_C": T_max,
                "min_temperature_C": T_min, "note": note}

    @contextlib.contextmanager
    def timer(self, key: str) -> Iterator[None]:
        """Accumulate the wall time of a block into ``self.timings[key]`` (reported in summary.json)."""
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.timings[key] = self.timings.get(key, 0.0) + time.perf_counter() - t0

    def _mechanics_step(self, T_qp: np.ndarray, fractions: dict[str, np.ndarray]) -> bool:
        """One stress step from the state of the last one (``self.mech_ref``) to (T_qp, fractions)."""
        if self.mech is None:
            return True
        T_ref, X_ref = self.mech_ref
        converged = bool(self.mech.step(T_qp, fractions, T_ref, X_ref).converged)
        if converged:
            self.mech_ref = (T_qp, fractions)
            self.counts["stress_steps"] = self.counts.get("stress_steps", 0) + 1
        return converged

    def _beyond_mechanics_limits(self, T_qp: np.ndarray, fractions: dict[str, np.ndarray]) -> bool:
        """Whether the change from the last stress step to (T_qp, fractions) exceeds ``time.mechanics_max_dT_K``
        or ``time.mechanics_max_dX``."""
        return self._mechanics_limit_ratio(T_qp, fractions) > 1.0

    def _mechanics_limit_ratio(self, T_qp: np.ndarray, fractions: dict[str, np.ndarray]) -> float:
        """The change from the last stress step to (T_qp, fractions) over the ``time.mechanics_*`` limits: the
        larger of the temperature change over ``mechanics_max_dT_K`` and any phase change over
        ``mechanics_max_dX`` (inf where a change meets a limit of 0)."""
        ctl = self.case.time
        T_ref, X_ref = self.mech_ref

        def ratio(change: float, limit: float) -> float:
            return change / limit if limit > 0.0 else (math.inf if change > 0.0 else 0.0)

        dX = max((float(np.max(np.abs(X - X_ref.get(p, 0.0)))) for p, X in fractions.items()), default=0.0)
        return max(ratio(float(np.max(np.abs(T_qp - T_ref))), ctl.mechanics_max_dT_K),
                   ratio(dX, ctl.mechanics_max_dX))

    def _mechanics_with(self, step: Any) -> bool:
        """The stress solver's part of a thermal step about to be committed (multirate: the stress solver is
        rate-independent, so it steps only when the change since its last step would exceed the time.mechanics_*
        limits). The thermal steps since its last step are first caught up to the committed state; then, when
        ``step`` alone exceeds the limits, it is taken in as many stress steps as keep each within them, along its
        own path. False when the first of them does not converge (nothing is committed and the caller cuts the
        thermal step, as when every step is a stress step); a later one that does not converge is halved
        (:meth:`_mechanics_to`)."""
        if self.mech is None or not self._beyond_mechanics_limits(step.T_qp, step.phase_state.fractions):
            return True
        self._mechanics_catch_up()  # raises SolverError if even sub-steps fail (committed steps cannot be cut)
        T1, X1 = step.T_qp, self.phase_model.fractions(step.phase_state)
        ratio = self._mechanics_limit_ratio(T1, X1)
        if ratio <= 1.0:
            return True
        # a thermal step beyond the limits is split into as many stress steps as keep each within them, along the
        # step's own path: the temperatures linear in time, the phases as the kinetics form them on that path
        # (martensite, for one, is not linear in T: a straight line in (T, X) moved ring B's dimensions by ~0.04 mm)
        # (the kinetics on the path advance from one sub-step's state to the next; their time counts as the stress
        # steps' own, which they serve)
        parts = int(min(math.ceil(ratio), MAX_STRESS_STEPS_PER_THERMAL_STEP)) if math.isfinite(ratio) else 1
        T0, state = self.thermal.T_qp, self.thermal.phase_state
        T = T0
        for k in range(1, parts + 1):
            with self.timer("mechanics_s"):
                if k == parts:
                    T, X = T1, X1
                else:
                    T_before, T = T, T0 + (k / parts) * (T1 - T0)
                    state = self.phase_model.advance(state, T_before, T, step.dt_s / parts)
                    X = self.phase_model.fractions(state)
                converged = self._mechanics_step(T, X)
            if not converged:
                if k == 1:
                    return False  # nothing committed: the caller cuts the thermal step
                self._mechanics_to(T1, X1, f"at t = {self.thermal.time_s + step.dt_s:.4g} s",
                                   share=1.0 / (parts - k + 1))
                return True
        return True

    def _mechanics_catch_up(self) -> None:
        """Bring the stress solver to the committed thermal state (its change since the last stress step spans
        committed thermal steps, which cannot be cut: :meth:`_mechanics_to` splits it if need be)."""
        if self.mech is not None:
            self._mechanics_to(self.thermal.T_qp, self.thermal.fractions(),
                               f"catching up to t = {self.thermal.time_s:.4g} s")

    def _mechanics_to(self, T_end: np.ndarray, X_end: dict[str, np.ndarray], what: str, share: float = 1.0) -> None:
        """Stress steps from the last one's state to (T_end, X_end) along the straight path between the two states,
        each ``share`` of the change (one step by default); a step that does not converge is halved, down to 1/64
        of the first."""
        T_ref, X_ref = self.mech_ref
        if np.array_equal(T_end, T_ref) and all(np.all(X == X_ref.get(p, 0.0)) for p, X in X_end.items()):
            return      # already there (no change since the last stress step)
        smallest = share / 64.0
        with self.timer("mechanics_s"):
            done = 0.0
            while done < 1.0 - 1e-12:
                s = min(1.0, done + share)
                s = 1.0 if s > 1.0 - 1e-9 else s
                T = T_ref + s * (T_end - T_ref) if s < 1.0 else T_end
                X = ({p: X_ref.get(p, 0.0) + s * (v - X_ref.get(p, 0.0)) for p, v in X_end.items()} if s < 1.0
                     else X_end)
                if self._mechanics_step(T, X):
                    done = s
                    continue
                share /= 2.0
                if share < smallest:
                    raise SolverError(f"the stress solver did not converge {what} even in sub-steps of {smallest:.3g} "
                                      "of the change since its last step")
                log.warning("stress Newton did not converge %s; sub-steps of %g of the change", what, share)

    def _equilibrate_at_room_temperature(self) -> None:
        """Final state: the whole ring at room temperature (the air stage ended with the hottest point below
        air.until_max_C; the last few kelvin are one step, with the martensite they still form).

        The step takes no time for the diffusional reactions (dt = 0): its length is not modelled, and an
        assumed hour at 20-40 C had let the peer's bainite law, extrapolated far below its 240-440 C data,
        form 0.02 bainite out of retained austenite after the quench had ended."""
        T_room = np.full(self.thermal.T.shape, self.T_room)
        T_qp = self.fe.at_qp(T_room)
        state = self.phase_model.advance(self.thermal.phase_state, self.thermal.T_qp, T_qp, 0.0)
        if self.mech is not None:
            self._mechanics_to(T_qp, state.fractions, "in the final step to room temperature")
        self.thermal.T, self.thermal.T_qp, self.thermal.phase_state = T_room, T_qp, state

    # -- the final part -------------------------------------------------------------------------
    def _rigid_axial_shift_m(self, vertices_m: np.ndarray) -> float:
        """Axial shift of the section's volume centroid from the "before" section: a rigid translation set by
        the solver's fixed point, not a distortion (removed from every final-part output)."""
        def centroid_z(p: np.ndarray) -> float:
            tri = p[:, self.section.mesh.t]                               # (2, 3, ne)
            area = 0.5 * np.abs((tri[0, 1] - tri[0, 0]) * (tri[1, 2] - tri[1, 0])
                                - (tri[0, 2] - tri[0, 0]) * (tri[1, 1] - tri[1, 0]))
            weight = area * tri[0].mean(axis=0)                          # r dA: the ring's volume
            return float(np.sum(weight * tri[1].mean(axis=0)) / np.sum(weight))
        return centroid_z(vertices_m) - centroid_z(self.before_mesh.p)

    def _deformed_vertices(self) -> tuple[np.ndarray, float]:
        """The mesh vertices moved by the solver's displacement and their rigid axial shift (stress solved)."""
        p = self.section.mesh.p + self.mech.vertex_displacement().T
        return p, self._rigid_axial_shift_m(p)

    def final_vertices(self) -> np.ndarray:
        """Mesh vertices (2, nv) of the part after the run, without rigid axial translation: the deformed
        section when the stress is solved; otherwise the "before" section (no distortion computed)."""
        if self.mech is None:
            return self.before_mesh.p.copy()
        p, shift = self._deformed_vertices()
        p[1] -= shift
        return p

    def final_section(self) -> FinalSection:
        if self.mech is None:
            return FinalSection.of(self.before_mesh.p.copy(), self.section.mesh.t,
                                   mechanics.section_outline(self.before_mesh))
        p, shift = self._deformed_vertices()
        p[1] -= shift
        outline = mechanics.section_outline(self.section.mesh, self.mech.displacement_m)
        outline[:, 1] -= shift
        return FinalSection.of(p, self.section.mesh.t, outline)

    def _final_frame(self, vtk: Any) -> Path:
        """The last VTK frame: on the "before" (room-temperature, pre-quench) section, with ``displacement_m``
        carrying it to the final part (warp by 1 shows the part, by 10 its distortion x10) and
        ``displacement_from_start_m``, the solver's displacement from the austenitised start section with its
        fixed point (the frames before it are on that section, displaced from there)."""
        fields = self.nodal_fields()
        if self.mech is not None:
            # the solver's own displacement from the quench's start section (fixed point held) stays available
            fields["displacement_from_start_m"] = fields["displacement_m"]
            d = self.final_vertices() - self.before_mesh.p
            fields["displacement_m"] = np.column_stack([d.T, np.zeros(d.shape[1])])
        return vtk.write(self.thermal.time_s, fields, points_rz=self.before_mesh.p)

    # -- summary --------------------------------------------------------------------------------
    def mechanics_summary(self, final: FinalSection) -> dict[str, Any]:
        """Dimensions before/after and their distortion budget, residual stresses at mid-width, traverse and
        outline files."""
        before = mechanics.ring_dimensions(self.before_mesh)
        after = mechanics.ring_dimensions(self.section.mesh, self.mech.displacement_m)
        r_mm, hoop, axial = residual_traverse(final, self.mech.nodal_fields())
        self.writer.residual_traverse(r_mm, hoop, axial)
        before_outline_mm = mechanics.section_outline(self.before_mesh) / MM
        self.writer.outline(before_outline_mm, final.outline_m / MM)
        budget = mechanics.distortion_budget(self.mech, self.before_mesh, self.thermal.T_qp, self.thermal.fractions(),
                                             self.mech_model.annealed_free_strain)
        return {"dimensions_mm": mechanics.dimension_change(before, after),
                "shape_mm": shape_change(before_outline_mm, final.outline_m / MM),
                "distortion_budget_mm": budget,
                "residual_stress_MPa": residual_stress_summary(hoop, axial)}

    def handling_summary(self) -> dict[str, Any]:
        """How the part was quenched: transfer, immersion, and for the bath model the quenchant and its
        liquid-property file, bath temperature, agitation and the part's support."""
        case = self.case
        out: dict[str, Any] = {"transfer_time_s": case.transfer.time_s, "htc_model": case.quench.htc_model,
                               "immersion_speed_mm_s": case.quench.immersion_speed_mm_s}
        bath = case.quench.bath
        if bath is not None:
            out.update(quenchant=case.get("quench.bath.quenchant"), liquid_properties=bath.liquid.name,
                       oil_temperature_C=bath.oil_temperature_C, agitation=bath.agitation,
                       agitation_m_s=bath.agitation_m_s, support=bath.support,
                       support_open_fraction=bath.turntable_open_fraction)
        return out

    def summary(self, time_s: np.ndarray, probe_T: dict[str, np.ndarray], wall0: float) -> dict[str, Any]:
        fields = self.nodal_fields()
        out: dict[str, Any] = {"case": self.case.name, "condition": self.case.condition,
                               "quenchsim_version": __version__, "case_sha256": self.case.digest()}
        out["probes"] = probe_times(time_s, probe_T)
        out["quench"] = self.handling_summary()
        final = self.final_section()
        if self.kin is None:
            out["notes"] = ['the material does not transform (transformations = "none"): no phases, no hardness']
        else:
            out["hardness"], traverse = hardness_summary(self.profile, self.projection.p1, final,
                                                         fields["hardness_HRC"])
            self.writer.hardness_traverse(traverse["bore"][0], traverse["bore"][1], traverse["od"][1])
            out["phases_final"] = phase_statistics(self.thermal.fractions(), self.fe.r_dx)
        if self.mech is not None:
            out.update(self.mechanics_summary(final))
            measured = compare_with_measured(out.get("dimensions_mm"), dict(self.case.data), self.case.condition)
            if measured is not None:
                out["measured"] = measured
        out["energy"] = {"heat_extracted_J": self.counts["heat_out_J"], "latent_released_J": self.counts["latent_J"]}
        out["solver"] = {"wall_time_s": time.perf_counter() - wall0, "stage_time_s": dict(self.timings),
                         "steps": self.counts["steps"], "rejected_steps": self.counts["rejected"],
                         "stress_steps": self.counts.get("stress_steps", 0), "dofs": int(self.fe.n_dofs),
                         "elements": int(self.section.n_elements), "end_time_s": float(self.thermal.time_s)}
        return out


def read_resumable(case: Case, out_dir: Path) -> tuple[dict[str, Any], dict[str, Any]]:
    """The checkpoint of ``out_dir`` when it belongs to ``case`` (the same resolved inputs); otherwise a one-line
    :class:`InputError` (no checkpoint, another case, another checkpoint format)."""
    path = out_dir / files.CHECKPOINT_NPZ
    if not path.is_file():
        raise InputError("--resume", str(out_dir), f"holds no {files.CHECKPOINT_NPZ} to continue from (the run "
                         "completed, or never reached its first checkpoint); run without --resume")
    try:
        header, state = read_checkpoint(path)
    except (OSError, ValueError, KeyError, zipfile.BadZipFile) as exc:
        raise InputError("--resume", str(path), f"cannot be read ({exc}); run without --resume") from None
    if header.get("format") != CHECKPOINT_FORMAT:
        raise InputError("--resume", str(path), f"is of checkpoint format {header.get('format')}, this version "
                         f"reads {CHECKPOINT_FORMAT}; run without --resume")
    difference = _first_difference(_results_inputs(header["case"]), _results_inputs(case.resolved()))
    if difference is not None:
        raise InputError("--resume", str(out_dir), f"its run is of another case ({difference}); resume with the "
                         "same case file, condition and --set options, or run without --resume")
    return header, state


def _results_inputs(resolved: dict[str, Any]) -> dict[str, Any]:
    """A resolved case as JSON data without the options that change no result (how often to checkpoint)."""
    data = json.loads(json.dumps(resolved))
    data.get("output", {}).pop("checkpoint_minutes", None)
    return data


def _first_difference(there: Any, here: Any, key: str = "") -> str | None:
    """The first dotted key where two resolved cases differ, as ``key: A there, B here``."""
    if isinstance(there, dict) and isinstance(here, dict):
        for k in sorted(set(there) | set(here)):
            found = _first_difference(there.get(k), here.get(k), f"{key}.{k}" if key else k)
            if found:
                return found
        return None
    return None if there == here else f"{key}: {there!r} there, {here!r} here"


class _StopRequest:
    """SIGTERM (a batch scheduler's time limit) or SIGINT (Ctrl-C) as a request to stop, honoured by the step
    loop after its last committed step (so the checkpoint it writes is whole); a second signal stops at once."""

    def __init__(self) -> None:
        self.signal_name: str | None = None

    @property
    def requested(self) -> bool:
        return self.signal_name is not None

    def __call__(self, signum: int, frame: Any) -> None:
        name = signal.Signals(signum).name
        if self.signal_name is not None:
            raise RunInterrupted(f"interrupted by a second signal {name}")
        self.signal_name = name

    def check(self) -> None:
        if self.signal_name is not None:
            raise RunInterrupted(f"interrupted by signal {self.signal_name}")


@contextlib.contextmanager
def _signals_as_stop_request(stop: _StopRequest) -> Iterator[None]:
    """Route SIGTERM and SIGINT to ``stop`` while the stages run (only in the main thread, where signals are
    delivered; elsewhere Ctrl-C stays a KeyboardInterrupt)."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = {sig: signal.signal(sig, stop) for sig in (signal.SIGTERM, signal.SIGINT)}
    try:
        yield
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
