"""The multirate coupling of the stress solver to the thermal march.

The stress solver is rate-independent, so it takes one step over as many thermal steps as keep its change within
``time.mechanics_max_dT_K`` and ``time.mechanics_max_dX``; a thermal step alone beyond them is split into stress
steps along its own path (the temperatures linear in time, the phases as the kinetics form them on that path); the
run brings the stresses up to the committed thermal state at every VTK frame, stage end and at the end.
"""

from __future__ import annotations

import logging
import math
from collections.abc import Callable
from contextlib import AbstractContextManager
from typing import Any

import numpy as np

from quenchsim.errors import SolverError

log = logging.getLogger("quenchsim")
MAX_STRESS_STEPS_PER_THERMAL_STEP = 64
"""Bound on the stress steps that one thermal step beyond the ``time.mechanics_*`` limits is split into."""


class StressCoupling:
    """The stress solver ``solver`` (:class:`quenchsim.mechanics.MechanicsSolver`) following the thermal solver
    ``thermal`` and its ``phase_model`` within the limits ``max_dT_K`` and ``max_dX`` per stress step; ``timer(key)``
    times its work, ``count()`` counts each stress step. ``ref``: the (T_qp, fractions) of the last stress step."""

    def __init__(self, solver: Any, thermal: Any, phase_model: Any, max_dT_K: float, max_dX: float,
                 timer: Callable[[str], AbstractContextManager[Any]], count: Callable[[], None]) -> None:
        self.solver, self.thermal, self.phase_model = solver, thermal, phase_model
        self.max_dT_K, self.max_dX = max_dT_K, max_dX
        self.timer, self.count = timer, count
        self.ref: tuple[np.ndarray, dict[str, np.ndarray]] = (thermal.T_qp, thermal.fractions())

    def checkpoint_state(self) -> dict[str, Any]:
        """The solver's state and the last stress step's (T_qp, fractions), as checkpoint arrays."""
        return {"mechanics": self.solver.checkpoint_state(),
                "mechanics_ref": {"T_qp": self.ref[0], "fractions": self.ref[1]}}

    def restore_state(self, state: dict[str, Any]) -> None:
        self.solver.restore_state(state["mechanics"])
        ref = state["mechanics_ref"]
        self.ref = (np.array(ref["T_qp"]), {p: np.array(v) for p, v in ref["fractions"].items()})

    def step(self, T_qp: np.ndarray, fractions: dict[str, np.ndarray]) -> bool:
        """One stress step from the state of the last one (``self.ref``) to (T_qp, fractions)."""
        T_ref, X_ref = self.ref
        converged = bool(self.solver.step(T_qp, fractions, T_ref, X_ref).converged)
        if converged:
            self.ref = (T_qp, fractions)
            self.count()
        return converged

    def beyond_limits(self, T_qp: np.ndarray, fractions: dict[str, np.ndarray]) -> bool:
        """Whether the change from the last stress step to (T_qp, fractions) exceeds ``time.mechanics_max_dT_K``
        or ``time.mechanics_max_dX``."""
        return self.limit_ratio(T_qp, fractions) > 1.0

    def limit_ratio(self, T_qp: np.ndarray, fractions: dict[str, np.ndarray]) -> float:
        """The change from the last stress step to (T_qp, fractions) over the ``time.mechanics_*`` limits: the
        larger of the temperature change over ``mechanics_max_dT_K`` and any phase change over
        ``mechanics_max_dX`` (inf where a change meets a limit of 0)."""
        T_ref, X_ref = self.ref

        def ratio(change: float, limit: float) -> float:
            return change / limit if limit > 0.0 else (math.inf if change > 0.0 else 0.0)

        dX = max((float(np.max(np.abs(X - X_ref.get(p, 0.0)))) for p, X in fractions.items()), default=0.0)
        return max(ratio(float(np.max(np.abs(T_qp - T_ref))), self.max_dT_K),
                   ratio(dX, self.max_dX))

    def with_step(self, step: Any) -> bool:
        """The stress solver's part of a thermal step about to be committed (multirate: the stress solver is
        rate-independent, so it steps only when the change since its last step would exceed the time.mechanics_*
        limits). The thermal steps since its last step are first caught up to the committed state; then, when
        ``step`` alone exceeds the limits, it is taken in as many stress steps as keep each within them, along its
        own path. False when the first of them does not converge (nothing is committed and the caller cuts the
        thermal step, as when every step is a stress step); a later one that does not converge is halved
        (:meth:`to`)."""
        if not self.beyond_limits(step.T_qp, self.phase_model.fractions(step.phase_state)):
            return True
        self.catch_up()  # raises SolverError if even sub-steps fail (committed steps cannot be cut)
        T1, X1 = step.T_qp, self.phase_model.fractions(step.phase_state)
        ratio = self.limit_ratio(T1, X1)
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
                converged = self.step(T, X)
            if not converged:
                if k == 1:
                    return False  # nothing committed: the caller cuts the thermal step
                self.to(T1, X1, f"at t = {self.thermal.time_s + step.dt_s:.4g} s",
                                   share=1.0 / (parts - k + 1))
                return True
        return True

    def catch_up(self) -> None:
        """Bring the stress solver to the committed thermal state (its change since the last stress step spans
        committed thermal steps, which cannot be cut: :meth:`to` splits it if need be)."""
        self.to(self.thermal.T_qp, self.thermal.fractions(), f"catching up to t = {self.thermal.time_s:.4g} s")

    def to(self, T_end: np.ndarray, X_end: dict[str, np.ndarray], what: str, share: float = 1.0) -> None:
        """Stress steps from the last one's state to (T_end, X_end) along the straight path between the two states,
        each ``share`` of the change (one step by default); a step that does not converge is halved, down to 1/64
        of the first."""
        T_ref, X_ref = self.ref
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
                if self.step(T, X):
                    done = s
                    continue
                share /= 2.0
                if share < smallest:
                    raise SolverError(f"the stress solver did not converge {what} even in sub-steps of {smallest:.3g} "
                                      "of the change since its last step")
                log.warning("stress Newton did not converge %s; sub-steps of %g of the change", what, share)
