"""Verification of the thermal solver against closed-form conduction solutions."""

import numpy as np
import pytest
import skfem
from scipy.optimize import brentq
from scipy.special import j0, j1, y0, y1

from quenchsim.materials import ThermalProperties, parse_property
from quenchsim.thermal import AxisymmetricP2, NoTransformation, TableHTC, ThermalSolver

K, RHO, CP = 30.0, 7800.0, 500.0
ALPHA = K / (RHO * CP)


def constant_props(latent: dict | None = None) -> ThermalProperties:
    c = lambda v: parse_property(v, "test")  # noqa: E731
    return ThermalProperties(c(RHO), c(K), c(CP), {p: c(v) for p, v in (latent or {}).items()})


def tensor_mesh(r0: float, r1: float, h: float, nr: int, nz: int) -> skfem.MeshTri:
    return skfem.MeshTri.init_tensor(np.linspace(r0, r1, nr + 1), np.linspace(0.0, h, nz + 1))


def facets_at(mesh: skfem.MeshTri, r: float) -> np.ndarray:
    return mesh.facets_satisfying(lambda x: np.isclose(x[0], r), boundaries_only=True)


def constant_htc(n_points: int, h: float, ambient: float) -> TableHTC:
    return TableHTC(["temperature"], [np.array([0.0])], [np.array([h])], [ambient], np.zeros(n_points, dtype=int))


def cylinder_series(r: np.ndarray, R: float, Bi: float, Fo: float, terms: int = 40) -> np.ndarray:
    """theta/theta_0 in a long solid cylinder cooled by convection (Carslaw & Jaeger, sec. 7.7):
    sum_n C_n exp(-z_n^2 Fo) J0(z_n r/R), z_n J1(z_n) = Bi J0(z_n), C_n = 2 J1(z_n) / (z_n (J0^2 + J1^2))."""
    f = lambda z: z * j1(z) - Bi * j0(z)  # noqa: E731
    grid = np.linspace(1e-6, terms * np.pi + 3, 20000)
    vals = f(grid)
    roots = [brentq(f, a, b) for a, b, fa, fb in zip(grid[:-1], grid[1:], vals[:-1], vals[1:]) if fa * fb < 0]
    roots = [z for z in roots if abs(j0(z)) > 1e-12][:terms]
    out = np.zeros_like(r)
    for z in roots:
        C = 2 * j1(z) / (z * (j0(z) ** 2 + j1(z) ** 2))
        out += C * np.exp(-z * z * Fo) * j0(z * r / R)
    return out


def run_cylinder(nr: int, dt: float, t_end: float, R: float = 0.05, h: float = 1500.0) -> tuple[float, float]:
    mesh = tensor_mesh(0.0, R, 0.01, nr, 1)
    fe = AxisymmetricP2(mesh, facets_at(mesh, R))
    solver = ThermalSolver(fe, constant_props(), 800.0, NoTransformation(), np.ones_like(fe.r_qp))
    htc = constant_htc(fe.facet_r.size, h, 50.0)
    n = int(round(t_end / dt))
    for _ in range(n):
        solver.commit(solver.try_step(dt, htc))
    probe = fe.basis.probes(np.array([[0.0, 0.5 * R, R], [0.005, 0.005, 0.005]]))
    numeric = probe @ solver.T
    exact = 50.0 + 750.0 * cylinder_series(np.array([0.0, 0.5 * R, R]), R, h * R / K, ALPHA * t_end / R**2)
    return float(np.max(np.abs(numeric - exact)) / 750.0), numeric


def test_solid_cylinder_robin_matches_series_solution_within_half_percent():
    err, _ = run_cylinder(nr=24, dt=0.5, t_end=60.0)
    assert err < 0.005


def test_solid_cylinder_time_step_convergence_is_first_order():
    e1, _ = run_cylinder(nr=24, dt=2.0, t_end=60.0)
    e2, _ = run_cylinder(nr=24, dt=1.0, t_end=60.0)
    assert 1.6 < e1 / e2 < 2.4  # backward Euler


def test_hollow_cylinder_transient_robin_on_bore_and_od_matches_eigenfunction_series():
    """Hollow cylinder a < r < b, the same Robin condition on bore and OD, uniform start (Ozisik,
    Heat Conduction, ch. 3): theta = sum_n c_n exp(-alpha l_n^2 t) R_n(r), R_n = A J0(l r) + B Y0(l r)
    with k R' = h R at r = a and -k R' = h R at r = b."""
    a, b, h = 0.02, 0.05, 800.0

    def rows(lam):
        row_a = [-K * lam * j1(lam * a) - h * j0(lam * a), -K * lam * y1(lam * a) - h * y0(lam * a)]
        row_b = [K * lam * j1(lam * b) - h * j0(lam * b), K * lam * y1(lam * b) - h * y0(lam * b)]
        return row_a, row_b

    def det(lam):
        ra, rb = rows(lam)
        return ra[0] * rb[1] - ra[1] * rb[0]

    grid = np.linspace(1.0, 4000.0, 80000)
    vals = det(grid)
    lams = [brentq(det, x0, x1) for x0, x1, v0, v1 in zip(grid[:-1], grid[1:], vals[:-1], vals[1:]) if v0 * v1 < 0][:40]
    r = np.linspace(a, b, 4001)
    series = np.zeros_like(r)
    t_end = 40.0
    for lam in lams:
        ra, _ = rows(lam)
        Rn = ra[1] * j0(lam * r) - ra[0] * y0(lam * r)
        coef = np.trapezoid(Rn * r, r) / np.trapezoid(Rn * Rn * r, r)
        series += coef * np.exp(-ALPHA * lam * lam * t_end) * Rn
    mesh = tensor_mesh(a, b, 0.005, 24, 1)
    fe = AxisymmetricP2(mesh, np.concatenate([facets_at(mesh, a), facets_at(mesh, b)]))
    solver = ThermalSolver(fe, constant_props(), 800.0, NoTransformation(), np.ones_like(fe.r_qp))
    htc = constant_htc(fe.facet_r.size, h, 50.0)
    for _ in range(160):
        solver.commit(solver.try_step(0.25, htc))
    pts = np.array([[a, 0.5 * (a + b), b], [0.0025] * 3])
    numeric = fe.basis.probes(pts) @ solver.T
    exact = 50.0 + 750.0 * np.interp(pts[0], r, series)
    assert np.max(np.abs(numeric - exact)) / 750.0 < 0.005


@pytest.mark.parametrize("nr", [4, 8])
def test_steady_hollow_cylinder_log_profile(nr):
    """Fixed-ish surface temperatures through very large h: T = T_a + (T_b - T_a) ln(r/a)/ln(b/a)."""
    a, b = 0.1, 0.15
    mesh = tensor_mesh(a, b, 0.01, nr, 1)
    fe = AxisymmetricP2(mesh, np.concatenate([facets_at(mesh, a), facets_at(mesh, b)]))
    solver = ThermalSolver(fe, constant_props(), 300.0, NoTransformation(), np.ones_like(fe.r_qp))
    segment = np.where(np.isclose(fe.facet_r.reshape(-1), a), 0, 1)
    htc = TableHTC(["temperature"] * 2, [np.array([0.0])] * 2, [np.array([1e9])] * 2, [500.0, 100.0], segment)
    solver.commit(solver.try_step(1e9, htc))
    r = np.linspace(a, b, 7)
    numeric = fe.basis.probes(np.vstack([r, np.full_like(r, 0.005)])) @ solver.T
    exact = 500.0 + (100.0 - 500.0) * np.log(r / a) / np.log(b / a)
    assert np.max(np.abs(numeric - exact)) < 0.05 * (4 / nr) ** 3  # P2: error falls fast under refinement
