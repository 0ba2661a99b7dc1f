"""Two-way roller clutch: wedge equilibrium and geometry, Hertz inversion, Lame and the Michell series against
elasticity identities and a coarse FE, CLI and bad input."""

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from quenchsim.bearings import hertz
from quenchsim.bearings import roller_clutch as rc
from quenchsim.bearings.roller_clutch import fe
from quenchsim.cli import main
from quenchsim.errors import InputError

E, NU = 2.08e11, 0.3
GEOMETRY = rc.ClutchGeometry(rollers=10, roller_diameter_m=0.0105, roller_length_m=0.0209, bore_diameter_m=0.095,
                             outer_diameter_m=0.128, ring_width_m=0.027, free_wedge_angle_rad=math.radians(8.4),
                             E_Pa=E, nu=NU)


def test_roller_inversion_round_trips_through_hertz():
    r, L = rc.roller_from_line_contact(29812.0, 3144e6, 0.227e-3, E, NU)
    c = hertz.line_contact(29812.0, L, r, 1e12, E, NU, E, NU)
    assert c.p_max_Pa == pytest.approx(3144e6, rel=1e-9)
    assert c.depth_max_shear_m == pytest.approx(0.227e-3, rel=1e-9)


def test_two_force_roller_moment_is_the_same_from_either_contact():
    """T = n N tan(eps/2) R (bore contact) equals n N [(R - r) sin(eps) - h tan(eps/2)] (flat contact: normal force
    at lever (R - r) sin(eps) along the flat, tangential force at the flat's distance h)."""
    g = GEOMETRY
    N, eps = 20000.0, g.free_wedge_angle_rad
    R, r, h = g.bore_radius_m, g.roller_radius_m, g.cam_offset_m
    flat = g.rollers * N * ((R - r) * math.sin(eps) - h * math.tan(eps / 2.0))
    assert rc.torque_Nm(g, N, compliant=False) == pytest.approx(flat, rel=1e-12)
    assert math.cos(eps) == pytest.approx((h + r) / (R - r), rel=1e-12)


def test_wedge_opens_as_the_closed_form_derivative_says():
    """d eps / d Delta = 1 / ((R - r) tan eps) for a radial take-up Delta at the bore (h + r fixed)."""
    g = GEOMETRY
    R, r, eps = g.bore_radius_m, g.roller_radius_m, g.free_wedge_angle_rad
    d = 1e-7
    eps_d = math.acos((g.cam_offset_m + r) / (R + d - r))
    assert (eps_d - eps) / d == pytest.approx(1.0 / ((R - r) * math.tan(eps)), rel=1e-4)


def test_compliance_lowers_the_load_per_torque_and_the_inverse_is_exact():
    g = GEOMETRY
    rated, top = rc.engage(g, 1152.0), rc.engage(g, 2646.0)
    rigid = rc.engage(g, 2646.0, compliant=False)
    assert top.load_per_torque_N_per_Nm < rated.load_per_torque_N_per_Nm < rigid.load_per_torque_N_per_Nm
    assert top.wedge_angle_rad > rated.wedge_angle_rad > g.free_wedge_angle_rad
    assert rc.torque_Nm(g, top.roller_load_N) == pytest.approx(2646.0, rel=1e-9)
    eps0 = rc.free_wedge_angle_for(g, 1152.0, rated.roller_load_N)
    assert eps0 == pytest.approx(g.free_wedge_angle_rad, rel=1e-8)
    assert rc.palmgren_approach_m(1000.0, 0.01) == pytest.approx(3.84e-5 * 1000.0**0.9 / 10.0**0.8 * 1e-3, rel=1e-12)


def test_michell_series_meets_its_boundary_conditions_and_equilibrium():
    a, b, n, W, c, mu = 0.0475, 0.06, 10, 1.4e6, 2e-3, 0.08   # a wide strip: few harmonics (k <= 1900)
    ring = rc.DiscreteLoadRing(a, b, n, W, c, E, NU, mu)
    assert ring.k.max() < 1901
    p0 = 2.0 * W / (math.pi * c)
    th = np.array([0.0, 0.5 * c / a, 0.3, math.pi / n])
    f = ring.field(a, th)
    q = p0 * np.sqrt(np.clip(1.0 - (th * a / c) ** 2, 0.0, None))
    assert f.s_rr == pytest.approx(-q, abs=0.01 * p0)          # bore pressure: the Hertz strips
    assert f.s_rt == pytest.approx(-mu * q, abs=0.01 * p0)
    fo = ring.field(b, th)
    assert np.abs(fo.s_rr).max() < 1e-9 * p0                    # free outer surface, uniform reaction shear
    assert fo.s_rt == pytest.approx(np.full(4, -mu * n * W / (2 * math.pi * a) * a * a / b**2), rel=1e-9)
    # every circle carries the transmitted torque and no net force; the mean displacement is Lame's
    t = np.linspace(0.0, 2.0 * math.pi, 1907, endpoint=False)  # 1907 is prime: no harmonic aliases onto the mean
    mid = ring.field(0.053, t)
    torque = np.mean(mid.s_rt) * 2 * math.pi * 0.053**2
    assert torque == pytest.approx(-mu * W * n * a, rel=1e-6)
    fx = np.mean(mid.s_rr * np.cos(t) - mid.s_rt * np.sin(t))
    assert abs(fx) < 1e-9 * p0
    lame = rc.lame_ring(a, b, n * W / (2 * math.pi * a), E, NU)
    assert np.mean(ring.field(a, t).u_r) == pytest.approx(lame.bore_displacement_m, rel=1e-6)


def test_fe_ring_matches_lame_on_a_coarse_mesh():
    a, b, p = 0.0475, 0.064, 40e6
    mesh = fe.polar_mesh(a, b, 10, per_pitch=6, layers=6)
    out = fe.solve_ring(mesh, a, b, E, NU, lambda t: p + 0 * t, lambda t: 0 * t, 0.0, np.array([a, b, a]),
                        np.array([0.0, math.pi / 10, 1.0]))
    lame = rc.lame_ring(a, b, p, E, NU)
    assert out.u_r[[0, 2]] == pytest.approx([lame.bore_displacement_m] * 2, rel=2e-3)
    assert out.u_r[1] == pytest.approx(lame.outer_displacement_m, rel=2e-3)
    assert out.s_tt[[0, 2]] == pytest.approx([lame.bore_hoop_Pa] * 2, rel=5e-3)
    assert out.s_tt[1] == pytest.approx(lame.outer_hoop_Pa, rel=5e-3)


def test_bad_geometry_is_one_input_error():
    with pytest.raises(InputError, match="outer_diameter_m"):
        replace(GEOMETRY, outer_diameter_m=0.09)
    with pytest.raises(InputError, match="rollers"):
        replace(GEOMETRY, rollers=30)
    with pytest.raises(InputError, match="torque_Nm"):
        rc.engage(GEOMETRY, -5.0)


def test_wedge_hold_needs_tan_half_wedge_and_slips_where_the_wedge_opens_to_mu():
    hold = rc.wedge_hold(GEOMETRY, 2646.0, 0.1)
    e = rc.engage(GEOMETRY, 2646.0)
    assert hold.required_friction == pytest.approx(math.tan(e.wedge_angle_rad / 2.0), rel=1e-12)
    assert hold.margin == pytest.approx(0.1 / hold.required_friction) and hold.holds
    # at the slip load the compliant wedge angle has opened to tan(eps/2) = mu, and T = n N mu R there
    eps = rc.wedge_angle_rad(GEOMETRY, hold.slip_roller_load_N)
    assert math.tan(eps / 2.0) == pytest.approx(0.1, rel=1e-9)
    assert hold.slip_torque_Nm == pytest.approx(GEOMETRY.rollers * hold.slip_roller_load_N * 0.1
                                                * GEOMETRY.bore_radius_m, rel=1e-9)
    assert hold.slip_torque_Nm > 2646.0
    # a friction below the free wedge's tan(eps0/2) cannot hold any torque; a rigid wedge never opens
    low = rc.wedge_hold(GEOMETRY, 1152.0, 0.5 * math.tan(GEOMETRY.free_wedge_angle_rad / 2.0))
    assert not low.holds and low.slip_torque_Nm == 0.0
    assert rc.wedge_hold(GEOMETRY, 1152.0, 0.1, compliant=False).slip_torque_Nm == math.inf
    with pytest.raises(InputError, match="friction"):
        rc.wedge_hold(GEOMETRY, 1152.0, 0.0)


ARGS = ["roller-clutch", "--torque", "1152", "2646", "--rollers", "10", "--roller-diameter-mm", "10.5",
        "--roller-length-mm", "20.9", "--bore-diameter-mm", "95", "--outer-diameter-mm", "128", "--ring-width-mm",
        "27.2", "--free-wedge-angle-deg", "8.4", "--friction", "0.1"]


def test_cli_json(capsys):
    assert main(["bearings", *ARGS, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    rated, top = out["states"]
    assert top["load_per_torque_N_per_Nm"] < rated["load_per_torque_N_per_Nm"]
    assert rated["wedged"] is True and rated["outer_bore"]["p_max_MPa"] < rated["inner_flat"]["p_max_MPa"]
    assert rated["ring_discrete"]["max_hoop_MPa"] > rated["ring_lame"]["bore_hoop_MPa"]
    # ISO 76 brinelling check: s0 = (4000 MPa / p_max)^2 per contact, below 1 at the paper's maximum torque
    for state in (rated, top):
        s0 = state["static_capacity"]["safety_factor"]
        assert s0["inner_flat"] == pytest.approx((4000.0 / state["inner_flat"]["p_max_MPa"]) ** 2)
        assert s0["outer_bore"] == pytest.approx((4000.0 / state["outer_bore"]["p_max_MPa"]) ** 2)
    assert rated["static_capacity"]["brinelling"] is False and top["static_capacity"]["brinelling"] is True
    assert top["wedge_hold"]["required_friction"] > rated["wedge_hold"]["required_friction"]
    assert rated["wedge_hold"]["slip_torque_Nm"] == pytest.approx(top["wedge_hold"]["slip_torque_Nm"], rel=1e-9)


@pytest.mark.parametrize("option, value, allowed", [
    ("--torque", "-1", "in (0, 1e+07] N m"),
    ("--rollers", "1", "an integer in [2, 200]"),
    ("--free-wedge-angle-deg", "60", "in (0, 60) deg"),
    ("--outer-diameter-mm", "90", "must exceed --bore-diameter-mm = 95"),
    ("--rollers", "40", "do not fit"),
])
def test_cli_bad_input_is_one_line(option, value, allowed, capsys):
    argv = list(ARGS)
    i = argv.index(option)
    argv[i + 1] = value
    if option == "--torque":
        del argv[i + 2]
    assert main(["bearings", *argv, "--json"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"quenchsim: error: {option} = ") and allowed in err[0], err
