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

import logging
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from quenchsim import closing
from quenchsim.case import Case
from quenchsim.quench_setup import (TEMPER_STAGES, QuenchModel, require_mechanics_data, stage_htc, stages,
                                    step_controller)
from quenchsim.errors import InputError, QuenchsimError, RunInterrupted, SolverError
from quenchsim.io.checkpoint import read_resumable, restore_run, save_run
from quenchsim.io.signals import StopRequest, signals_as_stop_request
from quenchsim.mechanics.coupling import StressCoupling
from quenchsim.progress import RunProgress
from quenchsim.progress.observer import QuenchObserver
from quenchsim.results import RunWriter, files
from quenchsim.results.assemble import final_frame, nodal_fields, run_summary, summary_or_why_not, with_outcome
from quenchsim.results.writer import claim_run_folder
from quenchsim.results.stream import RunRecord
from quenchsim.results.timings import StageTimings
from quenchsim.run_state import Position, StepCounts

log = logging.getLogger("quenchsim")


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


# -- the run ------------------------------------------------------------------------------------
class QuenchRun(QuenchModel):
    """Everything of one run: the model (section, solvers), output writer, stages and steps. Use :func:`run`."""

    def __init__(self, case: Case, out_dir: Path, progress: bool = True, resume: bool = False,
                 force: bool = False) -> None:
        self.case = case
        # a resumed run checks its case against the folder's before anything is written or meshed; a new one
        # checks the folder and clears an earlier run's outputs (stale frames, an earlier summary's status)
        self.checkpoint_path = Path(out_dir) / files.CHECKPOINT_NPZ
        if resume and case.temper is not None:
            raise InputError("--resume", str(out_dir), "a run with a [temper] stage cannot be resumed yet; run it "
                             "again without --resume")
        checkpoint = read_resumable(self.checkpoint_path, case.resolved(), Path(out_dir)) if resume else None
        require_mechanics_data(case)   # a transforming steel without mechanics data: refused, nothing written
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
        super().__init__(case, self.writer.mesh_path)
        self.timings = StageTimings()
        self.counts = StepCounts()
        self.position = Position(dt_s=case.time.dt_initial_s)
        self.as_quenched: dict[str, Any] | None = None   # the summary of the quenched state, kept when a temper follows
        self.stress: StressCoupling | None = None if self.mech is None else StressCoupling(
            self.mech, self.thermal, self.phase_model, case.time.mechanics_max_dT_K, case.time.mechanics_max_dX,
            self.timings, self._count_stress_step)
        self.stop = StopRequest()
        self.restored = None if checkpoint is None else restore_run(self, *checkpoint)
        if self.restored is not None:
            self.counts, self.position = self.restored.counts, self.restored.position
            log.warning("resuming %s from its checkpoint at t = %.6g s", self.out, self.thermal.time_s)

    def nodal_fields(self) -> dict[str, np.ndarray]:
        return nodal_fields(self)

    def run(self) -> RunResult:
        """March the stages, close the run and write its summary (see :func:`run`)."""
        self.wall0 = time.perf_counter()
        self.record = RunRecord(self.writer, self.section.mesh, [p.name for p in self.case.probes],
                                self.probe_matrix, (self.T_aust - self.T_room) / self.case.output.frames)
        if self.restored is None:
            self.record.start(self.thermal.T, self.nodal_fields())
        else:  # the probe rows and frames up to the checkpoint, as the interrupted run wrote them
            self.record.resume(self.restored.record, self.restored.frames)
            self.wall0 -= self.restored.wall_time_s
        status, error, end_state = self._march()
        self.bar.phase("output")
        self.writer.final_3d(final_frame(self))
        time_arr, probe_T = self.record.series()
        summary = summary_or_why_not(self, time_arr, probe_T)
        status = with_outcome(summary, status, error, end_state, self.thermal.time_s)
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

    def _march(self) -> tuple[str, str | None, dict[str, Any]]:
        """The stages and the run's end state, or where an interruption or a solver failure left it: (status,
        error, end state)."""
        status, error = "ok", None
        try:
            with signals_as_stop_request(self.stop):
                self._stages()
                self.stop.check()
                end_state = closing.end_state(self)
                if end_state["at_room_temperature"]:   # probes.csv ends, like the last frame, on the closing step
                    self.record.step(self.thermal.time_s, self.thermal.T)
        except (KeyboardInterrupt, RunInterrupted) as exc:
            status, error = "interrupted", str(exc) or "interrupted (Ctrl-C)"
            try:
                end_state = closing.end_state(self, closing_step=False)
            except KeyboardInterrupt:   # Ctrl-C again while the stresses catch up: keep the last stress step's
                end_state = {"at_room_temperature": False, "time_s": float(self.thermal.time_s),
                             "note": "interrupted again while the stresses caught up with the last thermal step: "
                                     "stresses and dimensions are those of the last stress step"}
            log.error("run interrupted at t = %.4g s", self.thermal.time_s)
        except QuenchsimError as exc:
            status, error = "failed", str(exc)
            end_state = closing.end_state(self, closing_step=False)
            log.error("run stopped at t = %.4g s: %s", self.thermal.time_s, exc)
        finally:
            self.record.probes.close()
        return status, error, end_state

    def _stages(self) -> None:
        """March the stages with adaptive steps (see the module docstring), from the checkpoint when resumed.

        A checkpoint is written at each stage end, every ``output.checkpoint_minutes`` of wall time and when a
        signal asks the run to stop; each holds the state after a committed step, so the run continues from it
        to the same result."""
        case, ctl, counts, position = self.case, self.case.time, self.counts, self.position
        every_s = 60.0 * case.output.checkpoint_minutes
        last_checkpoint = time.perf_counter()
        plan = stages(case)
        steps = step_controller(ctl)
        observer = QuenchObserver(self, self.bar)
        for index in range(position.stage, len(plan)):
            stage = plan[index]
            if stage.duration_s <= 0.0:     # a stage the case leaves out (no transfer, no air cooling)
                position.stage = index + 1
                continue
            self.bar.phase(f"{stage.name}: boundary HTC")
            with self.timings("bath_htc_s"):
                htc = stage_htc(case, stage.name, self.points)
            if position.stage_end_s is None:  # the stage starts (not resumed within it)
                if stage.name == "temper":
                    self._start_temper()
                position.stage_end_s = self.thermal.time_s + stage.duration_s
                self.thermal.restart()
            t_end = position.stage_end_s
            tempering = stage.name in TEMPER_STAGES
            if not tempering:
                observer.stage(stage, plan[index + 1:], htc, lambda name: stage_htc(case, name, self.points), t_end)
            self.bar.phase(stage.name)
            while self.thermal.time_s < t_end - 1e-9 and float(np.max(self.thermal.T)) > stage.until_max_C:
                if self.stop.requested or time.perf_counter() - last_checkpoint >= every_s:
                    self._checkpoint()
                    last_checkpoint = time.perf_counter()
                    self.stop.check()
                dt = min(position.dt_s, t_end - self.thermal.time_s)
                try:
                    with self.timings("thermal_metallurgy_s"):
                        step = self.thermal.try_step(dt, htc)
                except SolverError as exc:
                    if not steps.can_halve(dt):
                        raise
                    log.warning("%s; cutting the step to %.3g s", exc, dt / 2)
                    position.dt_s, counts.rejected = dt / 2, counts.rejected + 1
                    continue
                dX = max((step.max_dX_by_phase.get(p, 0.0) for p in self.phase_model.time_dependent_phases),
                         default=0.0)
                limit = steps.ratio(step.max_dT_K, dX)
                if steps.rejects(dt, limit):
                    position.dt_s, counts.rejected = dt / 2, counts.rejected + 1
                    continue
                converged = self.stress is None or self.stress.with_step(step)
                if not converged:
                    if not steps.can_halve(dt):
                        raise SolverError(f"the stress solver did not converge at t = {self.thermal.time_s:.4g} s "
                                          f"even with the smallest step {dt:.3g} s")
                    log.warning("stress Newton did not converge (dt = %.3g s at t = %.4g s); cutting the step",
                                dt, self.thermal.time_s)
                    position.dt_s, counts.rejected = dt / 2, counts.rejected + 1
                    continue
                T_qp_before = self.thermal.T_qp
                self.thermal.commit(step)
                counts.steps += 1
                counts.heat_out_J += step.heat_out_J
                counts.latent_J += step.latent_J
                self.record.step(self.thermal.time_s, self.thermal.T)
                if self.record.frame_due(self.thermal.T):
                    self.catch_up_stresses()
                    with self.timings("output_s"):
                        self.record.frame(self.thermal.time_s, self.thermal.T, self.nodal_fields())
                position.dt_s = steps.next_dt(dt, limit)
                if tempering:
                    self.bar.update(self.thermal.time_s, min(self.thermal.time_s / self.bar.total_s, 0.999),
                                    counts.steps, 0.0)
                else:
                    observer.step(dt, dX, step.max_dT_K, T_qp_before)
            self.catch_up_stresses()
            position.stage, position.stage_end_s = index + 1, None
            self._checkpoint()
            last_checkpoint = time.perf_counter()
        self.bar.finish(self.thermal.time_s)

    def _start_temper(self) -> None:
        """The quench is over: close it at room temperature (when the air stage cooled the part), keep the as-quenched
        summary, and hand the thermal and stress solvers the tempering (:mod:`quenchsim.metallurgy.tempering`,
        :mod:`quenchsim.mechanics.tempering`)."""
        from quenchsim.mechanics.tempering import TemperCoupling
        from quenchsim.metallurgy.tempering import TemperingPhaseModel, relaxation_term, tempering_free_strain
        from quenchsim.results.assemble import state_summary

        self.catch_up_stresses()
        if float(np.max(self.thermal.T)) <= self.case.air.until_max_C + 1e-9:
            closing.close_at_room_temperature(self)
        else:
            log.warning("the air stage ended with the part at up to %.0f C: the temper starts from that hot state",
                        float(np.max(self.thermal.T)))
        self.as_quenched = state_summary(self)
        tempering = self.tempering
        assert tempering is not None   # the case loads only when its steel has tempering data (case.parse._temper)
        model = TemperingPhaseModel(tempering)
        self.phase_model = self.thermal.phase_model = model
        self.thermal.phase_state = model.start(self.thermal.phase_state)
        if self.stress is not None:
            self.stress = TemperCoupling(self.mech, self.thermal, model,
                                         lambda state: tempering_free_strain(tempering, state),
                                         lambda state: relaxation_term(tempering, state.P),
                                         self.timings, self._count_stress_step)

    def _checkpoint(self) -> None:
        """Write the whole state after the last committed step to the run folder (:func:`save_run`)."""
        with self.timings("checkpoint_s"):
            save_run(self)

    def _count_stress_step(self) -> None:
        self.counts.stress_steps += 1

    def catch_up_stresses(self) -> None:
        """Bring the stresses to the committed thermal state (:meth:`StressCoupling.catch_up`)."""
        if self.stress is not None:
            self.stress.catch_up()

    def summary(self, time_s: np.ndarray, probe_T: dict[str, np.ndarray], wall0: float) -> dict[str, Any]:
        """summary.json of the finished run (:func:`quenchsim.results.assemble.run_summary`)."""
        return run_summary(self, time_s, probe_T, wall0)
