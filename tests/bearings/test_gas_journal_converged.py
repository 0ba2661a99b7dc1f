"""Grid-converged linear threshold: Richardson's estimate, the ladder's stopping rules, the windowed scan."""

import math

import pytest

from quenchsim.bearings.gas_journal import Bearing
from quenchsim.bearings.gas_journal.converged_threshold import (CONVERGED, MAX_LEVEL, TIME_BUDGET,
                                                                converged_linear_threshold, richardson)
from quenchsim.bearings.gas_journal.linear import LinearisedFilm
from quenchsim.bearings.gas_journal.linear_stability import linear_threshold
from quenchsim.errors import InputError


@pytest.mark.parametrize("order", [1.0, 1.5, 2.0])
def test_richardson_recovers_the_limit_of_a_power_law_sequence(order):
    # M_m = M_inf - C h_m^p with h halved per level: the estimate is exact, the order is p
    values = [12.0 - 3.0 * 0.5 ** (order * m) for m in range(3, 7)]
    estimate, error, observed = richardson(values)
    assert estimate == pytest.approx(12.0, rel=1e-12)
    assert observed == pytest.approx(order, rel=1e-12)
    assert error == pytest.approx(12.0 - values[-1], rel=1e-12)


def test_richardson_without_an_asymptotic_order_takes_the_last_change():
    assert richardson([1.0, 2.0]) == (2.0, *richardson([1.0, 2.0])[1:])
    assert math.isnan(richardson([1.0, 2.0])[1])
    estimate, error, order = richardson([1.0, 1.5, 2.5])   # growing differences: not converging
    assert (estimate, error) == (2.5, 1.0) and math.isnan(order)


def test_windowed_scan_finds_the_full_scans_threshold():
    film = LinearisedFilm(Bearing(), 1.0, 0.4, level=3)
    full = linear_threshold(film)
    near = linear_threshold(film, near=(full.whirl_ratio + 0.03,))
    assert near.critical_mass_parameter == pytest.approx(full.critical_mass_parameter, rel=1e-8)
    # a window holding no neutral whirl falls back to the full scan
    assert linear_threshold(film, near=(0.9,)).critical_mass_parameter == pytest.approx(
        full.critical_mass_parameter, rel=1e-8)


def test_ladder_stops_at_max_level_and_reports_the_estimate_of_the_levels_run():
    res = converged_linear_threshold(Bearing(), 1.0, 0.4, first_level=2, max_level=4, rel_tol=1e-6)
    assert res.status == MAX_LEVEL and [r.level for r in res.levels] == [2, 3, 4]
    expected = richardson([r.mass_parameter for r in res.levels])
    assert (res.mass_parameter, res.grid_error) == pytest.approx(expected[:2])
    assert "not converged to 0.0001 % by level 4" in res.message


def test_ladder_converges_on_the_plain_bearing():
    res = converged_linear_threshold(Bearing(), 1.0, 0.4)
    assert res.status == CONVERGED and res.relative_grid_error <= 0.02
    assert res.observed_order == pytest.approx(2.0, abs=0.3)   # second-order finite volumes on a smooth film


def test_ladder_time_budget_names_the_time_the_next_level_needs():
    res = converged_linear_threshold(Bearing(), 1.0, 0.4, max_time_s=1e-3)
    assert res.status == TIME_BUDGET and len(res.levels) == 1
    assert res.next_level_seconds == pytest.approx(5.0 * res.levels[0].seconds)
    assert "level 4 needs ~" in res.message and "--max-time-s" in res.message


@pytest.mark.parametrize(("kwargs", "field"), [({"max_level": 11}, "max_level"), ({"rel_tol": 0.0}, "rel_tol"),
                                               ({"max_time_s": 0.0}, "max_time_s"),
                                               ({"first_level": 5, "max_level": 4}, "max_level")])
def test_ladder_bad_limits(kwargs, field):
    with pytest.raises(InputError, match=field):
        converged_linear_threshold(Bearing(), 1.0, 0.4, **kwargs)
