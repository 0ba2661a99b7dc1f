"""DOJ internal forces (quasi-static, Hertz contacts with clearances): the paper's Eq. 12, torque balance, 6-fold
symmetry, the Hertz sphere-on-flat limit, clearance -> 0, and the paper's qualitative statements (Hayama 2001,
docs/reference/other_seed_systems.md sec. 1)."""

import dataclasses
import functools
import json
import math

import numpy as np
import pytest

from quenchsim.bearings import hertz
from quenchsim.bearings.doj import (Clearances, DOJModel, contact_stiffness, hayama_fit_stiffness, reference_case,
                                    reference_data, reference_geometry)
from quenchsim.bearings.doj.axial import axial_force_summary, friction_axial_force_N
from quenchsim.bearings.doj.geometry import scaled_reference_geometry
from quenchsim.bearings.doj.output import Revolution, harmonic_amplitude
from quenchsim.cli import main
from quenchsim.errors import InputError

GEO = reference_geometry()
TORQUE = reference_data()["conditions"]["torque_Nm"]


@functools.cache
def _revolution(case: str, angle: float, step: float, end: float = 60.0) -> Revolution:
    model = DOJModel(GEO, reference_case(case), angle, TORQUE)
    return Revolution.from_phases(model.revolution(np.arange(0.0, end + 1e-9, step)), model.p_n)


def test_ball_window_stiffness_is_the_hertz_sphere_on_flat_limit():
    e_star = GEO.youngs_modulus_Pa / (2.0 * (1.0 - GEO.poisson ** 2))  # E' / 2 for two steel bodies
    exact = 4.0 / 3.0 * e_star * 1e-6 * math.sqrt(GEO.ball_radius_mm)  # N/mm^1.5, F = (4/3) E* sqrt(R) delta^1.5
    assert contact_stiffness(GEO, reference_case("3")).window == pytest.approx(exact, rel=1e-9)


@pytest.mark.parametrize("ratio", [1.0, 2.0, 5.0, 10.0, 30.0, 100.0])
def test_paper_curve_fits_stay_within_5_percent_of_exact_hertz(ratio):
    # the paper's k, F, E fits (Eqs. 3-5) in its stiffness against exact elliptic integrals: +3.3 % at ratio 1,
    # -4.5 % at 5-7, +2.1 % at 100 (each fit alone is within ~4 %, reference notes sec. 1.2)
    e_prime = hertz.effective_modulus_Pa(GEO.youngs_modulus_Pa, GEO.poisson, GEO.youngs_modulus_Pa, GEO.poisson)
    rx, ry = 5.0, 5.0 * ratio
    exact = hertz.point_contact_stiffness(rx * 1e-3, ry * 1e-3, 1e12, 1e12, GEO.youngs_modulus_Pa, GEO.poisson,
                                          GEO.youngs_modulus_Pa, GEO.poisson) * 1e-3 ** 1.5
    assert abs(hayama_fit_stiffness(rx, ry, e_prime) / exact - 1.0) < 0.05


def test_zero_angle_without_clearance_every_ball_carries_the_eq12_load():
    model = DOJModel(GEO, reference_case("1"), 0.0, TORQUE)
    res = model.solve(0.0)
    assert np.allclose(res.p_inner_N, res.p_inner_N[0], rtol=1e-7)
    assert np.allclose(res.p_outer_N, res.p_inner_N, rtol=1e-4)  # the centring springs take ~1e-5 P_n
    assert np.abs(res.p_window_N).max() < 1e-6 * model.p_n
    assert res.f_inner_cage_N < 1e-6 * model.p_n and res.f_cage_outer_N < 1e-6 * model.p_n
    assert res.outer_race_torque_Nm == pytest.approx(TORQUE, rel=1e-4)  # the centring springs take ~2e-5 of T
    # phase does not matter
    assert model.solve(17.0, res.state).p_inner_N == pytest.approx(res.p_inner_N, rel=1e-7)
    # Eq. 12 holds for rigid bodies: the Hertz deflections turn the line of action off the ideal contact angle
    # (the flank centres are only r_g - r_b = 0.16 mm from the ball centre), so P_n is the rigid limit; the
    # deviation scales with the deflection, K^(-2/3): 1000x stiffer contacts leave 1/100 of it
    stiff = DOJModel(GEO, reference_case("1"), 0.0, TORQUE, stiffness=dataclasses.replace(
        model.k, track=model.k.track * 1e3, window=model.k.window * 1e3)).solve(0.0)
    soft_dev, stiff_dev = 1.0 - res.p_inner_N[0] / model.p_n, 1.0 - stiff.p_inner_N[0] / model.p_n
    assert 0.0 < soft_dev < 0.1
    assert soft_dev / stiff_dev == pytest.approx(100.0, rel=0.2)


def test_torque_is_transmitted_at_every_phase_without_clearance():
    rev = _revolution("1", 10.0, 15.0)
    # homokinetic: the outer race reacts the input torque (to the centring springs' 2e-4 P_n)
    assert np.abs(rev.outer_race_torque_Nm / TORQUE - 1.0).max() < 1e-4
    assert np.all(rev.p_outer_N > 0.8 * rev.p_n_N)  # every ball loaded


def test_six_fold_symmetry_and_the_6_per_rev_cage_force_with_clearance():
    rev = _revolution("3", 5.0, 5.0, end=70.0)
    shift = 12  # 60 deg
    # ball i at phase + 60 deg is ball i + 1 at phase
    np.testing.assert_allclose(rev.p_outer_N[shift:, :-1], rev.p_outer_N[:-shift, 1:], atol=1e-6 * rev.p_n_N)
    np.testing.assert_allclose(rev.f_inner_cage_N[shift:], rev.f_inner_cage_N[:-shift], atol=1e-6 * rev.p_n_N)
    f = rev.f_inner_cage_N[:shift + 1]
    assert (f.max() - f.min()) / f.mean() > 0.5  # a strong 6-per-rev wave with clearance
    clean = _revolution("1", 10.0, 15.0)
    g = clean.f_inner_cage_N
    assert (g.max() - g.min()) / g.mean() < 0.01  # almost constant without clearance


def test_several_balls_unloaded_at_10_deg_only_with_clearance():
    with_clearance = DOJModel(GEO, reference_case("3"), 10.0, TORQUE).solve(0.0)
    assert np.sum(with_clearance.p_outer_N < 1e-6 * with_clearance.p_inner_N.max()) >= 2
    assert np.isnan(with_clearance.wedge_angle_deg).any()  # undefined where a track force is zero
    without = DOJModel(GEO, reference_case("1"), 10.0, TORQUE).solve(0.0)
    assert without.p_outer_N.min() > 0.8 * DOJModel(GEO, reference_case("1"), 10.0, TORQUE).p_n


def test_results_approach_the_no_clearance_case_as_the_clearances_shrink():
    # case 3's clearances scaled towards 0 (continuation in the scale from case 1's solution), 10 deg, phase 0:
    # the largest change of a ball's outer-track force falls in proportion to the scale
    base = DOJModel(GEO, reference_case("1"), 10.0, TORQUE)
    ref = base.solve(0.0)
    state, distances = ref.state, []
    for factor in (0.001, 0.01, 0.1, 0.2, 0.4, 0.7, 1.0):
        model = DOJModel(GEO, reference_case("3").scaled(factor), 10.0, TORQUE)
        res = model.solve(0.0, state)
        state = res.state
        distances.append(np.abs(res.p_outer_N - ref.p_outer_N).max() / model.p_n)
    assert distances == sorted(distances)
    assert distances[1] / distances[0] == pytest.approx(10.0, rel=0.05)
    assert distances[0] < 0.01 and distances[-1] > 0.5
    # case 2 (tiny sphere clearances) is closer to case 1 than case 3 is
    case2 = DOJModel(GEO, reference_case("2"), 10.0, TORQUE).solve(0.0, ref.state)
    assert np.abs(case2.p_outer_N - ref.p_outer_N).max() / base.p_n < distances[-1]


def test_harmonic_amplitude_of_a_pure_sixth_order_wave():
    phase = np.arange(0.0, 361.0, 2.0)
    assert harmonic_amplitude(phase, 3.0 + 0.7 * np.cos(np.radians(6 * phase) + 0.3), 6) == pytest.approx(0.7)


@pytest.mark.parametrize(("kwargs", "field"), [({"track_mm": -0.01}, "track_mm"), ({"window_mm": -0.5}, "window_mm")])
def test_bad_clearances(kwargs, field):
    with pytest.raises(InputError, match=field):
        Clearances(**kwargs)


def test_bad_geometry_and_operating_point():
    with pytest.raises(InputError, match="cage_outer_sphere_radius_mm"):
        dataclasses.replace(GEO, cage_outer_sphere_radius_mm=40.0)
    with pytest.raises(InputError, match="operating_angle_deg"):
        DOJModel(GEO, reference_case("1"), 30.0, TORQUE)
    with pytest.raises(InputError, match="case"):
        reference_case("4")


def _cli(capsys, *argv):
    code = main(["bearings", "doj", *argv, "--json"])
    return code, capsys.readouterr()


def test_axial_force_is_zero_without_friction_and_of_order_6n_with_it():
    rev = _revolution("3", 5.0, 5.0, end=360.0)
    # straight tracks and a cylindrical bore parallel to the outer race's axis: no axial component
    assert np.abs(rev.outer_race_axial_N).max() <= 1e-12 * rev.p_n_N
    force = friction_axial_force_N(rev, 0.1)
    # first order in friction: linear in mu; the ball at psi_i drags the race the way it moves, sign(cos psi_i)
    np.testing.assert_allclose(friction_axial_force_N(rev, 0.05), 0.5 * force)
    psi = np.radians(rev.phase_deg[3] + 60.0 * np.arange(6))
    assert force[3] == pytest.approx(0.1 * np.sum(rev.p_outer_N[3] * np.sign(np.cos(psi))))
    s = axial_force_summary(rev, 0.1)
    h = s["harmonics_over_mu_p_n"]
    assert max(h[k] for k in h if int(k) % 6) < 1e-9 * max(h["6"], h["12"])   # six-fold symmetry: orders 6n only
    assert s["dominant_order"] in (6, 12) and s["frictionless_max_over_p_n"] < 1e-12
    with pytest.raises(InputError, match="friction"):
        friction_axial_force_N(rev, -0.1)


@pytest.mark.parametrize(("alpha", "pcr"), [(35.0, 27.0), (40.0, 35.0)])
def test_revolution_converges_where_the_direct_start_stalls(alpha, pcr):
    # issue 49: case 3 at 10 deg did not converge at contact angles 35 / 45 deg or a 27 mm pitch radius
    geo = dataclasses.replace(scaled_reference_geometry(pcr), track_contact_angle_deg=alpha)
    model = DOJModel(geo, reference_case("3"), 10.0, TORQUE)
    phases = model.revolution(np.arange(0.0, 60.0 + 1e-9, 4.0))
    assert max(r.residual for r in phases) < 1e-9
    assert all(abs(r.outer_race_torque_Nm / TORQUE - 1.0) < 0.05 for r in phases)


def test_scaled_geometry_keeps_the_spheres_around_the_pitch_circle():
    geo = scaled_reference_geometry(35.0)
    base = reference_geometry()
    assert geo.pitch_circle_radius_mm == 35.0
    assert geo.cage_outer_sphere_radius_mm - geo.pitch_circle_radius_mm == pytest.approx(
        base.cage_outer_sphere_radius_mm - base.pitch_circle_radius_mm)
    assert geo.pitch_circle_radius_mm - geo.inner_race_sphere_radius_mm == pytest.approx(
        base.pitch_circle_radius_mm - base.inner_race_sphere_radius_mm)


def test_doj_cli_json_and_files(capsys, tmp_path):
    code, out = _cli(capsys, "--case", "1", "--angle-deg", "10", "--phase-step-deg", "30", "--out", str(tmp_path))
    assert code == 0
    data = json.loads(out.out)
    assert data["p_n_N"] == pytest.approx(TORQUE / (6 * 0.025 * math.sin(math.radians(40.0))))
    assert data["unloaded_ball_phase_fraction"] == 0.0 and data["geometry"]["assumed"] is True
    assert data["torque_ratio_error"] < 1e-4
    assert data["axial_force"]["frictionless_max_over_p_n"] < 1e-12 and data["axial_force"]["friction"] == 0.0
    code, out = _cli(capsys, "--case", "3", "--angle-deg", "10", "--phase-step-deg", "5", "--friction", "0.1")
    axial = json.loads(out.out)["axial_force"]
    assert code == 0 and axial["friction"] == 0.1 and axial["dominant_order"] % 6 == 0
    assert axial["peak_to_peak_N"] == pytest.approx(axial["peak_to_peak_over_mu_p_n"] * 0.1 * data["p_n_N"])
    assert (tmp_path / "doj.csv").read_text().count("\n") == 14  # header + 13 phases
    assert (tmp_path / "doj.png").stat().st_size > 0


@pytest.mark.parametrize("argv", [["--angle-deg", "30"], ["--torque-Nm", "0"], ["--window-clearance-mm", "-0.5"],
                                  ["--ball-diameter-mm", "60"], ["--phase-step-deg", "0"], ["--friction", "-0.1"]])
def test_doj_cli_bad_input_exit_2(capsys, argv):
    code, out = _cli(capsys, *argv)
    assert code == 2
    assert len(out.err.strip().splitlines()) == 1
