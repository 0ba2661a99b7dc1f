"""Verification of the thermal solver against closed-form conduction solutions."""

import pytest

from quenchsim.thermal.verification import hollow_cylinder_error, log_profile_error, solid_cylinder_error


def test_solid_cylinder_robin_matches_series_solution_within_half_percent():
    assert solid_cylinder_error(n_radial=24, dt_s=0.5) < 0.005


def test_solid_cylinder_time_step_convergence_is_first_order_for_backward_euler():
    ratio = solid_cylinder_error(24, 2.0, order=1) / solid_cylinder_error(24, 1.0, order=1)
    assert 1.6 < ratio < 2.4  # backward Euler: error ~ dt


def test_solid_cylinder_time_step_convergence_is_second_order_for_bdf2():
    errors = [solid_cylinder_error(24, dt) for dt in (4.0, 2.0, 1.0)]
    assert all(3.6 < coarse / fine < 4.6 for coarse, fine in zip(errors, errors[1:]))  # BDF2: error ~ dt^2
    assert errors[1] < 0.2 * solid_cylinder_error(24, 2.0, order=1)


def test_hollow_cylinder_transient_robin_on_bore_and_od_matches_eigenfunction_series():
    assert hollow_cylinder_error() < 0.005


@pytest.mark.parametrize("n_radial", [4, 8])
def test_steady_hollow_cylinder_log_profile(n_radial):
    assert log_profile_error(n_radial) < 0.05 * (4 / n_radial) ** 3  # P2: error falls ~h^3 or faster


def test_log_profile_converges_under_mesh_refinement():
    e2, e4, e8 = log_profile_error(2), log_profile_error(4), log_profile_error(8)
    assert e2 > e4 > e8
    assert e2 / e4 > 6  # at least ~ third order in the nodal error of P2


def _cylinder_solver():
    import numpy as np
    import skfem

    from quenchsim.thermal.assembly import AxisymmetricP2
    from quenchsim.thermal.solver import NoTransformation, ThermalSolver
    from quenchsim.thermal.verification import _facets_at, constant_properties

    mesh = skfem.MeshTri.init_tensor(np.linspace(0.0, 0.05, 13), np.linspace(0.0, 0.01, 3))
    fe = AxisymmetricP2(mesh, _facets_at(mesh, 0.05))
    return fe, lambda **kw: ThermalSolver(fe, constant_properties(), 800.0, NoTransformation(), np.ones_like(fe.r_qp), **kw)


def test_one_pass_system_equals_the_sum_of_mass_stiffness_and_robin():
    import numpy as np

    fe, _ = _cylinder_solver()
    rng = np.random.default_rng(3)
    m, k, h = rng.random(fe.r_qp.shape), rng.random(fe.r_qp.shape), rng.random(fe.facet_r.shape)
    expected = (fe.mass(m) + fe.stiffness(k) + fe.robin(h)).toarray()
    assert np.abs(fe.system(m, k, h).toarray() - expected).max() < 1e-13 * np.abs(expected).max()


@pytest.mark.parametrize("order", [1, 2])
def test_step_through_a_boiling_curve_solves_the_nonlinear_step_equations(order):
    """Transition boiling: q = h(T_s)(T_s - T_oil) falls with T_s between 450 and 650 C, so the exact flux
    derivative is negative there. Each step (exact derivative first, damped once a correction grows) must
    solve the implicit step equations  C (a0 (T - T_old) - a2 (T_old - T_prev))/dt + K T + int q(T_s) phi r ds = 0
    to within the Picard tolerance: the remaining residual, as a temperature correction, is below 0.1 K.
    Backward Euler: a0 = 1, a2 = 0; BDF2 at a constant step: a0 = 3/2, a2 = 1/2 after a first backward-Euler step."""
    import numpy as np
    import scipy.sparse.linalg as spla

    from quenchsim.thermal.boundary import TableHTC
    from quenchsim.thermal.verification import CP_J_KGK, K_W_MK, RHO_KG_M3

    fe, make = _cylinder_solver()
    T_tab, h_tab = np.array([100.0, 450.0, 650.0, 900.0]), np.array([800.0, 6000.0, 800.0, 300.0])
    htc = TableHTC(["temperature"], [T_tab], [h_tab], [60.0], np.zeros(fe.facet_r.size, dtype=int))
    T_s = np.array([500.0, 600.0])
    q = np.interp(T_s, T_tab, h_tab) * (T_s - 60.0)
    assert q[1] < q[0]  # the flux falls with the surface temperature in this range
    solver, dt = make(order=order), 0.5
    solver.T[:] = 620.0
    rho_cp, k = np.full(fe.r_qp.shape, RHO_KG_M3 * CP_J_KGK), np.full(fe.r_qp.shape, K_W_MK)
    T_prev = None
    for n in range(4):
        a0, a2 = (1.0, 0.0) if order == 1 or n == 0 else (1.5, 0.5)
        step = solver.try_step(dt, htc)
        Ts = fe.at_facet_qp(step.T)
        T_old = fe.at_qp(solver.T)
        history = T_old if a2 == 0.0 else T_old + (a2 / a0) * (T_old - T_prev)
        linear = fe.system(a0 * rho_cp / dt, k, np.zeros(fe.facet_r.shape))
        residual = (linear @ step.T - fe.load(a0 * rho_cp * history / dt)
                    + fe.robin_load(htc(Ts.reshape(-1), 0.0).reshape(Ts.shape) * (Ts - 60.0)))
        assert np.abs(spla.spsolve(linear.tocsc(), residual)).max() < 0.1
        T_prev = T_old
        solver.commit(step)
    assert solver.T.min() < 450.0  # the surface did cool through the boiling range


def test_step_linear_solver_matches_a_direct_solve_in_every_mode():
    """Jacobi CG (short steps), CG preconditioned by a reused factor (long steps, after the switch) and
    the pivoting fallback for a matrix that is not positive definite all give the direct solution."""
    import numpy as np
    import scipy.sparse.linalg as spla

    from quenchsim.thermal.linear import StepLinearSolver

    fe, _ = _cylinder_solver()
    shape, facet_shape = fe.r_qp.shape, fe.facet_r.shape
    b = np.random.default_rng(9).normal(size=fe.n_dofs)
    linear = StepLinearSolver(rtol=1e-13, jacobi_max=40)

    def check(A):
        x = linear.solve(A, b, np.zeros_like(b))
        exact = spla.spsolve(A.tocsc(), b)
        assert np.linalg.norm(x - exact) < 1e-10 * np.linalg.norm(exact)

    check(fe.system(np.full(shape, 3.9e6 / 0.05), np.full(shape, 30.0), np.full(facet_shape, 2000.0)))
    assert not linear.use_factor  # a short step: Jacobi CG was enough
    for dt in (60.0, 90.0, 120.0):  # long steps: one factorisation, reused as preconditioner
        check(fe.system(np.full(shape, 3.9e6 / dt), np.full(shape, 30.0), np.full(facet_shape, 10.0)))
    assert linear.use_factor and linear.factorizations == 1
    # a strongly negative surface term (flux falling steeply with T_s): indefinite, still solved
    check(fe.system(np.full(shape, 3.9e6 / 120.0), np.full(shape, 30.0), np.full(facet_shape, -4e4)))


def test_an_indefinite_step_matrix_is_refused_by_the_factorisation():
    """LDL' without pivoting factorises an indefinite matrix without complaint; the definiteness check makes the
    factorisation refuse it (the thermal solver's LU then takes over), and a definite one is solved exactly."""
    import numpy as np
    import scipy.sparse as sp

    from quenchsim.fem.linalg import SparseCholesky

    indefinite = sp.csr_matrix(np.array([[1.0, 2.0], [2.0, 1.0]]))
    with pytest.raises(np.linalg.LinAlgError, match="not positive definite"):
        SparseCholesky(indefinite)
    SparseCholesky(indefinite, check_definite=False)   # the check is what refuses it
    spd = SparseCholesky(sp.csr_matrix(np.array([[2.0, 1.0], [1.0, 2.0]])))
    assert np.allclose(spd.solve(np.array([3.0, 3.0])), [1.0, 1.0])
    with pytest.raises(np.linalg.LinAlgError):
        spd.refactorize(indefinite)        # a numeric refactorisation is checked too


def test_a_numeric_refactorisation_is_the_fresh_factor_of_the_new_matrix():
    """:meth:`SparseCholesky.refactorize` keeps the ordering of the first matrix when the pattern is the same: the
    factor is then bit for bit the one a fresh factorisation gives (a resumed run refactorises from scratch); a
    matrix of another pattern is factorised afresh."""
    import numpy as np
    import scipy.sparse as sp

    from quenchsim.fem.linalg import SparseCholesky

    rng = np.random.default_rng(3)
    n = 60
    lap = sp.diags([-np.ones(n - 1), 2.0 * np.ones(n), -np.ones(n - 1)], [-1, 0, 1], format="csr")
    first = lap + sp.diags(rng.uniform(0.1, 1.0, n), format="csr")
    second = lap + sp.diags(rng.uniform(1.0, 5.0, n), format="csr")
    b = rng.standard_normal(n)
    factor = SparseCholesky(first)
    factor.refactorize(second)
    assert np.array_equal(factor.solve(b), SparseCholesky(second).solve(b))
    assert np.linalg.norm(second @ factor.solve(b) - b) < 1e-12 * np.linalg.norm(b)
    other = sp.csr_matrix(np.diag(np.arange(1.0, n + 1.0)))      # another pattern
    factor.refactorize(other)
    assert np.allclose(factor.solve(b), b / np.arange(1.0, n + 1.0), rtol=1e-14)
