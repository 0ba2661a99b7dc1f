"""Linearised gas film (Lund's perturbation of the discrete Reynolds equation) and the linear whirl threshold:
closed forms, the static solver's own derivative, the orbit method (coarse grids: a few seconds)."""

import json

import numpy as np
import pytest

from quenchsim.bearings.gas_journal import Bearing, Grooves
from quenchsim.bearings.gas_journal.film import FilmFrame
from quenchsim.bearings.gas_journal.forces import film_force
from quenchsim.bearings.gas_journal.linear import LinearisedFilm, concentric_impedance
from quenchsim.bearings.gas_journal.linear_stability import linear_threshold, whirl_root
from quenchsim.bearings.gas_journal.orbit import mass_from_parameter, orbit
from quenchsim.bearings.gas_journal.reynolds import operator_hierarchy
from quenchsim.bearings.gas_journal.solvers import newton_direct
from quenchsim.bearings.gas_journal.stability import critical_mass_parameter, loaded_start
from quenchsim.cli import main
from quenchsim.errors import InputError

FORWARD, BACKWARD = np.array([1.0, -1.0j]), np.array([1.0, 1.0j])


def _whirl_eigenvalues(z):
    """Forward and backward eigenvalues of an isotropic impedance (checks that it is isotropic)."""
    zf, zb = (z @ FORWARD)[0], (z @ BACKWARD)[0]
    np.testing.assert_allclose(z @ FORWARD, zf * FORWARD, atol=1e-9)
    np.testing.assert_allclose(z @ BACKWARD, zb * BACKWARD, atol=1e-9)
    return zf, zb


@pytest.mark.parametrize("gamma", [0.0, 0.25, 0.5, 0.8])
def test_concentric_plain_film_converges_to_the_closed_form(gamma):
    # Ausman's linearised solution with the whirl: second-order convergence of the finite volumes
    exact = concentric_impedance(1.0, 1.0, gamma)
    errors = []
    for level in (3, 4):
        zf, zb = _whirl_eigenvalues(LinearisedFilm(Bearing(), 1.0, 0.0, level=level).impedance(gamma))
        errors.append(max(abs(zf - exact[0]), abs(zb - exact[1])))
    assert errors[1] < 1e-3 * max(abs(exact[0]), abs(exact[1]))
    assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.35)


def test_half_frequency_whirl_of_the_concentric_film_is_force_free():
    # the whirl at half the rotor speed cancels the wedge: zero forward impedance, so an unloaded plain rotor
    # has no threshold (M = 0) and whirls at half frequency
    film = LinearisedFilm(Bearing(), 1.0, 0.0, level=4)
    zf, _ = _whirl_eigenvalues(film.impedance(0.5))
    assert abs(zf) < 1e-4 * abs(concentric_impedance(1.0, 1.0, 0.0)[0])
    threshold = linear_threshold(film)
    assert threshold.critical_mass_parameter == 0.0
    assert threshold.whirl_ratio == pytest.approx(0.5, abs=1e-3)


def test_concentric_growth_rate_matches_the_closed_form_root():
    # the rotor of Mbar = 0.1 on the unloaded plain bearing (issue 37: the orbit search measured +0.0017 per
    # unit T): root of M tau^2 = Z_f(tau / 2) from the closed form, against the discrete film's root
    mass = mass_from_parameter(0.1, 1.0)
    tau0, tau1 = 1.0 + 0j, 1.001 + 0.001j
    f = lambda tau: mass * tau * tau - concentric_impedance(1.0, 1.0, tau / 2.0)[0]  # noqa: E731
    while abs(tau1 - tau0) > 1e-12:
        tau0, tau1 = tau1, tau1 - f(tau1) * (tau1 - tau0) / (f(tau1) - f(tau0))
    growth, whirl = whirl_root(LinearisedFilm(Bearing(), 1.0, 0.0, level=4), mass, 0.5)
    assert growth == pytest.approx(-tau1.imag, rel=0.02)
    assert whirl == pytest.approx(tau1.real / 2.0, abs=1e-4)
    assert 0.0 < growth < 0.003


@pytest.mark.parametrize(("bearing", "lam", "eps"), [(Bearing(), 10.0, 0.7), (Bearing(), 1.0, 0.4),
                                                     (Bearing(1.0, Grooves(10, 30.0, 1.0, 0.5, 0.5)), 40.0, 0.7)])
def test_zero_frequency_stiffness_is_the_derivative_of_the_static_force(bearing, lam, eps):
    # with upwinding active (Lambda 10 and 40 at eps 0.7) the weights' dependence on P counts too
    film = LinearisedFilm(bearing, lam, eps, level=3)
    h = 1e-6
    fd = np.empty((2, 2))
    for k in range(2):
        forces = []
        for sign in (1.0, -1.0):
            disp = np.array(film.displacement)
            disp[k] += sign * h
            ops = operator_hierarchy(bearing, film.grid, lam, tuple(disp), FilmFrame())
            p = newton_direct(ops[0], film.p0, np.zeros(film.p0.shape), tol=1e-12).p
            forces.append(film_force(film.grid, p))
        fd[:, k] = -(forces[0] - forces[1]) / (2.0 * h)
    np.testing.assert_allclose(film.grid_impedance(0.0).real, fd, atol=1e-6 * np.abs(fd).max())
    assert np.abs(film.grid_impedance(0.0).imag).max() == 0.0


def test_grooved_rotor_impedance_is_isotropic_and_its_threshold_lies_between_stable_and_whirling_orbits():
    a1 = Bearing(1.0, Grooves(20, 30.0, 1.1, 0.5, 0.5, "rotor"))
    film = LinearisedFilm(a1, 1.0, 0.0, level=3)
    _whirl_eigenvalues(film.impedance(0.45))
    threshold = linear_threshold(film, (0.3, 0.7, 9))
    # orbit search of the same grid (tests/bearings/test_gas_journal_dynamics.py, slow): stable at 8.724,
    # whirling at 9.514
    assert 8.0 < threshold.critical_mass_parameter < 9.514
    assert threshold.whirl_ratio == pytest.approx(0.49, abs=0.01)


def test_loaded_plain_bearing_whirl_grows_as_the_linear_root_says():
    # issue 37's bearing (L/D 1, eps 0.4, Lambda 1) loaded to its eccentricity: a rotor 30 % above the linear
    # threshold whirls, at the growth rate of the linear root
    film = LinearisedFilm(Bearing(), 1.0, 0.4, level=2)
    threshold = linear_threshold(film)
    assert threshold.critical_mass_parameter == pytest.approx(16.6, rel=0.02)
    mass = mass_from_parameter(1.3 * threshold.critical_mass_parameter, 1.0)
    growth, whirl = whirl_root(film, mass, threshold.whirl_ratio)
    load, _, start = loaded_start(Bearing(), 1.0, 0.4, 2)
    assert load == pytest.approx(film.load, rel=1e-4)
    res = orbit(Bearing(), 1.0, load, mass, level=2, duration=20.0, start=start, initial_film="steady",
                stop_when_settled=False)
    assert not res.stable
    assert res.growth_rate == pytest.approx(growth, rel=0.25)
    assert res.whirl_ratio == pytest.approx(whirl, abs=0.02)


@pytest.mark.slow
def test_loaded_search_brackets_the_linear_threshold():
    res = critical_mass_parameter(Bearing(), 1.0, level=2, duration=20.0, eccentricity=0.4, mass_range=(1.0, 100.0),
                                  rel_tol=0.2)
    linear = linear_threshold(LinearisedFilm(Bearing(), 1.0, 0.4, level=2)).critical_mass_parameter
    assert res.status == "bracketed"
    assert res.stable_below < linear < res.unstable_above


@pytest.mark.parametrize(("kwargs", "field"), [({"eccentricity": 0.3, "load": 0.1}, "load"),
                                               ({"eccentricity": 0.95}, "eccentricity")])
def test_bad_loaded_search(kwargs, field):
    with pytest.raises(InputError, match=field):
        critical_mass_parameter(Bearing(), 1.0, **kwargs)


def test_bad_linearisation_inputs():
    a1 = Bearing(1.0, Grooves(20, 30.0, 1.1, 0.5, 0.5, "rotor"))
    with pytest.raises(InputError, match="eccentricity"):
        LinearisedFilm(a1, 1.0, 0.2, level=3)
    with pytest.raises(InputError, match="bearing_number"):
        LinearisedFilm(Bearing(), 0.0, 0.2, level=3)
    with pytest.raises(InputError, match="grooves.count"):
        LinearisedFilm(Bearing(1.0, Grooves(2, 30.0, 1.0, 0.5, 0.5, "rotor")), 1.0, 0.0, level=3)


def _cli(capsys, *argv):
    code = main(["bearings", "gas-journal", *argv, "--json"])
    return code, capsys.readouterr()


def test_linear_cli_json(capsys):
    code, out = _cli(capsys, "linear", "--bearing-number", "1", "--eccentricity", "0.4", "--level", "3",
                     "--whirl-ratio", "0.25", "0.5")
    assert code == 0
    data = json.loads(out.out)
    assert data["critical_mass_parameter"] == pytest.approx(17.0, rel=0.02)
    assert [c["whirl_ratio"] for c in data["coefficients"]] == [0.25, 0.5]
    k = np.array(data["coefficients"][0]["stiffness"])
    assert k.shape == (2, 2) and k[0, 0] > 0.0 and k[1, 1] > 0.0  # direct stiffness along and across the load


@pytest.mark.parametrize("argv", [
    ["linear", "--bearing-number", "1", "--eccentricity", "0.2", "--grooves", "20", "--grooved", "rotor"],
    ["linear", "--bearing-number", "1", "--whirl-ratio", "0"],
    ["stability", "--bearing-number", "1", "--eccentricity", "0.4", "--load", "0.2"],
    ["orbit", "--bearing-number", "1", "--eccentricity", "0.4", "--load", "0.2", "--mass", "1"]])
def test_linear_and_loaded_stability_bad_input_exit_2(capsys, argv):
    code, out = _cli(capsys, *argv)
    assert code == 2
    assert len(out.err.strip().splitlines()) == 1 and out.out == ""
