"""The summary of a quench run (``summary.json``) assembled from the finished run's state, with the traverse and
outline files it refers to (:mod:`quenchsim.results.files`)."""

from __future__ import annotations

import time
from typing import Any

import numpy as np

from quenchsim import __version__, mechanics, metallurgy
from quenchsim.errors import RunInterrupted
from quenchsim.geometry.profile import MM
from quenchsim.results import files
from quenchsim.results.measured import compare_with_measured
from quenchsim.results.postprocess import phase_statistics
from quenchsim.results.shape import shape_change
from quenchsim.run_state import RunState
from quenchsim.results.summary import (FinalSection, hardness_summary, probe_state, probe_times,
                                       residual_stress_summary, residual_traverse)


def nodal_fields(run: RunState) -> dict[str, np.ndarray]:
    """The nodal fields of ``run``'s present state (a VTK frame): temperature, the phases and hardness of a steel
    that transforms, the stress solver's fields when the stress is solved."""
    nv = run.section.mesh.p.shape[1]
    state = run.thermal.phase_state
    data = {"temperature_C": run.thermal.T[:nv].copy()}
    if run.kin is not None:  # a non-transforming material has no phases or hardness to show
        for phase, X in run.thermal.fractions().items():
            data[phase] = run.projection(X)
        if isinstance(state, metallurgy.TemperState):   # during and after a temper: its clock and tempered hardness
            assert run.tempering is not None   # a temper state comes with the tempering data (QuenchModel)
            data["tempering_parameter_K"] = run.projection(state.P)
            hv = metallurgy.tempering.tempered_hardness_HV(run.tempering, run.kin, state)
        else:
            hv = metallurgy.hardness_HV(state, run.kin)
        data["hardness_HV"] = run.projection(hv)
        data["hardness_HRC"] = metallurgy.hv_to_hrc(data["hardness_HV"])
    if run.mech is not None:
        data.update(run.mech.nodal_fields())
    return data


def final_frame(run: RunState) -> Any:
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
    bath = case.bath
    if bath is not None:
        out.update(quenchant=case.get("quench.bath.quenchant"), liquid_properties=bath.liquid.name,
                   oil_temperature_C=bath.oil_temperature_C, agitation=bath.agitation,
                   agitation_m_s=bath.agitation_m_s, support=bath.support,
                   support_open_fraction=bath.turntable_open_fraction)
    return out


def mechanics_summary(run: RunState, final: FinalSection, prefix: str = "") -> dict[str, Any]:
    """Dimensions before/after and their distortion budget, residual stresses at mid-width, traverse and
    outline files (named with ``prefix``) (``run``: a :class:`quenchsim.pipeline.QuenchRun` with the stress
    solved, at the state summarised)."""
    mech, model = run.mech, run.mech_model
    assert mech is not None and model is not None   # called with the stress solved (state_summary)
    before = mechanics.ring_dimensions(run.before_mesh)
    after = mechanics.ring_dimensions(run.section.mesh, mech.displacement_m)
    r_mm, hoop, axial = residual_traverse(final, mech.nodal_fields())
    run.writer.residual_traverse(r_mm, hoop, axial, prefix)
    before_outline_mm = mechanics.section_outline(run.before_mesh) / MM
    run.writer.outline(before_outline_mm, final.outline_m / MM, prefix)
    budget = mechanics.distortion_budget(mech, run.before_mesh, run.thermal.T_qp, run.thermal.fractions(),
                                         model.annealed_free_strain)
    return {"dimensions_mm": mechanics.dimension_change(before, after),
            "shape_mm": shape_change(before_outline_mm, final.outline_m / MM),
            "distortion_budget_mm": budget,
            "residual_stress_MPa": residual_stress_summary(hoop, axial)}


def state_summary(run: RunState, prefix: str = "") -> dict[str, Any]:
    """The hardness and phases (a transforming steel), the dimensions, shape, budget and residual stresses (stress
    solved) of ``run``'s present state, writing its traverse and outline files named with ``prefix``."""
    fields = nodal_fields(run)
    final = run.final_part.section()
    out: dict[str, Any] = {}
    if run.kin is None:
        out["notes"] = ['the material does not transform (transformations = "none"): no phases, no hardness']
    else:
        out["hardness"], traverse = hardness_summary(run.profile, run.projection.p1, final, fields["hardness_HRC"])
        run.writer.hardness_traverse(traverse["bore"][0], traverse["bore"][1], traverse["od"][1], prefix)
        out["phases_final"] = phase_statistics(run.thermal.fractions(), run.fe.r_dx)
        if run.case.probes:   # the phases and hardness where the thermocouples sit (austenitised geometry)
            pts = np.array([[p.r_mm, p.z_mm] for p in run.case.probes]).T * MM * run.case_to_hot
            out["probe_state"] = probe_state(run.projection.p1, pts, [p.name for p in run.case.probes], fields,
                                             tuple(run.thermal.fractions()))
    if run.mech is not None:
        out.update(mechanics_summary(run, final, prefix))
    return out


def tempered_summary(run: RunState, as_quenched: dict[str, Any]) -> dict[str, Any]:
    """The ``tempered`` block of a run with a ``[temper]``: the temper, the state after it (the keys of the
    as-quenched state, :func:`state_summary`, files prefixed ``tempered_``), the change of each dimension and shape
    measure by the temper and the tempering part of the distortion budget (each part after minus as quenched; the
    relaxation strain a part of its own)."""
    temper, tempering = run.case.temper, run.tempering
    assert temper is not None and tempering is not None   # a tempered summary follows a temper (run_summary)
    state = state_summary(run, files.TEMPERED_PREFIX)
    if "probe_state" in state:   # the tempered phases and HRC at each probe
        state["probes"] = state.pop("probe_state")
    out: dict[str, Any] = {"temper": {"temperature_C": temper.temperature_C, "time_s": temper.time_s,
                                      "htc_model": temper.htc_model,
                                      "hollomon_jaffe_constant": tempering.clock_constant},
                           **state}
    P = run.thermal.phase_state.P
    out["tempering_parameter_K"] = {"min": float(P.min()), "max": float(P.max()),
                                    "mean": float(np.sum(P * run.fe.r_dx) / np.sum(run.fe.r_dx))}
    if "dimensions_mm" in state:
        out["change_by_temper_mm"] = {k: state["dimensions_mm"]["after"][k] - as_quenched["dimensions_mm"]["after"][k]
                                      for k in state["dimensions_mm"]["after"]}
        before_parts = as_quenched["distortion_budget_mm"]["parts"]
        out["tempering_budget_mm"] = {
            part: {k: v - before_parts.get(part, {}).get(k, 0.0) for k, v in values.items()}
            for part, values in state["distortion_budget_mm"]["parts"].items()}
    return out


def run_summary(run: RunState, time_s: np.ndarray, probe_T: dict[str, np.ndarray], wall0: float) -> dict[str, Any]:
    """The summary of the finished ``run`` (:class:`quenchsim.pipeline.QuenchRun`): probes, handling, hardness and
    phases (a transforming steel), dimensions, shape, budget and stresses (stress solved), energy and solver
    counts; writes the hardness, residual-stress and outline files on the way."""
    case = run.case
    out: dict[str, Any] = {"case": case.name, "condition": case.condition,
                           "quenchsim_version": __version__, "case_sha256": case.digest()}
    out["probes"] = probe_times(time_s, probe_T)
    out["quench"] = handling_summary(case)
    as_quenched = run.as_quenched
    state = dict(state_summary(run) if as_quenched is None else as_quenched)
    for name, entry in state.pop("probe_state", {}).items():   # the as-quenched phases and HRC at each probe
        out["probes"][name].update(entry)
    out.update(state)
    if as_quenched is not None:
        out["tempered"] = tempered_summary(run, as_quenched)
    if run.mech is not None:
        measured = compare_with_measured(out.get("dimensions_mm"), dict(case.data), case.condition)
        if measured is not None:
            out["measured"] = measured
    counts = run.counts
    out["energy"] = {"heat_extracted_J": counts.heat_out_J, "latent_released_J": counts.latent_J}
    out["solver"] = {"wall_time_s": time.perf_counter() - wall0, "stage_time_s": dict(run.timings),
                     "steps": counts.steps, "rejected_steps": counts.rejected,
                     "stress_steps": counts.stress_steps, "dofs": int(run.fe.n_dofs),
                     "elements": int(run.section.n_elements), "end_time_s": float(run.thermal.time_s)}
    return out


def summary_or_why_not(run: RunState, time_s: np.ndarray, probe_T: dict[str, np.ndarray]) -> dict[str, Any]:
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
