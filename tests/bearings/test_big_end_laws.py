"""Contact laws, lubricant data and crank-slider kinematics of the big-end model at hand-checked points."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from quenchsim.bearings.big_end.contact import coulomb_friction, damped_contact_force, line_contact_force
from quenchsim.bearings.big_end.dynamics import entrainment_speed
from quenchsim.bearings.big_end.ehl import (hertz_line_max_pressure, pan_hamrock_central_film,
                                            thermal_reduction_factor, traction_coefficient)
from quenchsim.bearings.big_end.engine import CrankSlider, GasCycle, big_end_load, gas_force
from quenchsim.bearings.big_end.journal import short_bearing_force
from quenchsim.bearings.big_end.lubricant import load_oil, walther_viscosity
from quenchsim.errors import InputError

A = np.array


def test_palmgren_matches_harris_steel_formula():
    # Harris & Kotzalas: delta = 3.84e-5 Q^0.9 / l^0.8 (mm, N) for steel (E = 206 GPa, nu = 0.3):
    # Q = 100 N, l = 6.8 mm -> 3.84e-5 * 63.096 / 4.6347 = 5.2279e-4 mm
    e_star = 206e9 / (1 - 0.3**2)
    q = line_contact_force(A([5.2279e-7]), A([6.8e-3]), e_star)[0]
    assert q == pytest.approx(100.0, rel=5e-3)
    # 10/9 power law: doubling the approach multiplies the force by 2^(1/0.9)
    q2 = line_contact_force(A([2 * 5.2279e-7]), A([6.8e-3]), e_star)[0]
    assert q2 / q == pytest.approx(2 ** (1 / 0.9), rel=1e-12)
    assert line_contact_force(A([-1e-6]), A([6.8e-3]), e_star)[0] == 0.0


def test_damped_contact_pushes_only_and_damps_approach():
    e_star, l, m = 2.286e11, A([6.8e-3]), A([4e-4])
    q0 = damped_contact_force(A([1e-6]), A([0.0]), l, e_star, m, 0.1)[0]
    assert q0 == pytest.approx(line_contact_force(A([1e-6]), l, e_star)[0])
    assert damped_contact_force(A([1e-6]), A([0.01]), l, e_star, m, 0.1)[0] > q0
    assert damped_contact_force(A([1e-6]), A([-1e3]), l, e_star, m, 0.1)[0] == 0.0
    assert damped_contact_force(A([-1e-9]), A([1.0]), l, e_star, m, 0.1)[0] == 0.0


def test_coulomb_friction_regularised():
    f = coulomb_friction(A([100.0, 100.0, 100.0]), A([1.0, -1.0, 0.0]), 0.05, 0.01)
    assert f == pytest.approx([5.0, -5.0, 0.0], abs=1e-6)


def test_hertz_line_pressure_hand_point():
    # p_h = sqrt(w E' / (2 pi R)), w = 1e5 N/m, E' = 228.6 GPa, R = 1 mm -> 1.9074 GPa
    assert hertz_line_max_pressure(A([1e5]), A([1e-3]), 2.286e11)[0] == pytest.approx(1.9074e9, rel=1e-4)


def test_pan_hamrock_central_film_hand_point():
    # W = 1e5/(2.286e11*1e-3) = 4.3745e-4, U = 0.02*2/2.286e8 = 1.7498e-10, G = 2e-8*2.286e11 = 4572
    # h_c = 1e-3 * 2.922 W^-0.166 U^0.692 G^0.47 = 9.810e-8 m
    h = pan_hamrock_central_film(A([1e5]), A([2.0]), A([1e-3]), 2.286e11, 0.02, 2e-8)[0]
    assert h == pytest.approx(9.810e-8, rel=1e-3)
    # exponents: doubling the speed multiplies h by 2^0.692, doubling the load by 2^-0.166
    h_u = pan_hamrock_central_film(A([1e5]), A([4.0]), A([1e-3]), 2.286e11, 0.02, 2e-8)[0]
    h_w = pan_hamrock_central_film(A([2e5]), A([2.0]), A([1e-3]), 2.286e11, 0.02, 2e-8)[0]
    assert h_u / h == pytest.approx(2**0.692, rel=1e-12)
    assert h_w / h == pytest.approx(2**-0.166, rel=1e-12)


def test_thermal_reduction_hand_point():
    # L = 0.02, p_h = 1 GPa, E' = 228.6 GPa, S = 0.1:
    # (1 - 13.2 * 0.0043745 * 0.02^0.42) / (1 + 0.213 (1 + 2.23 * 0.1^0.83) 0.02^0.64) = 0.96645
    phi = thermal_reduction_factor(A([1e9]), 2.286e11, A([0.02]), A([0.1]))[0]
    assert phi == pytest.approx(0.96645, rel=1e-4)
    assert thermal_reduction_factor(A([1e9]), 2.286e11, A([0.0]), A([0.1]))[0] == 1.0
    more_slip = thermal_reduction_factor(A([1e9]), 2.286e11, A([0.02]), A([0.5]))[0]
    assert more_slip < phi


def test_traction_curve_film_and_boundary():
    s = A([0.0, 0.01, -0.01, 1.0, 1.0, 1.0])
    lam = A([5.0, 5.0, 5.0, 5.0, 0.5, 2.0])
    mu = traction_coefficient(s, lam, 0.04, 0.01, 0.05, 1.0, 3.0)
    assert mu[0] == 0.0
    assert mu[1] == pytest.approx(0.04 * (1 - math.exp(-1)), rel=1e-12)
    assert mu[2] == pytest.approx(-mu[1])
    assert mu[3] == pytest.approx(0.04, rel=1e-12)  # full film: limiting traction
    assert mu[4] == pytest.approx(0.05, rel=1e-12)  # film broken: boundary friction 0.05
    assert mu[5] == pytest.approx(0.045, rel=1e-12)  # half way between the regimes


def _short_bearing_by_quadrature(eps, a, eps_dot, mu, r, length, c):
    """Integrate the short-bearing pressure over the pi film (theta in (pi, 2 pi))."""
    base = mu * r * length**3 / c**2

    def g(th):
        return eps * a * math.sin(th) - eps_dot * math.cos(th)

    fr = base * quad(lambda th: g(th) * math.cos(th) / (1 - eps * math.cos(th)) ** 3, math.pi, 2 * math.pi)[0]
    ft = base * quad(lambda th: g(th) * math.sin(th) / (1 - eps * math.cos(th)) ** 3, math.pi, 2 * math.pi)[0]
    return fr, ft


@pytest.mark.parametrize("eps,omega_j,eps_dot", [(0.3, 300.0, 0.0), (0.8, 120.0, 0.0), (0.6, 0.0, 50.0),
                                                 (0.9, 200.0, -20.0)])
def test_short_bearing_matches_pi_film_integral(eps, omega_j, eps_dot):
    mu, r, length, c = 0.02, 0.01, 0.8e-3, 1e-4
    # eccentricity along +y, radial velocity eps_dot * c, bearing at rest -> omega_bar = omega_j / 2
    fx, fy, _ = short_bearing_force(0.0, eps * c, 0.0, eps_dot * c, omega_j, 0.0, r, length, c, mu, 0.999)
    fr_ref, ft_ref = _short_bearing_by_quadrature(eps, 0.5 * omega_j, eps_dot, mu, r, length, c)
    # line of centres e_r = +y, e_t = z x e_r = -x
    assert fy == pytest.approx(fr_ref, rel=1e-6)
    assert -fx == pytest.approx(ft_ref, rel=1e-6, abs=1e-15)


def test_short_bearing_ocvirk_load_and_petroff_torque():
    mu, r, length, c, w = 0.02, 0.01, 0.8e-3, 1e-4, 400.0
    eps = 0.5
    fx, fy, _ = short_bearing_force(eps * c, 0.0, 0.0, 0.0, w, 0.0, r, length, c, mu, 0.999)
    # Ocvirk load capacity (U = R w): W = mu U L^3 / (4 c^2) * eps / (1-eps^2)^2 * sqrt(16 eps^2 + pi^2 (1-eps^2))
    load = mu * w * r * length**3 / (4 * c**2) * eps / (1 - eps**2) ** 2 * math.sqrt(
        16 * eps**2 + math.pi**2 * (1 - eps**2))
    assert math.hypot(fx, fy) == pytest.approx(load, rel=1e-12)
    _, _, torque = short_bearing_force(0.0, 0.0, 0.0, 0.0, w, 0.0, r, length, c, mu, 0.999)
    assert torque == pytest.approx(-2 * math.pi * mu * r**3 * length * w / c, rel=1e-12)  # Petroff


def test_crank_slider_kinematics():
    crank = CrankSlider(0.018, 0.062, 7000 * math.pi / 30)
    lam = 0.018 / 0.062
    _, acc = crank.piston(A([0.0, math.pi]))
    w2r = crank.omega**2 * 0.018
    assert acc[0] == pytest.approx(-w2r * (1 + lam), rel=1e-12)  # TDC
    assert acc[1] == pytest.approx(w2r * (1 - lam), rel=1e-12)  # BDC
    th = A([0.7])
    h = 1e-6
    beta_p, _, _ = crank.rod_angle(th + h)
    beta_m, _, _ = crank.rod_angle(th - h)
    _, beta_dot, _ = crank.rod_angle(th)
    assert beta_dot[0] == pytest.approx((beta_p - beta_m)[0] / (2 * h) * crank.omega, rel=1e-6)


def test_gas_force_scaled_to_amplitude_and_rod_force_at_tdc():
    crank = CrankSlider(0.018, 0.062, 7000 * math.pi / 30)
    cycle = GasCycle(7.0, -100.0, 100.0, -10.0, 60.0, 5.0, 2.0, 1.3, 25.0, 30.0)
    th = np.linspace(0, 2 * np.pi, 2881)
    f = gas_force(th, crank, cycle, 1000.0)
    assert f.max() == pytest.approx(1000.0, rel=1e-3) and f.min() == pytest.approx(0.0, abs=1e-9)
    peak = np.degrees(th[np.argmax(f)])
    assert 0.0 < peak < 40.0  # peak pressure after TDC
    fx, fy = big_end_load(A([0.0]), crank, cycle, 1000.0, 0.11)
    expected = -(gas_force(A([0.0]), crank, cycle, 1000.0)[0] - 0.11 * crank.omega**2 * 0.018 * (1 + 0.018 / 0.062))
    assert fx[0] == pytest.approx(expected, rel=1e-9) and fy[0] == pytest.approx(0.0, abs=1e-9)


def test_walther_reproduces_data_points_and_unknown_oil():
    nu, _ = walther_viscosity(40.0, 100.0, 40.0, 11.0, 100.0)
    assert nu == pytest.approx(100.0, rel=1e-9)
    nu, beta = walther_viscosity(100.0, 100.0, 40.0, 11.0, 100.0)
    assert nu == pytest.approx(11.0, rel=1e-9)
    h = 1e-3
    nu_p, _ = walther_viscosity(70.0 + h, 100.0, 40.0, 11.0, 100.0)
    nu_m, _ = walther_viscosity(70.0 - h, 100.0, 40.0, 11.0, 100.0)
    nu_0, beta = walther_viscosity(70.0, 100.0, 40.0, 11.0, 100.0)
    assert beta == pytest.approx(-(nu_p - nu_m) / (2 * h) / nu_0, rel=1e-6)
    oil = load_oil("engine_oil_sae30", 70.0)
    assert 0.01 < oil.dynamic_viscosity_Pa_s < 0.04
    with pytest.raises(InputError, match="lubrication.oil"):
        load_oil("whale_oil", 70.0)


@pytest.mark.parametrize("omega_o", [-733.0, -520.0, 300.0])
def test_entrainment_speed_at_the_kinematic_orbit_matches_harris(omega_o):
    """Pure rolling at the kinematic orbit: both contacts entrain at (d_m^2 - D^2)/(4 d_m) |omega_i - omega_o|
    (Harris & Kotzalas 2007), with the inner ring at rest (frame of the pin) and the bore turning at omega_o."""
    r_i, r = 7.2e-3, 1.5e-3
    r_o = r_i + 2 * r
    d_m, dia = r_i + r_o, 2 * r
    orbit = omega_o * r_o / (r_i + r_o)
    spin = orbit * r_i / r + orbit  # rolling on the pin: r (w - Omega) = Omega R_i, w relative to the frame
    d = r_i + r
    u_c = orbit * d
    expected = (d_m**2 - dia**2) / (4 * d_m) * abs(omega_o)
    pin = entrainment_speed(u_c, u_c - r * spin, 0.0, d, d - r)
    bore = entrainment_speed(u_c, u_c + r * spin, omega_o * r_o, d, d + r)
    assert pin == pytest.approx(expected, rel=1e-12)
    assert bore == pytest.approx(expected, rel=1e-12)
    assert u_c + r * spin == pytest.approx(omega_o * r_o, rel=1e-12)  # also rolls on the bore
