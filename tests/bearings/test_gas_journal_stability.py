"""Stability search: range ends first, no-threshold outcomes, orbit and time budgets (coarse grids, short
orbits: a few seconds)."""

import math

import pytest

from quenchsim.bearings.gas_journal import Bearing
from quenchsim.bearings.gas_journal.orbit import WallTimeExceeded, mass_from_parameter, orbit
from quenchsim.bearings.gas_journal.stability import (BRACKETED, ITERATION_BUDGET, TIME_BUDGET, UNSTABLE_IN_RANGE,
                                                      critical_mass_parameter, orbits_to_converge)
from quenchsim.errors import InputError

# level 2 (21 x 5 nodes), T = 20 (just over the 3 whirl periods an orbit needs to be classified)
FAST = {"level": 2, "duration": 20.0}


def test_unloaded_plain_bearing_is_unstable_for_every_mass_in_range():
    # concentric plain journal without load: half-frequency whirl at any mass -> no threshold; the search
    # stops after the two ends instead of dividing the mass by 4 for ever
    res = critical_mass_parameter(Bearing(), 1.0, mass_range=(0.5, 50.0), **FAST)
    assert res.status == UNSTABLE_IN_RANGE
    assert [m for m, *_ in res.trials] == [50.0, 0.5]
    assert not any(s for _, s, _, _ in res.trials)
    assert math.isnan(res.critical_mass_parameter)
    assert res.stable_below is None and res.unstable_above == 0.5
    assert res.whirl_ratio == pytest.approx(0.5, abs=0.01)  # the whirl at the light end is half-frequency
    assert "unstable for every mass in range" in res.message and "[0.5, 50]" in res.message


def test_loaded_plain_bearing_bracket_does_not_depend_on_the_search_path():
    # a loaded plain bearing has a whirl onset: two searches from different first guesses (different
    # trial masses) must end on overlapping brackets, each no wider than rel_tol
    kwargs = {"load": 0.2, "mass_range": (1.0, 100.0), "rel_tol": 0.1, **FAST}
    up = critical_mass_parameter(Bearing(), 1.0, first_guess=1.0, **kwargs)
    down = critical_mass_parameter(Bearing(), 1.0, first_guess=60.0, **kwargs)
    for res in (up, down):
        assert res.status == BRACKETED
        assert [m for m, *_ in res.trials[:2]] == [100.0, 1.0]
        assert res.unstable_above / res.stable_below <= 1.1
        assert (res.stable_below, True) in [(m, s) for m, s, _, _ in res.trials]
        assert (res.unstable_above, False) in [(m, s) for m, s, _, _ in res.trials]
    assert {m for m, *_ in up.trials[2:]} != {m for m, *_ in down.trials[2:]}
    assert max(up.stable_below, down.stable_below) < min(up.unstable_above, down.unstable_above)


def test_orbit_budget_stops_with_the_bracket_so_far():
    res = critical_mass_parameter(Bearing(), 1.0, load=0.2, mass_range=(1.0, 100.0), max_trials=3, **FAST)
    assert res.status == ITERATION_BUDGET and len(res.trials) == 3
    stable = [m for m, s, _, _ in res.trials if s]
    assert res.stable_below == max(stable)
    assert res.unstable_above == min(m for m, s, _, _ in res.trials if not s and m > res.stable_below)
    assert math.isnan(res.critical_mass_parameter)
    assert res.message.startswith("stopped: orbit budget of 3 orbits reached; bracket so far: stable at ")
    # what it still needs: bisections of the bracket so far to 5 %, at the measured time per orbit
    more = orbits_to_converge(res.stable_below, res.unstable_above, 0.05)
    assert f"~{more} more orbits to a bracket within 5 %" in res.message
    assert res.seconds_needed == pytest.approx(more * res.wall_time_s / 3, rel=0.05)


@pytest.mark.parametrize(("lo", "hi", "orbits"), [(1.0, 1.04, 0), (1.0, 1.1, 1), (1.0, 4.0, 5), (0.1, 100.0, 8)])
def test_orbits_to_converge_counts_bisections_in_log_mass(lo, hi, orbits):
    # each bisection halves ln(hi / lo); stop at hi / lo <= 1.05
    assert orbits_to_converge(lo, hi, 0.05) == orbits
    assert (hi / lo) ** (0.5 ** orbits) <= 1.05 < (hi / lo) ** (0.5 ** max(orbits - 1, 0)) or orbits == 0


def test_time_budget_abandons_the_running_orbit():
    budget_s = 0.05
    res = critical_mass_parameter(Bearing(), 1.0, mass_range=(0.5, 50.0), max_time_s=budget_s, **FAST)
    assert res.status == TIME_BUDGET and res.trials == []
    assert res.stable_below is None and res.unstable_above is None
    assert "time budget of 0.05 s reached during orbit 1 (Mbar 50" in res.message
    assert res.wall_time_s < budget_s + 1.0  # one RK step (six film solves) past the deadline at most
    with pytest.raises(WallTimeExceeded, match="wall-time budget"):
        orbit(Bearing(), 1.0, 0.0, mass_from_parameter(0.5, 1.0), start=(0.1, 0.0), max_wall_time_s=0.0, **FAST)


@pytest.mark.parametrize(("kwargs", "field"), [({"mass_range": (10.0, 1.0)}, "mass_range"),
                                               ({"max_trials": 1}, "max_trials"),
                                               ({"max_time_s": 0.0}, "max_time_s")])
def test_bad_search_limits(kwargs, field):
    with pytest.raises(InputError, match=field):
        critical_mass_parameter(Bearing(), 1.0, **kwargs)
