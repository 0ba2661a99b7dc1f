"""Verification of the axisymmetric mechanics solver against closed-form solutions
(formulas and sources in quenchsim/mechanics/verification.py)."""

import numpy as np
import pytest

from quenchsim.materials import load_material
from quenchsim.mechanics import load_mechanics
from quenchsim.mechanics import verification as v


def _material(name):
    return load_material(name)


def test_lame_thick_cylinder_internal_pressure_converges():
    coarse, u_coarse = v.run_lame(4)
    fine, u_fine = v.run_lame(8)
    for comp in ("rr", "tt", "zz"):
        assert fine.errors[comp] < 0.004  # relative to the pressure
        assert coarse.errors[comp] / fine.errors[comp] > 3.0  # ~O(h^2) for P2 stresses
    assert u_fine < 3e-4 and u_coarse / u_fine > 4.0


def test_thermoelastic_hollow_cylinder_logarithmic_temperature_converges():
    coarse = v.run_log_thermal(4)
    fine = v.run_log_thermal(8)
    for comp in ("rr", "tt", "zz"):
        assert fine.errors[comp] < 0.003  # relative to alpha E |tau_a|
        assert coarse.errors[comp] / fine.errors[comp] > 3.0


@pytest.mark.parametrize("name, options", [("SUJ3", {"plasticity": False, "trip": False}), ("SUJ3", {}),
                                           ("100Cr6_furlan", {"plasticity": False, "trip": False})])
def test_uniform_free_expansion_and_transformation_is_stress_free(name, options):
    model = load_mechanics(_material(name), options)
    out = v.run_uniform_free_strain(model, T_C=20.0, martensite=0.7)
    E = 2.1e11
    assert abs(out["free_strain"]) > 1e-3
    assert out["max_von_mises_Pa"] < 1e-9 * E * abs(out["free_strain"])
    assert out["max_displacement_error_m"] < 1e-12


def test_restrained_bar_heated_and_cooled_matches_closed_form():
    out = v.run_restrained_bar(n_steps=6)
    exact = out["exact"]
    assert exact["p_cold"] > exact["p_hot"] > 0  # yields on heating and again on cooling
    assert out["hot"]["sigma_zz"] == pytest.approx(exact["hot"], rel=1e-9)
    assert out["cold"]["sigma_zz"] == pytest.approx(exact["cold"], rel=1e-9)
    assert out["hot"]["p"] == pytest.approx(exact["p_hot"], rel=1e-9)
    assert out["cold"]["p"] == pytest.approx(exact["p_cold"], rel=1e-9)
    assert out["max_lateral_Pa"] < 1e-6 * 200e6
    assert max(out["newton_iterations"]) <= 3  # consistent tangent: no more than predictor + 2


def test_restrained_bar_result_does_not_depend_on_step_size():
    a = v.run_restrained_bar(n_steps=2)["cold"]["sigma_zz"]
    b = v.run_restrained_bar(n_steps=9)["cold"]["sigma_zz"]
    assert a == pytest.approx(b, rel=1e-9)


def test_perfectly_plastic_tube_limit_pressure():
    # Hill's plane-strain limit pressure (2/sqrt 3) sigma_y ln(b/a): equilibrium exists below it, not above
    assert v.run_limit_pressure(0.97, n_r=16)
    assert not v.run_limit_pressure(1.03, n_r=16)


@pytest.mark.parametrize("plasticity", [False, True])
def test_trip_under_constant_uniaxial_stress(plasticity):
    out = v.run_trip_bar(np.linspace(0.0, 1.0, 6), plasticity=plasticity)
    assert out["trip_zz_exact"][-1] > 1e-3
    np.testing.assert_allclose(out["eps_zz"], out["eps_zz_exact"], rtol=0, atol=1e-12)
    np.testing.assert_allclose(out["eps_rr"], out["eps_rr_exact"], rtol=0, atol=1e-12)


def test_trip_strain_is_independent_of_the_transformation_steps():
    few = v.run_trip_bar(np.array([0.0, 0.5, 1.0]))
    many = v.run_trip_bar(np.linspace(0.0, 1.0, 21))
    assert few["eps_zz"][-1] == pytest.approx(many["eps_zz"][-1], rel=1e-12)
