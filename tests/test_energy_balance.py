"""Energy conservation of the thermal solver with latent heat: enthalpy change == heat extracted."""

import numpy as np
import skfem

from quenchsim.materials import ThermalProperties, parse_property
from quenchsim.thermal import AxisymmetricP2, TableHTC, ThermalSolver

RHO, L_J_KG = 7800.0, 8.0e4
CP_TABLE = {"T_C": [0.0, 400.0, 900.0], "value": [450.0, 600.0, 650.0]}


class LinearTransformation:
    """Test kinetics: product fraction X = clip((T_start - T)/(T_start - T_end), 0, 1), irreversible."""

    T_start, T_end = 600.0, 300.0

    def advance(self, state, T_old, T_new, dt):
        target = np.clip((self.T_start - T_new) / (self.T_start - self.T_end), 0.0, 1.0)
        return np.maximum(state, target)

    def fractions(self, state):
        return {"austenite": 1.0 - state, "pearlite": state}


def enthalpy_sensible(T: np.ndarray) -> np.ndarray:
    """int_0^T c_p dT for the piecewise-linear c_p table (exact)."""
    Tg = np.asarray(CP_TABLE["T_C"])
    cg = np.asarray(CP_TABLE["value"])
    out = np.zeros_like(T)
    for a, b, ca, cb in zip(Tg[:-1], Tg[1:], cg[:-1], cg[1:]):
        lo, hi = np.clip(T, a, b), b
        x = np.clip(T, a, b) - a
        out += ca * x + 0.5 * (cb - ca) / (b - a) * x * x
        del lo, hi
    return out


def test_enthalpy_change_equals_boundary_heat_including_latent_heat():
    mesh = skfem.MeshTri.init_tensor(np.linspace(0.05, 0.09, 9), np.linspace(0.0, 0.04, 9))
    fe = AxisymmetricP2(mesh, mesh.boundary_facets())
    props = ThermalProperties(parse_property(RHO, "rho"), parse_property(30.0, "k"),
                              parse_property(CP_TABLE, "cp"), {"pearlite": parse_property(L_J_KG, "L")})
    model = LinearTransformation()
    solver = ThermalSolver(fe, props, 850.0, model, np.zeros_like(fe.r_qp))
    htc = TableHTC(["temperature"], [np.array([0.0, 900.0])], [np.array([800.0, 2500.0])], [60.0],
                   np.zeros(fe.facet_r.size, dtype=int))
    heat_out, latent = 0.0, 0.0
    H0 = 2 * np.pi * fe.integrate(RHO * enthalpy_sensible(fe.at_qp(solver.T)))
    for _ in range(300):
        step = solver.try_step(0.25, htc)
        solver.commit(step)
        heat_out += step.heat_out_J
        latent += step.latent_J
    X = solver.phase_state
    H1 = 2 * np.pi * fe.integrate(RHO * enthalpy_sensible(fe.at_qp(solver.T)))
    latent_exact = 2 * np.pi * fe.integrate(RHO * L_J_KG * X)
    assert np.mean(X) > 0.5                                   # the transformation really happened
    assert abs(latent - latent_exact) / latent_exact < 1e-9   # source bookkeeping
    # total enthalpy H = sensible - latent (released heat leaves through the surface)
    assert abs((H0 - H1) + latent - heat_out) / heat_out < 0.01
