"""Bearing kinematics: published defect-frequency factors, cage-speed identities, bad input."""

import math

import pytest

from quenchsim.bearings import kinematics as kin
from quenchsim.errors import InputError


def test_cwru_6205_published_defect_factors():
    # Case Western Reserve University bearing data centre, SKF 6205-2RS JEM, multiples of the
    # shaft speed: BPFI 5.4152, BPFO 3.5848, FTF 0.39828, "BSF" 4.7135 (= the ball defect frequency,
    # two raceway strikes per ball spin turn).
    f = kin.frequencies(kin.bearing("6205").geometry, inner_hz=1.0, outer_hz=0.0)
    assert f.ball_pass_inner_hz == pytest.approx(5.4152, rel=2e-4)
    assert f.ball_pass_outer_hz == pytest.approx(3.5848, rel=2e-4)
    assert f.cage_hz == pytest.approx(0.39828, rel=2e-4)
    assert f.ball_defect_hz == pytest.approx(4.7135, rel=2e-4)
    assert f.ball_defect_hz == pytest.approx(2.0 * f.ball_spin_hz)


def test_grease_paper_cage_speeds_6204():
    # grease-life paper: 6204 at 10000 rpm -> cage 3850 rpm (inner rotation), 6150 rpm (outer)
    g = kin.bearing("6204").geometry
    inner = kin.frequencies(g, 10000.0 / 60.0, 0.0).cage_hz * 60.0
    outer = kin.frequencies(g, 0.0, 10000.0 / 60.0).cage_hz * 60.0
    assert inner == pytest.approx(3850.0, rel=0.012)
    assert outer == pytest.approx(6150.0, rel=0.012)
    assert inner + outer == pytest.approx(10000.0)
    # K ~ 1.6: outer rotation at 10000 rpm ~ inner rotation at 16000 rpm
    assert kin.equivalent_inner_speed_factor(g) == pytest.approx(1.6, rel=0.02)


@pytest.mark.parametrize("fi, fo", [(50.0, 0.0), (0.0, 50.0), (50.0, 20.0), (50.0, -20.0), (-30.0, 0.0)])
def test_rolling_identities(fi, fo):
    g = kin.BearingGeometry(pitch_diameter_m=0.046, ball_diameter_m=0.009525, balls=9,
                            contact_angle_rad=math.radians(15.0))
    f = kin.frequencies(g, fi, fo)
    # the cage speed is the mean of the raceway contact-point speeds (pure rolling)
    r_i = (g.pitch_diameter_m - g.ball_diameter_m * math.cos(g.contact_angle_rad)) / 2.0
    r_o = (g.pitch_diameter_m + g.ball_diameter_m * math.cos(g.contact_angle_rad)) / 2.0
    assert f.cage_hz * g.pitch_diameter_m == pytest.approx((fi * r_i + fo * r_o), rel=1e-12)
    # ball-pass frequencies add up to Z times the relative ring speed
    assert f.ball_pass_inner_hz + f.ball_pass_outer_hz == pytest.approx(g.balls * abs(fi - fo), rel=1e-12)
    # no slip at the inner contact: ball surface speed = inner raceway speed relative to the cage
    assert f.ball_spin_hz * g.ball_diameter_m == pytest.approx(abs(f.inner_rel_cage_hz) * 2.0 * r_i, rel=1e-12)


def test_equivalent_speed_gives_same_cage_speed():
    g = kin.bearing("608").geometry
    K = kin.equivalent_inner_speed_factor(g)
    assert kin.frequencies(g, K * 100.0, 0.0).cage_hz == pytest.approx(kin.frequencies(g, 0.0, 100.0).cage_hz)


def test_slip_ratio():
    assert kin.roller_slip_ratio_pct(950.0, 1000.0) == pytest.approx(5.0)
    assert kin.roller_slip_ratio_pct(1000.0, 1000.0) == 0.0
    with pytest.raises(InputError):
        kin.roller_slip_ratio_pct(1.0, 0.0)


@pytest.mark.parametrize("name", ["6204", "695", "608", "6206"])
def test_table_rows_consistent(name):
    b = kin.bearing(name)
    assert b.bore_m < b.pitch_diameter_m - b.ball_diameter_m
    assert b.pitch_diameter_m + b.ball_diameter_m < b.outer_diameter_m
    # balls fit around the pitch circle
    assert b.balls * b.ball_diameter_m < math.pi * b.pitch_diameter_m
    assert b.dynamic_rating_N > 0 and b.source


def test_bad_input():
    with pytest.raises(InputError, match="bearing"):
        kin.bearing("9999")
    with pytest.raises(InputError, match="pitch_diameter_m"):
        kin.BearingGeometry(pitch_diameter_m=0.009, ball_diameter_m=0.010, balls=8)
    with pytest.raises(InputError, match="balls"):
        kin.BearingGeometry(pitch_diameter_m=0.03, ball_diameter_m=0.005, balls=0)
    with pytest.raises(InputError, match="contact_angle_rad"):
        kin.BearingGeometry(pitch_diameter_m=0.03, ball_diameter_m=0.005, balls=8, contact_angle_rad=2.0)
