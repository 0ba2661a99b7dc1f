"""Closed-form conduction problems that verify the thermal solver (used by the tests and the report).

- long solid cylinder cooled by convection: series solution (Carslaw & Jaeger, Conduction of Heat in
  Solids, 2nd ed., sec. 7.7): theta/theta_0 = sum_n C_n exp(-z_n^2 Fo) J0(z_n r/R),
  z_n J1(z_n) = Bi J0(z_n), C_n = 2 J1(z_n) / (z_n (J0(z_n)^2 + J1(z_n)^2));
- long hollow cylinder with the same Robin condition on bore and OD: eigenfunction series
  (Ozisik, Heat Conduction, 2nd ed., ch. 3) with R_n = A J0(l r) + B Y0(l r);
- steady hollow cylinder between two surface temperatures: T = T_a + (T_b - T_a) ln(r/a) / ln(b/a).
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import skfem
from scipy.optimize import brentq
from scipy.special import j0, j1, y0, y1

from quenchsim.materials import ThermalProperties, parse_property
from quenchsim.thermal.assembly import AxisymmetricP2
from quenchsim.thermal.boundary import TableHTC
from quenchsim.thermal.solver import NoTransformation, ThermalSolver

K_W_MK, RHO_KG_M3, CP_J_KGK = 30.0, 7800.0, 500.0
ALPHA_M2_S = K_W_MK / (RHO_KG_M3 * CP_J_KGK)


def constant_properties() -> ThermalProperties:
    c = lambda v: parse_property(v, "verification")  # noqa: E731
    return ThermalProperties(c(RHO_KG_M3), c(K_W_MK), c(CP_J_KGK), {})


def _roots(f, upper: float, n: int, samples: int = 40000) -> list[float]:
    grid = np.linspace(1e-6, upper, samples)
    vals = f(grid)
    return [brentq(f, a, b) for a, b, fa, fb in zip(grid[:-1], grid[1:], vals[:-1], vals[1:]) if fa * fb < 0][:n]


def solid_cylinder_series(r: np.ndarray, R: float, Bi: float, Fo: float, terms: int = 40) -> np.ndarray:
    """theta / theta_0 in a long solid cylinder cooled by convection (Carslaw & Jaeger 7.7)."""
    f = lambda z: z * j1(z) - Bi * j0(z)  # noqa: E731
    out = np.zeros_like(np.asarray(r, dtype=float))
    for z in _roots(f, terms * np.pi + 3, terms):
        out += 2 * j1(z) / (z * (j0(z) ** 2 + j1(z) ** 2)) * np.exp(-z * z * Fo) * j0(z * np.asarray(r) / R)
    return out


def hollow_cylinder_series(r: np.ndarray, a: float, b: float, h: float, t: float, terms: int = 40) -> np.ndarray:
    """theta / theta_0 in a long hollow cylinder with h on both surfaces, uniform start."""

    def rows(lam):
        row_a = (-K_W_MK * lam * j1(lam * a) - h * j0(lam * a), -K_W_MK * lam * y1(lam * a) - h * y0(lam * a))
        row_b = (K_W_MK * lam * j1(lam * b) - h * j0(lam * b), K_W_MK * lam * y1(lam * b) - h * y0(lam * b))
        return row_a, row_b

    def det(lam):
        ra, rb = rows(lam)
        return ra[0] * rb[1] - ra[1] * rb[0]

    rr = np.linspace(a, b, 4001)
    series = np.zeros_like(rr)
    for lam in _roots(det, 4000.0, terms, 80000):
        ra, _ = rows(lam)
        Rn = ra[1] * j0(lam * rr) - ra[0] * y0(lam * rr)
        series += np.trapezoid(Rn * rr, rr) / np.trapezoid(Rn * Rn * rr, rr) * np.exp(-ALPHA_M2_S * lam * lam * t) * Rn
    return np.interp(r, rr, series)


def _facets_at(mesh: skfem.MeshTri, r: float) -> np.ndarray:
    return mesh.facets_satisfying(lambda x: np.isclose(x[0], r), boundaries_only=True)


def _march(mesh: skfem.MeshTri, facets: np.ndarray, h: float, dt: float, t_end: float,
           ambients: tuple[float, ...] = (50.0,),
           table_of_point: Callable[[AxisymmetricP2], np.ndarray] | None = None,
           T0: float = 800.0, order: int = 2) -> tuple[AxisymmetricP2, np.ndarray]:
    fe = AxisymmetricP2(mesh, facets)
    solver = ThermalSolver(fe, constant_properties(), T0, NoTransformation(), np.ones_like(fe.r_qp), order=order)
    which = np.zeros(fe.facet_r.size, dtype=int) if table_of_point is None else table_of_point(fe)
    htc = TableHTC(["temperature"] * len(ambients), [np.array([0.0])] * len(ambients),
                   [np.array([h])] * len(ambients), list(ambients), which)
    for _ in range(int(round(t_end / dt))):
        solver.commit(solver.try_step(dt, htc))
    return fe, solver.T


def solid_cylinder_error(n_radial: int, dt_s: float, t_end_s: float = 60.0, R: float = 0.05,
                         h: float = 1500.0, order: int = 2) -> float:
    """Max error at r = 0, R/2, R after t_end, as a fraction of the initial temperature drop (750 K), marched
    by BDF ``order`` (1: backward Euler)."""
    mesh = skfem.MeshTri.init_tensor(np.linspace(0.0, R, n_radial + 1), np.linspace(0.0, 0.01, 2))
    fe, T = _march(mesh, _facets_at(mesh, R), h, dt_s, t_end_s, order=order)
    r = np.array([0.0, 0.5 * R, R])
    numeric = fe.basis.probes(np.vstack([r, np.full(3, 0.005)])) @ T
    exact = 50.0 + 750.0 * solid_cylinder_series(r, R, h * R / K_W_MK, ALPHA_M2_S * t_end_s / R**2)
    return float(np.max(np.abs(numeric - exact)) / 750.0)


def hollow_cylinder_error(n_radial: int = 24, dt_s: float = 0.25, t_end_s: float = 40.0,
                          a: float = 0.02, b: float = 0.05, h: float = 800.0) -> float:
    """Max error at the bore, mid-wall and OD, as a fraction of the initial drop."""
    mesh = skfem.MeshTri.init_tensor(np.linspace(a, b, n_radial + 1), np.linspace(0.0, 0.005, 2))
    facets = np.concatenate([_facets_at(mesh, a), _facets_at(mesh, b)])
    fe, T = _march(mesh, facets, h, dt_s, t_end_s)
    r = np.array([a, 0.5 * (a + b), b])
    numeric = fe.basis.probes(np.vstack([r, np.full(3, 0.0025)])) @ T
    exact = 50.0 + 750.0 * hollow_cylinder_series(r, a, b, h, t_end_s)
    return float(np.max(np.abs(numeric - exact)) / 750.0)


def log_profile_error(n_radial: int, a: float = 0.1, b: float = 0.15) -> float:
    """Max error (K) of the steady profile between 500 C (bore) and 100 C (OD), through h = 1e9."""
    mesh = skfem.MeshTri.init_tensor(np.linspace(a, b, n_radial + 1), np.linspace(0.0, 0.01, 2))
    facets = np.concatenate([_facets_at(mesh, a), _facets_at(mesh, b)])
    fe, T = _march(mesh, facets, 1e9, 1e9, 1e9, ambients=(500.0, 100.0), T0=300.0,
                   table_of_point=lambda fe: np.where(np.isclose(fe.facet_r.reshape(-1), a), 0, 1))
    r = np.linspace(a, b, 7)
    numeric = fe.basis.probes(np.vstack([r, np.full_like(r, 0.005)])) @ T
    exact = 500.0 + (100.0 - 500.0) * np.log(r / a) / np.log(b / a)
    return float(np.max(np.abs(numeric - exact)))
