"""Verification of the gas journal bearing statics against Raimondi's solution (reference section 1)."""

import numpy as np
import pytest

from quenchsim.bearings.gas_journal import Bearing, Grooves, equilibrium, static_characteristics
from quenchsim.bearings.gas_journal.geometry import grid_for_level
from quenchsim.bearings.gas_journal.reynolds import operator_hierarchy, solve
from quenchsim.errors import InputError

# Raimondi's finite-difference solution, L/D = 1 (reference section 1 table): Lambda, eps, F_y, attitude deg
RAIMONDI = [
    (0.6, 0.2, 0.0457, 79.33),
    (0.6, 0.6, 0.188, 62.09),
    (3.0, 0.2, 0.176, 47.93),
    (3.0, 0.6, 0.720, 30.50),
    (12.0, 0.2, 0.273, 17.95),
    (12.0, 0.6, 1.280, 11.58),
]


@pytest.mark.parametrize(("lam", "eps", "load", "attitude"), RAIMONDI)
def test_raimondi_points(lam, eps, load, attitude):
    res = static_characteristics(Bearing(), lam, eps, level=4)
    assert res.load == pytest.approx(load, rel=0.02)
    assert abs(res.attitude_deg - attitude) < 0.5
    assert res.residual <= 1e-5


def test_inverse_problem_recovers_raimondi_equilibrium():
    res = equilibrium(Bearing(), 3.0, 0.720, level=4)
    assert np.hypot(*res.displacement) == pytest.approx(0.6, abs=0.005)
    assert abs(res.attitude_deg - 30.50) < 0.5
    assert res.load == pytest.approx(0.720, rel=1e-4)


@pytest.mark.parametrize("method", ["multigrid", "gauss-seidel", "sor", "direct"])
def test_all_methods_reach_the_same_solution(method):
    bearing = Bearing(1.0, Grooves(5, 30.0, 1.0, 0.5, 0.5))
    ref = static_characteristics(bearing, 10.0, 0.5, level=3, method="direct")
    res = static_characteristics(bearing, 10.0, 0.5, level=3, method=method, sor_omega=1.7)
    assert res.residual <= 1e-5
    # ||R||_2 <= 1e-5 bounds the load difference far below the discretisation error
    assert res.load == pytest.approx(ref.load, rel=1e-4)
    assert res.attitude_deg == pytest.approx(ref.attitude_deg, abs=0.01)


def test_zero_depth_grooves_reproduce_the_plain_bearing():
    plain_skewed = Bearing(1.0, Grooves(5, 30.0, 0.0, 0.5, 0.5))
    grid = grid_for_level(4, plain_skewed)
    ops = operator_hierarchy(plain_skewed, grid, 3.0, (0.0, -0.6))
    p_ref = solve(ops, "direct").p
    for grooves in (Grooves(20, 30.0, 0.0, 0.3, 0.7), Grooves(5, 30.0, 0.0, 0.5, 0.5, "rotor")):
        bearing = Bearing(1.0, grooves)
        res = static_characteristics(bearing, 3.0, 0.6, level=4, method="direct")
        np.testing.assert_allclose(res.p, p_ref, atol=1e-6)
    # and against the unskewed plain grid: the same solution up to the skewed grid's discretisation error,
    # which vanishes under refinement at the scheme's second order
    gaps = []
    for level in (4, 5, 6):
        skewed = static_characteristics(plain_skewed, 3.0, 0.6, level=level)
        plain = static_characteristics(Bearing(), 3.0, 0.6, level=level)
        gaps.append(abs(skewed.load / plain.load - 1.0))
    assert gaps[-1] < 5e-4 and abs(skewed.attitude_deg - plain.attitude_deg) < 0.05
    assert np.log2(gaps[0] / gaps[1]) > 1.8 and np.log2(gaps[1] / gaps[2]) > 1.8


@pytest.mark.parametrize(
    ("kwargs", "field"),
    [
        (dict(bearing_number=3.0, eccentricity=1.0), "eccentricity"),
        (dict(bearing_number=3.0, eccentricity=1.2), "eccentricity"),
        (dict(bearing_number=-1.0, eccentricity=0.5), "bearing_number"),
    ],
)
def test_bad_operating_point(kwargs, field):
    with pytest.raises(InputError, match=field):
        static_characteristics(Bearing(), **kwargs)


@pytest.mark.parametrize("bad", [dict(width_ratio=0.0), dict(width_ratio=1.0), dict(length_ratio=1.5),
                                 dict(length_ratio=-0.1), dict(depth_ratio=-1.0), dict(angle_deg=90.0)])
def test_bad_grooves(bad):
    args = dict(count=5, angle_deg=30.0, depth_ratio=1.0, width_ratio=0.5, length_ratio=0.5) | bad
    with pytest.raises(InputError):
        Grooves(**args)
