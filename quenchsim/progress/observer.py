"""The quench run as the progress bar sees it: at each stage's start and after each committed step the run hands
over its state (the run object, read only); the observer assembles the :class:`StepState`, asks the forecasts and
updates the bar. Nothing here reaches a result."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

from quenchsim import metallurgy
from quenchsim.metallurgy import Kinetics
from quenchsim.progress import CoolingProgress, RunProgress, StepState, film_collapse_temperatures
from quenchsim.run_state import RunState
from quenchsim.progress.forecasts import diffusional_fraction_to_come, martensite_limit_steps_to_come


class QuenchObserver:
    """The progress of one quench run on ``bar``: ``stage(...)`` when a stage starts, ``step(...)`` after each
    committed step (an update of the estimate when the bar is due, :meth:`RunProgress.due`; otherwise a record of the
    step's clock and of the vapour film, :meth:`RunProgress.record_step`, :meth:`CoolingProgress.record_film`)."""

    def __init__(self, run: RunState, bar: RunProgress) -> None:
        case, ctl = run.case, run.case.time
        self.run, self.bar = run, bar
        self.estimate = CoolingProgress(run.T_aust, case.air.until_max_C, case.air.temperature_C, ctl.dt_max_s,
                                        ctl.max_dT_K, ctl.max_dX, ctl.growth, ctl.mechanics_max_dT_K,
                                        ctl.mechanics_max_dX)
        self.limited_by_phase_change = False   # the phase-fraction limit held at a step since the last update

    def stage(self, stage: Any, later: list[Any], htc: Any, stage_htc: Callable[[str], Any], t_end: float) -> None:
        """A stage starts (or resumes) with boundary ``htc`` until ``t_end``; ``later``: the stages after it, whose
        boundaries ``stage_htc(name)`` gives."""
        self.stage_now, self.t_end = stage, t_end
        self.bath_C = float(np.mean(htc.ambient_C))
        self.later = [(st.duration_s, self._newton_rate_per_s(st, stage_htc(st.name))
                       if math.isfinite(st.until_max_C) else None) for st in later]
        self.collapse_C = self._film_collapse_C(htc, t_end)

    def step(self, dt_s: float, dX: float, max_dT_K: float, T_qp_before: np.ndarray) -> None:
        """A step of ``dt_s`` was committed (its largest diffusional change ``dX`` and nodal temperature change
        ``max_dT_K``; the temperatures before it ``T_qp_before``)."""
        run, ctl = self.run, self.run.case.time
        thermal, counts, kin = run.thermal, run.counts, run.kin
        self.limited_by_phase_change |= dX / ctl.max_dX > max_dT_K / ctl.max_dT_K
        stress_s, solve_s = run.timings.get("mechanics_s", 0.0), run.timings.get("thermal_metallurgy_s", 0.0)
        collapse_C, filmed = self.collapse_C, np.isfinite(self.collapse_C)
        T_surface_C = run.fe.at_facet_qp(thermal.T).reshape(-1)
        film_excess_K = float(np.max(T_surface_C - collapse_C))
        wetted = float(np.mean(T_surface_C[filmed] < collapse_C[filmed])) if filmed.any() else 0.0
        if not self.bar.due():
            self.bar.record_step(counts.steps, counts.stress_steps, stress_s, solve_s)
            self.estimate.record_film(thermal.time_s, counts.steps, film_excess_K, wetted)
            return
        fractions = thermal.fractions() if kin is not None else {}
        now = StepState(counts.steps, thermal.time_s, thermal.T, run.position.dt_s,
                        self.t_end - thermal.time_s, math.isfinite(self.stage_now.until_max_C), self.later,
                        float(np.mean(T_surface_C)), film_excess_K, wetted,
                        float(np.mean(fractions.get("austenite", 0.0))),
                        self.limited_by_phase_change,
                        0.0 if kin is None else metallurgy.incubation_share(thermal.phase_state, kin, thermal.T_qp),
                        float(np.mean(sum(fractions.get(r, 0.0) for r in kin.reactions))) if kin is not None else 0.0,
                        None if kin is None else self._diffusional_to_come(kin, T_qp_before, dt_s),
                        stage_ambient_C=self.bath_C,
                        martensite_fraction=float(np.mean(fractions.get("martensite", 0.0))),
                        martensite_limit_steps=None if kin is None else self._martensite_limit_steps(
                            kin, T_qp_before, dt_s, self.bath_C),
                        stress_steps_done=counts.stress_steps, clock_s=self.bar.clock())
        self.limited_by_phase_change = False
        steps_left = self.estimate.steps_left(now)
        self.bar.update(thermal.time_s, self.estimate.fraction(thermal.T), counts.steps, steps_left,
                        counts.stress_steps, self.estimate.stress_steps_left(now, steps_left),
                        stress_s, solve_s)

    def _diffusional_to_come(self, kin: Kinetics, T_qp_before: np.ndarray, dt_s: float) -> Callable[[], float]:
        """The forecast of the pearlite + bainite still to form, from each point's cooling rate over the step just
        taken (asked only when the estimate needs it)."""
        run = self.run
        state, T_qp = run.thermal.phase_state, run.thermal.T_qp
        return lambda: diffusional_fraction_to_come(state, kin, T_qp, (T_qp_before - T_qp) / dt_s,
                                                    run.case.air.temperature_C)

    def _martensite_limit_steps(self, kin: Kinetics, T_qp_before: np.ndarray, dt_s: float, bath_C: float
                                ) -> Callable[[], float]:
        """The forecast of the stress steps the martensite still needs (``time.mechanics_max_dX`` on it), from the
        section's cooling rate over the step just taken towards the stage's ambient ``bath_C``, then the air's
        (asked only when needed)."""
        run = self.run
        state, T_qp = run.thermal.phase_state, run.thermal.T_qp
        return lambda: martensite_limit_steps_to_come(state, kin, T_qp, (T_qp_before - T_qp) / dt_s,
                                                      bath_C, run.case.air.temperature_C,
                                                      run.case.time.mechanics_max_dX)

    def _newton_rate_per_s(self, stage: Any, htc: Any) -> float:
        """The rate ``h A / C`` at which the part would cool in ``stage`` as one lump (Newton's law: the stage's HTC
        ``htc`` at its end temperature integrated over the cooled surface, over the heat capacity of the part as it
        is now), for the estimate of a later stage's length."""
        thermal = self.run.thermal
        fe, props = thermal.fe, thermal.props
        T_surface = np.full(fe.facet_r_ds.shape, stage.until_max_C)
        hA = fe.integrate_boundary(htc(T_surface.reshape(-1), thermal.time_s).reshape(T_surface.shape))
        T_qp, X = thermal.T_qp, thermal.fractions()
        C = fe.integrate(props.density_kg_m3(T_qp, X) * props.specific_heat_J_kgK(T_qp, X))
        return hA / C

    def _film_collapse_C(self, htc: Any, time_s: float) -> np.ndarray:
        """Per cooled-surface quadrature point, the temperature above which ``htc`` (at ``time_s``) is in film
        boiling (:func:`film_collapse_temperatures`; +inf without a film)."""
        run = self.run
        n = run.fe.facet_r_ds.size
        T_grid_C = np.arange(run.T_room, run.T_aust + 10.0, 10.0)
        return film_collapse_temperatures(T_grid_C, np.array([htc(np.full(n, T), time_s) for T in T_grid_C]))
