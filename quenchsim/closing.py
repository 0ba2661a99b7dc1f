"""The end of a run: the closing step to room temperature, or the hot state as it is.

A run whose air stage cooled the part to within ``air.until_max_C`` closes with one step to room temperature
(:func:`close_at_room_temperature`); a stage that ended early, a failed or an interrupted run reports the state
where it stopped, with its stresses brought up to the last thermal state where the stress solver allows.
"""

from __future__ import annotations

import logging
from typing import Any

import numpy as np
from quenchsim.errors import SolverError
from quenchsim.run_state import RunState

log = logging.getLogger("quenchsim")

STILL_HOT_NOTE = ("the part is still hot: temperatures, phases, hardness, dimensions and stresses are those at the "
                  "end of the last stage, not of the cooled part")


def end_state(run: RunState, closing_step: bool = True) -> dict[str, Any]:
    """Close ``run`` (a :class:`quenchsim.pipeline.QuenchRun`) at room temperature when the part has cooled to
    within ``air.until_max_C`` and ``closing_step``; otherwise report the hot state as it is. Returns the
    summary's ``end_state`` (temperatures in C, time in s)."""
    T_max, T_min = float(np.max(run.thermal.T)), float(np.min(run.thermal.T))
    temper = run.case.temper
    until_max_C = run.case.air.until_max_C if temper is None or temper.cool_until_max_C is None \
        else temper.cool_until_max_C
    if closing_step and T_max <= until_max_C + 1e-9:
        close_at_room_temperature(run)
        return {"at_room_temperature": True, "time_s": float(run.thermal.time_s),
                "max_temperature_before_closing_C": T_max}
    try:   # the stresses of the last thermal state (a failed or interrupted run; the checkpoint is written)
        run.catch_up_stresses()
    except SolverError as exc:
        log.error("stresses and dimensions are those at the last stress step before t = %.4g s: %s",
                  run.thermal.time_s, exc)
    if closing_step:
        log.warning("the last stage ended at t = %.4g s with the part at up to %.0f C (its until_max_C = %g C): %s",
                    run.thermal.time_s, T_max, until_max_C, STILL_HOT_NOTE)
    return {"at_room_temperature": False, "time_s": float(run.thermal.time_s), "max_temperature_C": T_max,
            "min_temperature_C": T_min, "note": STILL_HOT_NOTE}


def close_at_room_temperature(run: RunState) -> None:
    """The final state: the whole ring at room temperature, reached in one step with the martensite that the
    last few kelvin still form.

    The step takes no time for the diffusional reactions (dt = 0): its length is not modelled, and an assumed
    hour at 20-40 C had let the peer's bainite law, extrapolated far below its 240-440 C data, form 0.02 bainite
    out of retained austenite after the quench had ended."""
    thermal = run.thermal
    T_room = np.full(thermal.T.shape, run.T_room)
    T_qp = run.fe.at_qp(T_room)
    state = run.phase_model.advance(thermal.phase_state, thermal.T_qp, T_qp, 0.0)
    if run.stress is not None:
        run.stress.to(T_qp, run.phase_model.fractions(state), "in the final step to room temperature")
    thermal.T, thermal.T_qp, thermal.phase_state = T_room, T_qp, state
