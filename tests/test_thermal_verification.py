"""Verification of the thermal solver against closed-form conduction solutions."""

import pytest

from quenchsim.thermal.verification import hollow_cylinder_error, log_profile_error, solid_cylinder_error


def test_solid_cylinder_robin_matches_series_solution_within_half_percent():
    assert solid_cylinder_error(n_radial=24, dt_s=0.5) < 0.005


def test_solid_cylinder_time_step_convergence_is_first_order():
    ratio = solid_cylinder_error(24, 2.0) / solid_cylinder_error(24, 1.0)
    assert 1.6 < ratio < 2.4  # backward Euler: error ~ dt


def test_hollow_cylinder_transient_robin_on_bore_and_od_matches_eigenfunction_series():
    assert hollow_cylinder_error() < 0.005


@pytest.mark.parametrize("n_radial", [4, 8])
def test_steady_hollow_cylinder_log_profile(n_radial):
    assert log_profile_error(n_radial) < 0.05 * (4 / n_radial) ** 3  # P2: error falls ~h^3 or faster


def test_log_profile_converges_under_mesh_refinement():
    e2, e4, e8 = log_profile_error(2), log_profile_error(4), log_profile_error(8)
    assert e2 > e4 > e8
    assert e2 / e4 > 6  # at least ~ third order in the nodal error of P2
