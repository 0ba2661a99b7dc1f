"""Hertz contact: closed forms, the exact ellipticity equation, stiffness identities, bad input."""

import math

import pytest
from scipy.special import ellipe, ellipk

from quenchsim.bearings import hertz
from quenchsim.bearings import kinematics as kin
from quenchsim.errors import InputError

STEEL_E, STEEL_NU = 2.08e11, 0.3


def test_sphere_on_flat_closed_form():
    r, Q = 0.005, 100.0
    c = hertz.point_contact(Q, r, r, 1e12, 1e12, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    e_star = hertz.effective_modulus_Pa(STEEL_E, STEEL_NU, STEEL_E, STEEL_NU) / 2.0
    a = (3.0 * Q * r / (4.0 * e_star)) ** (1.0 / 3.0)  # Johnson 1985 eq. 4.22
    assert c.a_m == pytest.approx(a, rel=1e-6) and c.b_m == pytest.approx(a, rel=1e-6)
    assert c.approach_m == pytest.approx(a * a / r, rel=1e-6)
    assert c.p_max_Pa == pytest.approx(3.0 * Q / (2.0 * math.pi * a * a), rel=1e-6)
    assert c.stiffness_N_m15 == pytest.approx(4.0 / 3.0 * e_star * math.sqrt(r), rel=1e-6)


@pytest.mark.parametrize("ratio", [1.0 + 1e-7, 1.001, 1.7, 12.0, 310.0, 1e5])
def test_ellipticity_solves_hertz_equation(ratio):
    k = hertz.ellipticity_from_radius_ratio(ratio)
    m = 1.0 - 1.0 / k**2
    K, E = ellipk(m), ellipe(m)
    if ratio - 1.0 > 1e-4:
        assert (k * k * E - K) / (K - E) == pytest.approx(ratio, rel=1e-9)
    if 1.5 < ratio <= 100.0:  # Brewe & Hamrock (1977) fit k ~ 1.0339 ratio^0.636 (range 1..100, few %)
        assert k == pytest.approx(1.0339 * ratio**0.636, rel=0.04)


@pytest.mark.parametrize("load", [10.0, 500.0, 5000.0])
def test_stiffness_matches_load_deflection(load):
    radii = (0.004, 0.004, 0.0125, -0.00416)  # ball on an inner raceway
    c = hertz.point_contact(load, *radii, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    assert load == pytest.approx(c.stiffness_N_m15 * c.approach_m**1.5, rel=1e-10)
    assert c.stiffness_N_m15 == pytest.approx(
        hertz.point_contact_stiffness(*radii, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU), rel=1e-12)
    # the pressure integrates to the load: Q = (2/3) pi a b p_max
    assert 2.0 / 3.0 * math.pi * c.a_m * c.b_m * c.p_max_Pa == pytest.approx(load, rel=1e-12)
    assert c.major_axis == "y"  # groove is conformal across the rolling direction
    # swapping x and y only rotates the ellipse
    s = hertz.point_contact(load, radii[1], radii[0], radii[3], radii[2], STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    assert (s.a_m, s.b_m, s.major_axis) == (pytest.approx(c.a_m), pytest.approx(c.b_m), "x")


def test_ball_race_series_stiffness():
    s = hertz.ball_race_stiffness(0.0079375, 0.0335, 0.0, 0.515, 0.525, STEEL_E, STEEL_NU)
    Q = 300.0
    total = (Q / s.inner_N_m15) ** (2 / 3) + (Q / s.outer_N_m15) ** (2 / 3)
    assert total == pytest.approx((Q / s.combined_N_m15) ** (2 / 3), rel=1e-12)
    same = hertz.ball_race_stiffness(0.0079375, 0.0335, 0.0, 0.52, 0.52, STEEL_E, STEEL_NU)
    assert same.outer_N_m15 > same.inner_N_m15  # equal grooves: the concave outer race is stiffer


def test_line_contact_closed_form_and_shear():
    lc = hertz.line_contact(1000.0, 0.01, 0.005, 1e12, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    e_star = hertz.effective_modulus_Pa(STEEL_E, STEEL_NU, STEEL_E, STEEL_NU) / 2.0
    b = math.sqrt(4.0 * (1000.0 / 0.01) * 0.005 / (math.pi * e_star))  # Johnson eq. 4.43
    assert lc.half_width_m == pytest.approx(b, rel=1e-9)
    assert lc.p_max_Pa == pytest.approx(2.0 * 1e5 / (math.pi * b), rel=1e-9)
    # textbook values of the max principal shear: 0.30 p0 at 0.78 b
    assert lc.max_shear_Pa / lc.p_max_Pa == pytest.approx(0.300, abs=1e-3)
    assert lc.depth_max_shear_m / b == pytest.approx(0.786, abs=1e-3)
    # tau_1(z) = (p0/b)(z - z^2/sqrt(b^2+z^2)) is maximal there (sampled check)
    tau = lambda z: lc.p_max_Pa / b * (z - z * z / math.sqrt(b * b + z * z))  # noqa: E731
    z0 = lc.depth_max_shear_m
    assert tau(z0) >= max(tau(0.95 * z0), tau(1.05 * z0))
    assert tau(z0) == pytest.approx(lc.max_shear_Pa, rel=1e-12)


def test_bad_input():
    with pytest.raises(InputError, match="load_N"):
        hertz.point_contact(-1.0, 0.004, 0.004, 0.01, -0.0042, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    with pytest.raises(InputError, match="ry1_m, ry2_m"):  # groove tighter than the ball
        hertz.point_contact(10.0, 0.004, 0.004, 0.01, -0.0039, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    with pytest.raises(InputError, match="nu1"):
        hertz.effective_modulus_Pa(STEEL_E, 0.6, STEEL_E, 0.3)
    with pytest.raises(InputError, match="outer_groove_radius_ratio"):
        hertz.ball_race_stiffness(0.008, 0.0335, 0.0, 0.515, 0.49, STEEL_E, STEEL_NU)


def test_timoshenko_goodier_coefficient_table():
    # a = m (3 Q R / E')^(1/3), b = n (...)^(1/3), cos(theta) = (B - A)/(A + B) -- the classical table
    tg = hertz.reference_data()["timoshenko_goodier"]
    Ep = hertz.effective_modulus_Pa(STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    for th, m, n in zip(tg["theta_deg"], tg["m"], tg["n"]):
        c = math.cos(math.radians(th))
        cx, cy = 1.0 + c, 1.0 - c  # curvature sums (1/m) in the two principal planes
        r = hertz.point_contact(50.0, 1.0 / cx, 1.0 / cy, 1e15, 1e15, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
        scale = (3.0 * 50.0 / (cx + cy) / Ep) ** (1.0 / 3.0)
        assert r.a_m / scale == pytest.approx(m, rel=0.01), th
        assert r.b_m / scale == pytest.approx(n, rel=0.01), th


def test_roller_clutch_pressures_from_geometry_fixed_by_first_case():
    # The reference prints loads, pressures and max-shear depths but no geometry. Fix the contact
    # length and the two effective radii from the first load case (depth = 0.786 b, inner contact);
    # the second load case is then an independent check of the line-contact solution.
    rc = hertz.reference_data()["roller_clutch"]
    Ep = hertz.effective_modulus_Pa(STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    Q1, Q2 = rc["roller_load_N"]
    b1 = rc["depth_max_shear_mm"][0] * 1e-3 / hertz.LINE_SHEAR_DEPTH_RATIO
    w1 = math.pi * rc["p_inner_MPa"][0] * 1e6 * b1 / 2.0
    length = Q1 / w1
    R_in = math.pi * Ep * b1**2 / (8.0 * w1)
    b_out = 2.0 * w1 / (math.pi * rc["p_outer_MPa"][0] * 1e6)
    R_out = math.pi * Ep * b_out**2 / (8.0 * w1)
    inner = hertz.line_contact(Q2, length, R_in, 1e12, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    outer = hertz.line_contact(Q2, length, R_out, 1e12, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    assert inner.p_max_Pa / 1e6 == pytest.approx(rc["p_inner_MPa"][1], rel=0.002)
    assert outer.p_max_Pa / 1e6 == pytest.approx(rc["p_outer_MPa"][1], rel=0.002)
    # the printed depths grow 1.46x for a sqrt(load) factor of 1.44: ~1 % off Hertz scaling
    assert inner.depth_max_shear_m * 1e3 == pytest.approx(rc["depth_max_shear_mm"][1], rel=0.015)
    # the first case is reproduced by construction, and the geometry is a plausible clutch
    first = hertz.line_contact(Q1, length, R_in, 1e12, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    assert first.p_max_Pa / 1e6 == pytest.approx(rc["p_inner_MPa"][0], rel=1e-9)
    assert 0.005 < length < 0.05 and 0.002 < R_in < R_out < 0.02


@pytest.mark.parametrize("name", ["6204", "6205", "6206"])
def test_iso76_contact_stress_at_static_rating(name):
    # ISO 76: at Fr = C0r the most heavily loaded ball (Q = 5 C0r / Z) presses the inner raceway
    # (groove 0.52 Dw; outer 0.53 Dw) with 4200 MPa at the contact centre (E = 207 GPa, nu = 0.3).
    iso = hertz.reference_data()["iso76"]
    b = kin.bearing(name)
    E, nu = iso["youngs_modulus_Pa"], iso["poisson"]
    Q = iso["stribeck_factor"] * b.static_rating_N / b.balls
    D = b.ball_diameter_m
    (rxi, ryi), (rxo, ryo) = hertz.race_radii_m(D, b.pitch_diameter_m, 0.0, iso["inner_groove_radius_ratio"],
                                                iso["outer_groove_radius_ratio"])
    inner = hertz.point_contact(Q, D / 2, D / 2, rxi, ryi, E, nu, E, nu)
    outer = hertz.point_contact(Q, D / 2, D / 2, rxo, ryo, E, nu, E, nu)
    assert inner.p_max_Pa / 1e6 == pytest.approx(iso["contact_stress_MPa"], rel=0.01)
    assert outer.p_max_Pa < inner.p_max_Pa  # the inner contact is the most heavily stressed


def test_static_safety_factor_follows_the_load_exponent_of_the_contact():
    # ISO 76: roller bearings 4000 MPa, ball bearings 4200 MPa at C0; a line contact's load grows as p^2, a point
    # contact's as p^3 (fixed geometry), so doubling the load of a line contact at the limit gives s0 = 1/2
    limits = hertz.iso76_limits()
    assert (limits["roller_MPa"], limits["ball_MPa"], limits["self_aligning_ball_MPa"]) == (4000.0, 4200.0, 4600.0)
    line = hertz.line_contact(1.0e4, 0.02, 0.005, 1e12, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    doubled = hertz.line_contact(2.0e4, 0.02, 0.005, 1e12, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    ratio = hertz.static_safety_factor(line.p_max_Pa) / hertz.static_safety_factor(doubled.p_max_Pa)
    assert ratio == pytest.approx(2.0, rel=1e-12)
    ball = hertz.point_contact(1.0e3, 0.005, 0.005, 1e12, 1e12, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    ball8 = hertz.point_contact(8.0e3, 0.005, 0.005, 1e12, 1e12, STEEL_E, STEEL_NU, STEEL_E, STEEL_NU)
    assert hertz.static_safety_factor(ball.p_max_Pa, "ball") / hertz.static_safety_factor(ball8.p_max_Pa, "ball") == \
        pytest.approx(8.0, rel=1e-9)
    assert hertz.static_safety_factor(4000e6) == pytest.approx(1.0)
    with pytest.raises(InputError, match="kind"):
        hertz.static_safety_factor(4000e6, "needle")
