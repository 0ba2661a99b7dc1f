"""Transient axisymmetric heat conduction with latent heat and a Robin boundary (implicit BDF2).

    rho c_p dT/dt = (1/r) d/dr(r k dT/dr) + d/dz(k dT/dz) + rho sum_i L_i dX_i/dt      in the section
    -k dT/dn = h(T_s, t) (T_s - T_inf)                                                    on the surface

Variable-step BDF2 in time (backward Euler on the first step and after :meth:`ThermalSolver.restart`; ``order=1``
keeps backward Euler throughout), on the sensible heat rho c_p T and the latent heat rho L X alike; within a step
the temperature, the phase fractions (hence k, rho c_p and the latent-heat source) and h(T_s) are iterated to
convergence -- Picard on the coefficients, Newton on the latent-heat source (its temperature derivative enters as
an apparent heat capacity) -- so the step is fully implicit. With backward Euler the discrete energy balance holds
step by step (the sensible-heat change minus the latent heat released equals the heat extracted through the
boundary); BDF2 holds it to its truncation error. Measured on ring A condition 1 (full chain, 2026-11-26): BDF2 at
30 K / 0.02 per step (426 steps) is as close to the step-converged results as backward Euler at 20 K / 0.002 (1127
steps); backward Euler at 20 K / 0.02 (586 steps) was 0.45 mm off in HRC58 depth, BDF2 0.007 mm.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol, cast

import numpy as np

from quenchsim.errors import SolverError
from quenchsim.materials import ThermalProperties
from quenchsim.thermal.assembly import AxisymmetricP2
from quenchsim.thermal.linear import StepLinearSolver


NEWTON_RANGE_MARGIN_K = 20.0
"""Margin beyond the range of the old temperatures and the ambients within which an iterate taken with the
exact (possibly negative) boiling-curve flux derivative is accepted; outside it the iteration is redone
with the damped derivative. Latent heat can lift a point above its own old temperature, but on case A
never by more than a few kelvin above the hottest old temperature."""


class PhaseModel(Protocol):
    """What the thermal solver needs from the metallurgy: pure updates of a material-point state."""

    def advance(self, state: Any, T_old_C: np.ndarray, T_new_C: np.ndarray, dt_s: float) -> Any: ...

    def fractions(self, state: Any) -> dict[str, np.ndarray]: ...


class HTC(Protocol):
    ambient_C: np.ndarray

    def __call__(self, T_surface_C: np.ndarray, time_s: float) -> np.ndarray: ...


class NoTransformation:
    """A phase model in which nothing transforms (pure conduction; verification cases)."""

    def __init__(self, phase: str = "austenite") -> None:
        self.phase = phase

    def advance(self, state: Any, T_old_C: np.ndarray, T_new_C: np.ndarray, dt_s: float) -> Any:
        return state

    def fractions(self, state: Any) -> dict[str, np.ndarray]:
        return {self.phase: state}


@dataclass
class ThermalStep:
    """An uncommitted step: the new temperature and phase state and what it took."""

    T: np.ndarray
    phase_state: Any
    T_qp: np.ndarray
    dt_s: float
    iterations: int
    max_dT_K: float
    max_dX_by_phase: dict[str, float]   # largest change of each phase fraction over the step
    heat_out_J: float          # heat extracted through the surface during the step (full 2 pi revolution)
    latent_J: float            # latent heat released during the step


@dataclass(frozen=True)
class _LastStep:
    """What BDF2 keeps of the last committed step: its length and its changes at the quadrature points."""

    dt_s: float
    dT_qp: np.ndarray
    dX: dict[str, np.ndarray]


class ThermalSolver:
    """Marches T (P2 nodal values) and the phase state at the quadrature points."""

    def __init__(self, fe: AxisymmetricP2, props: ThermalProperties, T_initial_C: float,
                 phase_model: PhaseModel, phase_state: Any, *, picard_tol_K: float = 0.02,
                 max_iterations: int = 30, latent_probe_K: float = 0.5, htc_probe_K: float = 0.5,
                 order: int = 2) -> None:
        self.fe = fe
        self.props = props
        self.phase_model = phase_model
        self.phase_state = phase_state
        self.T = np.full(fe.n_dofs, float(T_initial_C))
        self.T_qp = fe.at_qp(self.T)
        self.time_s = 0.0
        self._rate_K_s: np.ndarray | None = None
        self.picard_tol_K = picard_tol_K
        self.max_iterations = max_iterations
        self.latent_probe_K = latent_probe_K
        self.htc_probe_K = htc_probe_K
        self.linear = StepLinearSolver()
        if order not in (1, 2):
            raise ValueError(f"order = {order}: the time integrator is BDF1 (backward Euler) or BDF2")
        self.order = order
        self._last: _LastStep | None = None

    def restart(self) -> None:
        """Forget the last step: the next one is a backward-Euler step (at a stage start, where the boundary
        condition jumps and the last step's change says nothing of the next)."""
        self._last = None

    def _bdf_weights(self, dt_s: float) -> tuple[float, float]:
        """(a0, a2) of the variable-step BDF2 derivative (a0 (y1 - y0) - a2 (y0 - y_-1)) / dt with
        w = dt / dt_last: a0 = (1 + 2w) / (1 + w), a2 = w^2 / (1 + w) (Hairer, Norsett & Wanner, Solving ODEs I,
        sec. III.5); (1, 0), backward Euler, on the first step, after :meth:`restart` and for w > 2 (BDF2 is
        zero-stable for w < 1 + sqrt(2))."""
        if self.order == 1 or self._last is None:
            return 1.0, 0.0
        w = dt_s / self._last.dt_s
        if w > 2.0:
            return 1.0, 0.0
        return (1.0 + 2.0 * w) / (1.0 + w), w * w / (1.0 + w)

    def _fractions(self, state: Any) -> dict[str, np.ndarray]:
        return self.phase_model.fractions(state)

    def try_step(self, dt_s: float, htc: HTC) -> ThermalStep:
        """Solve one implicit step of length ``dt_s`` without committing it; raises SolverError if the
        Picard iteration does not converge (the caller cuts the step)."""
        fe, props = self.fe, self.props
        X0 = self._fractions(self.phase_state)
        # initial iterate: the last step's rate continued (measured on case A: 37 % fewer CG iterations and
        # 19 % less thermal CPU than starting from T_old; the converged step is the same within the tolerance)
        T_iter = self.T.copy() if self._rate_K_s is None else self.T + self._rate_K_s * dt_s
        T_old_qp = fe.at_qp(self.T)
        # BDF2 as a backward-Euler step of dt / a0 from the old state moved by the last step's change:
        # rho c_p (T1 - T_hist) / (dt / a0) = div k grad T1 + (Q1 - Q_hist) / (dt / a0), with
        # T_hist = T0 + (a2 / a0) (T0 - T_-1) and Q_hist = (a2 / a0) rho L (X0 - X_-1)
        a0, a2 = self._bdf_weights(dt_s)
        dt_eff = dt_s / a0
        # a2 > 0 only after a last step (_bdf_weights)
        if a2 > 0.0:
            T_hist_qp = T_old_qp + (a2 / a0) * cast(_LastStep, self._last).dT_qp
        else:
            T_hist_qp = T_old_qp
        ambient = htc.ambient_C.reshape(fe.facet_r.shape)
        t_new = self.time_s + dt_s
        change, damped = np.inf, False
        # an iterate outside [min(T_old, T_inf), max(T_old, T_inf)] by more than NEWTON_RANGE_MARGIN_K is not
        # physical (no heat source beyond the latent heat): it comes from the exact, negative flux derivative
        T_floor = min(float(self.T.min()), float(ambient.min())) - NEWTON_RANGE_MARGIN_K
        T_ceiling = max(float(self.T.max()), float(ambient.max())) + NEWTON_RANGE_MARGIN_K
        for it in range(1, self.max_iterations + 1):
            T_qp = fe.at_qp(T_iter)
            state = self.phase_model.advance(self.phase_state, self.T_qp, T_qp, dt_s)
            X = self._fractions(state)
            rho = props.density_kg_m3(T_qp, X)
            rho_cp = rho * props.specific_heat_J_kgK(T_qp, X)
            k = props.conductivity_W_mK(T_qp, X)
            latent = self._latent_J_m3(T_qp, X, X0, rho)
            # Newton on the latent-heat source: Q(T) ~ Q(T_k) + dQ/dT (T - T_k), dQ/dT <= 0 acts as an
            # apparent heat capacity (a plain fixed point diverges when L dX/dT exceeds c_p, e.g. martensite)
            # (the derivative costs a second kinetics evaluation: it is refreshed on the first and every
            # third iteration only -- a frozen-Jacobian Newton, which converges to the same solution)
            if it % 3 == 1:
                T_lo = T_qp - self.latent_probe_K
                X_lo = self._fractions(self.phase_model.advance(self.phase_state, self.T_qp, T_lo, dt_s))
                dQ_dT = np.minimum((latent - self._latent_J_m3(T_lo, X_lo, X0, rho)) / self.latent_probe_K, 0.0)
            Ts, q, dq_dT = self._surface_flux(T_iter, htc, t_new, ambient, damped)
            A = fe.system((rho_cp - dQ_dT) / dt_eff, k, dq_dT)
            # C T_old with C = int rho_cp/dt phi_i phi_j r dA is the load of rho_cp/dt T_old (same quadrature)
            latent_hist: np.ndarray | float
            if a2 > 0.0:
                latent_hist = (a2 / a0) * self._latent_J_m3(T_qp, cast(_LastStep, self._last).dX, {}, rho)
            else:
                latent_hist = 0.0
            b = (fe.load((rho_cp * T_hist_qp + latent - latent_hist - dQ_dT * T_qp) / dt_eff)
                 + fe.robin_load(dq_dT * Ts - q))
            T_next = self.linear.solve(A, b, T_iter)
            if not np.all(np.isfinite(T_next)):
                raise SolverError(f"thermal step of {dt_s:g} s at t = {self.time_s:g} s produced non-finite temperatures")
            if not damped and (T_next.min() < T_floor or T_next.max() > T_ceiling):
                damped = True  # the exact-derivative iterate left the physical range: redo it damped
                continue
            change, last_change = float(np.max(np.abs(T_next - T_iter))), change
            step_change = float(np.max(np.abs(T_next - self.T)))
            if not damped and change > last_change:
                damped = True  # the exact-derivative iteration diverges: go on damped from the last iterate
                continue
            T_iter = T_next
            # converged when the last correction is below the tolerance or 0.5 % of the step's change
            if change < max(self.picard_tol_K, 5e-3 * step_change):
                break
        else:
            raise SolverError(f"thermal Picard iteration did not converge in {self.max_iterations} iterations "
                              f"(dt = {dt_s:g} s at t = {self.time_s:g} s; last change {change:.3g} K)")
        return self._converged(T_iter, X0, htc, t_new, ambient, dt_s, it)

    def _surface_flux(self, T_iter: np.ndarray, htc: HTC, t_new: float, ambient: np.ndarray, damped: bool
                      ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The surface temperatures of ``T_iter``, the flux q = h(T_s)(T_s - T_inf) out and its derivative for
        Newton: dq/dT = h + h'(T_s)(T_s - T_inf), negative where boiling makes q fall with T_s.

        Exact at first (measured on case A, t = 1-40 s: 3-4 iterations instead of 6-12 with the floor, the iterate
        2x closer to the converged step); once a correction grows instead of shrinking or an iterate leaves the
        physical range, that iterate is dropped and the flux derivative kept >= 0.1 h for the rest of the step
        (``damped``: a damped, positive Jacobian). The residual, hence the solution, is the same."""
        Ts = self.fe.at_facet_qp(T_iter)
        h = htc(Ts.reshape(-1), t_new).reshape(Ts.shape)
        dh = (htc(Ts.reshape(-1) + self.htc_probe_K, t_new).reshape(Ts.shape) - h) / self.htc_probe_K
        dq_dT = h + dh * (Ts - ambient)
        if damped:
            dq_dT = np.maximum(dq_dT, 0.1 * h)
        q = h * (Ts - ambient)
        return Ts, q, dq_dT

    def _converged(self, T_iter: np.ndarray, X0: dict[str, np.ndarray], htc: HTC, t_new: float,
                   ambient: np.ndarray, dt_s: float, iterations: int) -> ThermalStep:
        """The step to the converged temperatures ``T_iter``: the final phase state consistent with them; the
        latent heat reported is the one of this state (the solve used the previous iterate's, within the Picard
        tolerance)."""
        fe, props = self.fe, self.props
        T_qp = fe.at_qp(T_iter)
        state = self.phase_model.advance(self.phase_state, self.T_qp, T_qp, dt_s)
        X = self._fractions(state)
        latent = self._latent_J_m3(T_qp, X, X0, props.density_kg_m3(T_qp, X))
        Ts = fe.at_facet_qp(T_iter)
        h = htc(Ts.reshape(-1), t_new).reshape(Ts.shape)
        two_pi = 2.0 * np.pi
        heat_out = two_pi * dt_s * fe.integrate_boundary(h * (Ts - ambient))
        latent_J = two_pi * fe.integrate(latent)
        max_dX_by_phase = {p: float(np.max(np.abs(X[p] - X0.get(p, 0.0)))) for p in X}
        return ThermalStep(T=T_iter, phase_state=state, T_qp=T_qp, dt_s=dt_s, iterations=iterations,
                           max_dT_K=float(np.max(np.abs(T_iter - self.T))), max_dX_by_phase=max_dX_by_phase,
                           heat_out_J=heat_out, latent_J=latent_J)

    def _latent_J_m3(self, T_qp: np.ndarray, X: dict[str, np.ndarray], X0: dict[str, np.ndarray],
                     rho: np.ndarray) -> np.ndarray:
        """Heat released per volume over the step: rho sum_i L_i(T) (X_i - X_i,0)."""
        latent = np.zeros_like(T_qp)
        for phase, L in self.props.latent_heat_J_kg.items():
            if phase in X:
                latent += L(T_qp) * (X[phase] - X0.get(phase, 0.0))
        return rho * latent

    def commit(self, step: ThermalStep) -> None:
        X0 = self._fractions(self.phase_state)
        X1 = self._fractions(step.phase_state)
        self._last = _LastStep(step.dt_s, step.T_qp - self.fe.at_qp(self.T), {p: X1[p] - X0.get(p, 0.0) for p in X1})
        self._rate_K_s = (step.T - self.T) / step.dt_s
        self.T = step.T
        self.T_qp = step.T_qp
        self.phase_state = step.phase_state
        self.time_s += step.dt_s

    def fractions(self) -> dict[str, np.ndarray]:
        return self._fractions(self.phase_state)

    def checkpoint_state(self) -> dict[str, Any]:
        """The committed temperatures, time, last rate (the next step's first iterate) and linear-solver state;
        the phase state is the phase model's (``phase_state``)."""
        last = None if self._last is None else {"dt_s": self._last.dt_s, "dT_qp": self._last.dT_qp, "dX": self._last.dX}
        return {"T": self.T, "T_qp": self.T_qp, "time_s": self.time_s, "rate_K_s": self._rate_K_s,
                "linear": self.linear.checkpoint_state(), "last_step": last}

    def restore_state(self, state: dict[str, Any], phase_state: Any) -> None:
        """Continue from :meth:`checkpoint_state` and a phase state."""
        self.T, self.T_qp, self.time_s = np.array(state["T"]), np.array(state["T_qp"]), float(state["time_s"])
        self._rate_K_s = None if state.get("rate_K_s") is None else np.array(state["rate_K_s"])
        self.linear.restore_state(state["linear"])
        last = state.get("last_step")
        self._last = None if last is None else _LastStep(float(last["dt_s"]), np.array(last["dT_qp"]),
                                                         {p: np.array(v) for p, v in last.get("dX", {}).items()})
        self.phase_state = phase_state
