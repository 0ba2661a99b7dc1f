"""Crank-Nicolson time stepping of the film (reference section 1: "Crank-Nicolson on the flux balance").

Lambda d(P H)/dT + div q = 0 integrated over each control volume between T_n and T_n+1:

    Lambda (V_p^{n+1} P_p^{n+1} - V_p^n P_p^n) / dT + (Flux_p^{n+1} + Flux_p^n) / 2 = 0

(V_p: film volume of the control volume, Flux_p: outflow), solved for P^{n+1} as
L(P) = Flux(P; H^{n+1}) + (2 Lambda / dT) V^{n+1} P = (2 Lambda / dT) V^n P^n - Flux^n.
For a grooved rotor the grid is fixed to the rotor (mirrored, see film.FilmFrame) and the sleeve
angle of a grid point advances by 2 dT (the rotor turns omega t = 2 T).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from quenchsim.bearings.gas_journal.film import FilmFrame
from quenchsim.bearings.gas_journal.geometry import Bearing, Grid
from quenchsim.bearings.gas_journal.reynolds import film_volume, operator_hierarchy, solve
from quenchsim.errors import SolverError


def film_frame(bearing: Bearing, time: float) -> FilmFrame:
    """Grid frame at dimensionless time T: the sleeve, or the (mirrored) grooved rotor turned by 2T."""
    if bearing.grooved_rotor:
        return FilmFrame(sign=-1.0, offset=2.0 * time)
    return FilmFrame()


@dataclass
class FilmState:
    """Pressure field at time T with the rotor displacement it was computed for (the Crank-Nicolson
    terms of the old level, (V^n P^n, Flux^n), are cached on first use)."""

    time: float
    displacement: tuple[float, float]
    p: np.ndarray
    _old_terms: tuple[np.ndarray, np.ndarray] | None = None


class CrankNicolsonFilm:
    """Advances the film pressure of ``bearing`` on ``grid`` between two rotor positions."""

    def __init__(self, bearing: Bearing, grid: Grid, bearing_number: float, method: str = "multigrid") -> None:
        self.bearing = bearing
        self.grid = grid
        self.lam = float(bearing_number)
        self.method = method

    def _old_terms(self, state: FilmState) -> tuple[np.ndarray, np.ndarray]:
        if state._old_terms is None:
            frame = film_frame(self.bearing, state.time)
            old = operator_hierarchy(self.bearing, self.grid, self.lam, state.displacement, frame)[0]
            old.update_weights(state.p)
            volume = film_volume(self.bearing, self.grid, state.displacement, frame)
            state._old_terms = (volume * state.p, old.apply(state.p))
        return state._old_terms

    def step(self, state: FilmState, time: float, displacement: tuple[float, float]) -> FilmState:
        """P at ``time`` with the rotor at ``displacement`` (film linear in time across the step)."""
        dt = time - state.time
        if dt <= 0.0:
            return state
        factor = 2.0 * self.lam / dt
        mass_p, outflow = self._old_terms(state)
        ops = operator_hierarchy(self.bearing, self.grid, self.lam, displacement,
                                 film_frame(self.bearing, time), factor)
        rhs = factor * mass_p - outflow
        rhs[0, :] = 0.0
        result = solve(ops, self.method, p0=state.p, f=rhs)
        if not result.converged:
            raise SolverError(f"Crank-Nicolson film step to T = {time:.6g} did not converge "
                              f"(||R||_2 = {result.residual:.3g})")
        return FilmState(time, displacement, result.p)
