"""Numerical machinery of the mechanics solver: the reused factorisation and the elastic-step shortcut
give the answers of a fresh direct solve and of the thermo-elastic model."""

from pathlib import Path

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from quenchsim.mechanics import load_mechanics
from quenchsim.mechanics import verification as v
from quenchsim.mechanics.constitutive import lame_bulk_shear, return_map
from quenchsim.mechanics.solver import MechanicsSolver, _LinearSolver


def _tube_stiffness(E_Pa: float) -> sp.csr_matrix:
    mesh = v.tube_mesh(0.1, 0.15, 0.05, 4)
    solver = MechanicsSolver(mesh, load_mechanics(v.uniform_material(2e11, 0.3), {"plasticity": False, "trip": False}))
    shape = solver.asm.radius.shape
    k, mu = lame_bulk_shear(np.full(shape, E_Pa), np.full(shape, 0.3))
    K = solver.asm.stiffness(return_map(np.zeros(shape + (4,)), k, mu, None, None, None))
    K.data[solver._zero_pos] = 0.0
    K.data[solver._diag_pos] = 1.0
    return K


def test_reused_factorisation_solves_a_changed_matrix_like_a_fresh_direct_solve():
    K_old, K_new = _tube_stiffness(2.0e11), _tube_stiffness(1.8e11)  # e.g. the next step, 10 % softer
    b = np.random.default_rng(5).normal(size=K_old.shape[0])
    linear = _LinearSolver()
    linear.solve(K_old, b, 1e-12)  # factorises K_old
    x = linear.solve(K_new, b, 1e-13)  # CG preconditioned by the factor of K_old
    assert linear.factorizations == 1 and linear.cg_iterations > 0
    exact = spla.spsolve(K_new.tocsc(), b)
    assert np.linalg.norm(x - exact) < 1e-10 * np.linalg.norm(exact)


def test_elastic_step_of_a_plastic_model_ends_in_one_newton_iteration_with_the_elastic_answer():
    mesh = v.tube_mesh(0.1, 0.15, 0.05, 4)
    results = {}
    for name, options in (("elastic", {"plasticity": False, "trip": False}), ("plastic", {"trip": False})):
        model = load_mechanics(v.uniform_material(2e11, 0.3, 1.2e-5, yield_Pa=1e12, hardening_Pa=1e9), options)
        solver = MechanicsSolver(mesh, model)
        T0, X = v.uniform_fields(solver, v.T_REF_C)
        r = solver.asm.radius
        T1 = v.T_REF_C - 50.0 * (r - 0.1) / 0.05  # a radial gradient: thermal stresses, far below yield
        info = solver.step(T1, X, T0, X)
        assert info.converged and info.plastic_points == 0
        results[name] = (solver.displacement_m, info.newton_iterations)
    assert results["plastic"][1] == 1
    u_el, u_pl = results["elastic"][0], results["plastic"][0]
    assert np.abs(u_pl - u_el).max() < 1e-8 * np.abs(u_el).max()


def test_a_step_whose_load_is_below_round_off_converges():
    """After a large free strain (stress-free 1 % expansion) a step with a vanishing temperature change has
    an out-of-balance load at the round-off level of the stresses D (eps - eps_free). Newton cannot reduce
    that residual further; the step must count as converged instead of being cut until it fails (seen at
    the end of a stress-free quench: a uniform, cooled part)."""
    mesh = v.tube_mesh(0.1, 0.15, 0.05, 8)
    model = load_mechanics(v.uniform_material(2e11, 0.3, 1.2e-5), {"plasticity": False, "trip": False})
    solver = MechanicsSolver(mesh, model)
    T0, X = v.uniform_fields(solver, v.T_REF_C)
    T1 = T0 - 800.0  # uniform: ~1 % free contraction, no stress
    assert solver.step(T1, X, T0, X).converged
    r = solver.asm.radius
    T2 = T1 + 1e-9 * (r - 0.1) / 0.05  # a nano-kelvin gradient
    info = solver.step(T2, X, T1, X)
    assert info.converged and info.newton_iterations <= 2


@pytest.mark.slow
def test_fine_step_limits_do_not_stall_the_stress_newton_at_round_off(tmp_path):
    """Ring A, a steel that stays austenitic, a uniform 3000 W/m2K, steps of at most 5 K / 5 s: from t ~ 850 s the
    steps carry ~1e-7..1e-10 K and Newton's residual wandered at 4-6e-5 N, above a round-off floor of 2.8e-5 N,
    so the run was refused at 899.4 s. The run must complete (the floor is now 1e-12 of the forces of D |eps|)."""
    import tomllib

    import tomli_w

    from quenchsim.case import load_case
    from quenchsim.pipeline import run

    root = Path(__file__).resolve().parents[1]
    steel = tomllib.loads((root / "materials" / "SUJ3.toml").read_text())
    for reaction in ("pearlite", "bainite"):     # no diffusional product within the run, no martensite
        steel["kinetics"][reaction] = {"model": "ttt_table", "source": "test: a steel that does not transform",
                                       "T_C": [400.0, 600.0], "t_start_s": [1e12, 1e12], "t_finish_s": [1e13, 1e13],
                                       "X_start": 0.01, "X_finish": 0.99, "T_upper_C": 700.0}
    steel["kinetics"]["martensite"] = {"source": "test", "Ms_C": -200.0, "alpha_per_K": 0.011}
    (tmp_path / "austenitic.toml").write_text(tomli_w.dumps(steel))
    (tmp_path / "austenitic.mechanics.toml").write_text((root / "materials" / "SUJ3.mechanics.toml").read_text())
    case = load_case(root / "cases" / "crb_outer_ring.toml", "1", {
        "material": str(tmp_path / "austenitic.toml"), "quench.htc_model": "table",
        "quench.htc_table": {"T_C": [0.0, 1000.0], "h_W_m2K": [3000.0, 3000.0], "ambient_C": 60.0},
        "time.max_dT_K": 5.0, "time.dt_max_s": 5.0})
    summary = run(case, tmp_path / "run", progress=False).summary
    assert summary["status"] == "ok" and summary["end_state"]["at_room_temperature"]
    assert summary["phases_final"]["austenite"]["min"] == pytest.approx(1.0)


def test_nodal_von_mises_and_plastic_strain_are_never_negative():
    """The vertex projection of a field that is >= 0 at every quadrature point overshoots below zero next to a
    steep gradient: ParaView showed von Mises down to -6.9 MPa and plastic strain to -3.5e-4 (issue 36)."""
    mesh = v.tube_mesh(0.1, 0.15, 0.05, 4)
    solver = MechanicsSolver(mesh, load_mechanics(v.uniform_material(2e11, 0.3), {"plasticity": False, "trip": False}))
    state = solver._state
    state.eq_plastic[0] = 1e-2                    # one plastic element in an elastic section
    state.stress[0, :, 0] = 5e8                   # and one uniaxially stressed
    assert solver.project_to_vertices(state.eq_plastic).min() < 0.0   # the overshoot this guards against
    fields = solver.nodal_fields()
    assert fields["equivalent_plastic_strain"].min() >= 0.0 and fields["von_mises_Pa"].min() >= 0.0
    assert fields["equivalent_plastic_strain"].max() > 1e-3 and fields["von_mises_Pa"].max() > 1e8
