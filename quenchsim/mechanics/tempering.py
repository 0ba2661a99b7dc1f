"""The stress solver during a temper: one stress step per thermal step (the temperatures change slowly and the
tempering reactions and the relaxation are time dependent, so the multirate rule of a quench, rate independent, does
not apply), each with the tempering reactions' free-strain increment and the relaxation's viscous increment
(:meth:`quenchsim.mechanics.MechanicsSolver.step`)."""

from __future__ import annotations

from collections.abc import Callable
from contextlib import AbstractContextManager
from typing import Any

import numpy as np

from quenchsim.mechanics.coupling import StressCoupling


class TemperCoupling(StressCoupling):
    """:class:`StressCoupling` for a temper: ``free_strain_of(state)`` is the tempering free strain of a phase state
    of the thermal solver (from the start of the temper), ``relaxation_of(state)`` its relaxation term r (the
    deviatoric stress at a fixed strain falls as exp(-r))."""

    def __init__(self, solver: Any, thermal: Any, phase_model: Any, free_strain_of: Callable[[Any], np.ndarray],
                 relaxation_of: Callable[[Any], np.ndarray],
                 timer: Callable[[str], AbstractContextManager[Any]], count: Callable[[], None]) -> None:
        super().__init__(solver, thermal, phase_model, 0.0, 0.0, timer, count)
        self.free_strain_of, self.relaxation_of = free_strain_of, relaxation_of

    def with_step(self, step: Any) -> bool:
        """The stress step of the thermal step ``step`` about to be committed: False when Newton does not converge
        (nothing committed; the caller cuts the thermal step)."""
        state0, state1 = self.thermal.phase_state, step.phase_state
        X0, X1 = self.phase_model.fractions(state0), self.phase_model.fractions(state1)
        with self.timer("mechanics_s"):
            info = self.solver.step(step.T_qp, X1, self.thermal.T_qp, X0,
                                    extra_free_strain=self.free_strain_of(state1) - self.free_strain_of(state0),
                                    relaxation_increment=self.relaxation_of(state1) - self.relaxation_of(state0))
        if info.converged:
            self.ref = (step.T_qp, X1)
            self.count()
        return bool(info.converged)

    def catch_up(self) -> None:
        """Nothing to do: every committed thermal step of a temper took its stress step."""
