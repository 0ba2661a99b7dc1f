"""Orbits (RK45 + Crank-Nicolson film), whirl detection and the stability threshold."""

import numpy as np
import pytest

from quenchsim.bearings.gas_journal import Bearing, Grooves, static_characteristics
from quenchsim.bearings.gas_journal.orbit import mass_from_parameter, orbit, whirl_analysis
from quenchsim.bearings.gas_journal.stability import critical_mass_parameter
from quenchsim.bearings.gas_journal.transient import CrankNicolsonFilm, FilmState
from quenchsim.bearings.gas_journal.geometry import grid_for_level
from quenchsim.errors import InputError


def test_whirl_analysis_of_a_synthetic_spiral():
    t = np.linspace(0.0, 60.0, 60001)
    sigma, omega = -0.05, 1.0  # decay per unit T; 1 rad per unit T = half the rotor speed
    r = 0.1 * np.exp(sigma * t)
    growth, whirl = whirl_analysis(t, 0.2 + r * np.cos(omega * t), -0.3 + r * np.sin(omega * t), (0.2, -0.3))
    assert growth == pytest.approx(sigma, rel=1e-3)
    assert whirl == pytest.approx(0.5, rel=1e-3)


def test_crank_nicolson_film_relaxes_to_the_steady_solution():
    bearing = Bearing()
    grid = grid_for_level(3, bearing)
    steady = static_characteristics(bearing, 3.0, 0.5, level=3)
    film = CrankNicolsonFilm(bearing, grid, 3.0)
    state = FilmState(0.0, steady.displacement, np.ones(grid.shape))
    for k in range(1, 41):
        state = film.step(state, 0.25 * k, steady.displacement)
    np.testing.assert_allclose(state.p, steady.p, atol=1e-4)


def test_orbit_settles_at_the_static_equilibrium_of_the_same_grid():
    lam, load = 3.0, 0.720
    res = orbit(Bearing(), lam, load, mass_from_parameter(0.5, lam), level=2, duration=80.0, start=(0.0, -0.48))
    assert res.settled and res.stable
    angle = np.degrees(np.arctan2(res.centre[1], res.centre[0]))
    static = static_characteristics(Bearing(), lam, res.eccentricity, angle, level=2)
    assert static.load == pytest.approx(load, rel=2e-3)
    assert static.attitude_deg == pytest.approx(res.attitude_deg, abs=0.1)


@pytest.mark.slow
@pytest.mark.parametrize(("lam", "eps", "load", "attitude"),
                         [(0.6, 0.2, 0.0457, 79.33), (0.6, 0.6, 0.188, 62.09), (3.0, 0.2, 0.176, 47.93),
                          (3.0, 0.6, 0.720, 30.50), (12.0, 0.2, 0.273, 17.95), (12.0, 0.6, 1.280, 11.58)])
def test_orbit_recovers_raimondi(lam, eps, load, attitude):
    res = orbit(Bearing(), lam, load, mass_from_parameter(0.1, lam), level=4, duration=200.0,
                start=(0.0, -0.8 * eps), initial_film="steady", settle_tolerance=2e-6)
    assert res.eccentricity == pytest.approx(eps, abs=0.005)
    assert abs(res.attitude_deg - attitude) < 0.5


def test_bad_orbit_inputs():
    with pytest.raises(InputError, match="mass"):
        orbit(Bearing(), 3.0, 0.7, -1.0)
    with pytest.raises(InputError, match="eccentricity"):
        orbit(Bearing(), 3.0, 0.7, 0.1, start=(1.0, 0.0))
    with pytest.raises(InputError, match="bearing_number"):
        critical_mass_parameter(Bearing(), 0.0)


@pytest.mark.slow
def test_grooved_rotor_a1_has_a_stability_threshold():
    # the search of the report page (reports/bearing_gas_journal.md section 5, before the range ends were
    # run first): stable at Mbar 8.724, unstable at 9.514; running the ends of the mass range first must
    # not change the bisection that follows
    a1 = Bearing(1.0, Grooves(20, 30.0, 1.1, 0.5, 0.5, "rotor"))
    res = critical_mass_parameter(a1, 1.0, level=3, rel_tol=0.1, duration=40.0)
    assert res.status == "bracketed"
    assert [m for m, *_ in res.trials[:2]] == [100.0, 0.1]
    assert res.stable_below == pytest.approx(8.724, abs=5e-4)
    assert res.unstable_above == pytest.approx(9.514, abs=5e-4)
    assert res.whirl_ratio == pytest.approx(0.5, abs=0.03)
