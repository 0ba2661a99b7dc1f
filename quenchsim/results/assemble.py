"""The summary of a quench run (``summary.json``) assembled from the finished run's state, with the traverse and
outline files it refers to (:mod:`quenchsim.results.files`)."""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from quenchsim import __version__, mechanics, metallurgy
from quenchsim.errors import RunInterrupted
from quenchsim.geometry.profile import MM
from quenchsim.results.measured import compare_with_measured
from quenchsim.results.postprocess import phase_statistics
from quenchsim.results.shape import shape_change
from quenchsim.results.summary import (FinalSection, hardness_summary, probe_state, probe_times,
                                       residual_stress_summary, residual_traverse)


def nodal_fields(run: Any) -> dict[str, np.ndarray]:
    """The nodal fields of ``run``'s present state (a VTK frame): temperature, the phases and hardness of a steel
    that transforms, the stress solver's fields when the stress is solved."""
    nv = run.section.mesh.p.shape[1]
    state = run.thermal.phase_state
    data = {"temperature_C": run.thermal.T[:nv].copy()}
    if run.kin is not None:  # a non-transforming material has no phases or hardness to show
        for phase, X in state.fractions.items():
            data[phase] = run.projection(X)
        hv = metallurgy.hardness_HV(state, run.kin)
        data["hardness_HV"] = run.projection(hv)
        data["hardness_HRC"] = metallurgy.hv_to_hrc(data["hardness_HV"])
    if run.mech is not None:
        data.update(run.mech.nodal_fields())
    return data


def final_frame(run: Any) -> Any:
    """The last VTK frame: on the "before" (room-temperature, pre-quench) section, with ``displacement_m``
    carrying it to the final part (warp by 1 shows the part, by 10 its distortion x10) and
    ``displacement_from_start_m``, the solver's displacement from the austenitised start section with its
    fixed point (the frames before it are on that section, displaced from there)."""
    fields = nodal_fields(run)
    if run.mech is not None:
        # the solver's own displacement from the quench's start section (fixed point held) stays available
        fields["displacement_from_start_m"] = fields["displacement_m"]
        d = run.final_part.vertices() - run.before_mesh.p
        fields["displacement_m"] = np.column_stack([d.T, np.zeros(d.shape[1])])
    return run.record.vtk.write(run.thermal.time_s, fields, points_rz=run.before_mesh.p)


def handling_summary(case: Any) -> dict[str, Any]:
    """How the part was quenched: transfer, immersion, and for the bath model the quenchant and its
    liquid-property file, bath temperature, agitation and the part's support."""
    out: dict[str, Any] = {"transfer_time_s": case.transfer.time_s, "htc_model": case.quench.htc_model,
                           "immersion_speed_mm_s": case.quench.immersion_speed_mm_s}
    bath = case.quench.bath
    if bath is not None:
        out.update(quenchant=case.get("quench.bath.quenchant"), liquid_properties=bath.liquid.name,
                   oil_temperature_C=bath.oil_temperature_C, agitation=bath.agitation,
                   agitation_m_s=bath.agitation_m_s, support=bath.support,
                   support_open_fraction=bath.turntable_open_fraction)
    return out


def mechanics_summary(run: Any, final: FinalSection) -> dict[str, Any]:
    """Dimensions before/after and their distortion budget, residual stresses at mid-width, traverse and
    outline files (``run``: a finished :class:`quenchsim.pipeline.QuenchRun` with the stress solved)."""
    before = mechanics.ring_dimensions(run.before_mesh)
    after = mechanics.ring_dimensions(run.section.mesh, run.mech.displacement_m)
    r_mm, hoop, axial = residual_traverse(final, run.mech.nodal_fields())
    run.writer.residual_traverse(r_mm, hoop, axial)
    before_outline_mm = mechanics.section_outline(run.before_mesh) / MM
    run.writer.outline(before_outline_mm, final.outline_m / MM)
    budget = mechanics.distortion_budget(run.mech, run.before_mesh, run.thermal.T_qp, run.thermal.fractions(),
                                         run.mech_model.annealed_free_strain)
    return {"dimensions_mm": mechanics.dimension_change(before, after),
            "shape_mm": shape_change(before_outline_mm, final.outline_m / MM),
            "distortion_budget_mm": budget,
            "residual_stress_MPa": residual_stress_summary(hoop, axial)}


def run_summary(run: Any, time_s: np.ndarray, probe_T: dict[str, np.ndarray], wall0: float) -> dict[str, Any]:
    """The summary of the finished ``run`` (:class:`quenchsim.pipeline.QuenchRun`): probes, handling, hardness and
    phases (a transforming steel), dimensions, shape, budget and stresses (stress solved), energy and solver
    counts; writes the hardness, residual-stress and outline files on the way."""
    case = run.case
    fields = nodal_fields(run)
    out: dict[str, Any] = {"case": case.name, "condition": case.condition,
                           "quenchsim_version": __version__, "case_sha256": case.digest()}
    out["probes"] = probe_times(time_s, probe_T)
    out["quench"] = handling_summary(case)
    final = run.final_part.section()
    if run.kin is None:
        out["notes"] = ['the material does not transform (transformations = "none"): no phases, no hardness']
    else:
        out["hardness"], traverse = hardness_summary(run.profile, run.projection.p1, final, fields["hardness_HRC"])
        run.writer.hardness_traverse(traverse["bore"][0], traverse["bore"][1], traverse["od"][1])
        out["phases_final"] = phase_statistics(run.thermal.fractions(), run.fe.r_dx)
        if case.probes:   # the final phases and hardness where the thermocouples sit (austenitised geometry)
            pts = np.array([[p.r_mm, p.z_mm] for p in case.probes]).T * MM * run.case_to_hot
            phases = tuple(run.thermal.fractions())
            state = probe_state(run.projection.p1, pts, [p.name for p in case.probes], fields, phases)
            for name, entry in state.items():
                out["probes"][name].update(entry)
    if run.mech is not None:
        out.update(mechanics_summary(run, final))
        measured = compare_with_measured(out.get("dimensions_mm"), dict(case.data), case.condition)
        if measured is not None:
            out["measured"] = measured
    counts = run.counts
    out["energy"] = {"heat_extracted_J": counts["heat_out_J"], "latent_released_J": counts["latent_J"]}
    out["solver"] = {"wall_time_s": time.perf_counter() - wall0, "stage_time_s": dict(run.timings),
                     "steps": counts["steps"], "rejected_steps": counts["rejected"],
                     "stress_steps": counts.get("stress_steps", 0), "dofs": int(run.fe.n_dofs),
                     "elements": int(run.section.n_elements), "end_time_s": float(run.thermal.time_s)}
    return out


def summary_or_why_not(run: Any, time_s: np.ndarray, probe_T: dict[str, np.ndarray]) -> dict[str, Any]:
    """``run.summary(...)``; when post-processing is interrupted or fails, a summary.json that says so (and the
    interruption or error raised on)."""
    case = run.case
    try:
        return run.summary(time_s, probe_T, run.wall0)
    except KeyboardInterrupt:  # the stages are done and checkpointed: say so, and how to finish
        run.writer.summary({"case": case.name, "condition": case.condition, "status": "interrupted",
                            "error": "interrupted during post-processing (finish it with --resume)",
                            "stopped_at_s": run.thermal.time_s})
        raise RunInterrupted(f"run interrupted during post-processing; finish it with --resume ({run.out})") \
            from None
    except Exception as exc:  # keep what was computed: record the failure, then re-raise
        run.writer.summary({"case": case.name, "condition": case.condition, "status": "failed",
                            "error": f"post-processing: {exc!r}"})
        raise


def with_outcome(summary: dict[str, Any], status: str, error: str | None, end_state: dict[str, Any],
                 time_s: float) -> str:
    """Put the run's outcome into ``summary``: its end state, its status ("hot" for an "ok" run whose stages ended
    before the part cooled: its results are not the finished part's) and, after an error, where it stopped.
    Returns the status."""
    summary["end_state"] = end_state
    if status == "ok" and not end_state["at_room_temperature"]:
        status = "hot"
    summary["status"] = status
    if error:
        summary["error"] = error
        summary["stopped_at_s"] = time_s
    return status
