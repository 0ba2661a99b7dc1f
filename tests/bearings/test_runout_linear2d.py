"""2-D linear-spring model against the published frequency table (reference sec. 2, inner ring
rotating, outer fixed): one imperfection at a time on the 695 bearing (Table 2), the line must
appear at the predicted frequency, direction and amplitude ratio, and nowhere else."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from quenchsim.bearings.runout import parse_case, run
from quenchsim.bearings.runout.analysis import simulate, spectra_and_peaks
from quenchsim.bearings.runout.excitation import excitation

Z = 8
ALPHA = math.radians(19.8)
BASE = {
    "model": "linear2d",
    "bearing": {"pitch_diameter_mm": 9.0, "ball_diameter_mm": 2.0, "balls": Z, "contact_angle_deg": 19.8},
    "operation": {"rotating": "inner", "speed_rpm": 1800, "axial_load_N": 7.8, "revolutions": 10, "step_deg": 1.0},
}
AMP_UM = 0.1


def _run(**extra):
    data = copy.deepcopy(BASE)
    data.update(extra)
    case = parse_case(data)
    spectra, peaks, f = spectra_and_peaks(case, simulate(case))
    return case, peaks, f


def _lines(peaks, direction):
    return [p for p in peaks if p.direction == direction]


def _one_line(peaks, direction, freq, tol_hz):
    found = [p for p in _lines(peaks, direction) if abs(abs(p.frequency_hz) - freq) < tol_hz]
    assert len(found) == 1, f"{direction} line at {freq:.4g} Hz not found in {[p.frequency_hz for p in peaks]}"
    return found[0]


@pytest.mark.parametrize("n", [1, 2])
@pytest.mark.parametrize("sign", [-1, 1])
def test_inner_raceway_nZ_pm1_radial_at_nZfi_pm_fr(n, sign):
    case, peaks, f = _run(waviness=[{"part": "inner", "order": n * Z + sign, "amplitude_um_pp": AMP_UM}])
    fi, fr = f.inner_rel_cage_hz, case.speed_hz
    expected = n * Z * fi + sign * fr
    tol = 0.3 / case.duration_s
    line = _one_line(peaks, "radial", expected, tol)
    assert line.amplitude_pp_m == pytest.approx(AMP_UM * 1e-6, rel=2e-3)  # amplitude ratio 1
    assert line.source == f"{n * Z} f_i {'+' if sign > 0 else '-'} f_r"
    for d in ("x", "y"):
        assert _one_line(peaks, d, expected, tol).amplitude_pp_m == pytest.approx(AMP_UM * 1e-6, rel=5e-3)
    assert not _lines(peaks, "axial")
    assert len(_lines(peaks, "radial")) == 1


@pytest.mark.parametrize("n", [1, 2])
def test_inner_raceway_nZ_axial_at_nZfi(n):
    case, peaks, f = _run(waviness=[{"part": "inner", "order": n * Z, "amplitude_um_pp": AMP_UM}])
    line = _one_line(peaks, "axial", n * Z * f.inner_rel_cage_hz, 0.3 / case.duration_s)
    assert line.amplitude_pp_m == pytest.approx(AMP_UM * 1e-6 / math.tan(ALPHA), rel=2e-3)  # cot(alpha)
    assert line.source == f"{n * Z} f_i"
    assert not _lines(peaks, "radial") and not _lines(peaks, "x") and not _lines(peaks, "y")


@pytest.mark.parametrize("n", [1, 2])
@pytest.mark.parametrize("sign", [-1, 1])
def test_outer_raceway_nZ_pm1_radial_at_nZfc_and_whirl(n, sign):
    case, peaks, f = _run(waviness=[{"part": "outer", "order": n * Z + sign, "amplitude_um_pp": AMP_UM}])
    line = _one_line(peaks, "radial", n * Z * f.cage_hz, 0.3 / case.duration_s)
    assert line.amplitude_pp_m == pytest.approx(AMP_UM * 1e-6, rel=2e-3)
    assert line.source == f"{n * Z} f_c"
    # nZ - 1 whirls with the inner ring (forward), nZ + 1 against it (reference sec. 2)
    assert line.whirl == ("forward" if sign < 0 else "backward")
    assert not _lines(peaks, "axial")


@pytest.mark.parametrize("n", [1, 2])
def test_outer_raceway_nZ_axial_at_nZfc(n):
    case, peaks, f = _run(waviness=[{"part": "outer", "order": n * Z, "amplitude_um_pp": AMP_UM}])
    line = _one_line(peaks, "axial", n * Z * f.cage_hz, 0.3 / case.duration_s)
    assert line.amplitude_pp_m == pytest.approx(AMP_UM * 1e-6 / math.tan(ALPHA), rel=2e-3)
    assert not _lines(peaks, "radial")


def test_ball_diameter_variation_radial_at_fc_ratio_4_over_Z_no_axial():
    dev_um = 0.01  # the test bearing of Table 3
    case, peaks, f = _run(ball_diameter_deviation=[{"ball": 3, "deviation_um": dev_um}])
    line = _one_line(peaks, "radial", f.cage_hz, 0.3 / case.duration_s)
    assert line.source == "f_c" and line.whirl == "forward"
    assert line.amplitude_pp_m == pytest.approx(4.0 / Z * dev_um * 1e-6, rel=2e-3)
    assert not _lines(peaks, "axial")


@pytest.mark.parametrize("n", [1, 2])
def test_ball_waviness_2n_radial_2nfb_pm_fc_axial_2nfb(n):
    case, peaks, f = _run(waviness=[{"part": "ball", "ball": 0, "order": 2 * n, "amplitude_um_pp": AMP_UM}])
    tol = 0.3 / case.duration_s
    fb, fc = f.ball_spin_hz, f.cage_hz
    lo = _one_line(peaks, "x", 2 * n * fb - fc, tol)
    hi = _one_line(peaks, "x", 2 * n * fb + fc, tol)
    # amplitude ratio 4/Z: modulation envelope (sum of both sidebands) over the input amplitude
    assert lo.amplitude_pp_m + hi.amplitude_pp_m == pytest.approx(4.0 / Z * AMP_UM * 1e-6, rel=5e-3)
    assert lo.source == f"{2 * n} f_b - f_c" and hi.source == f"{2 * n} f_b + f_c"
    ax = _one_line(peaks, "axial", 2 * n * fb, tol)
    assert ax.amplitude_pp_m == pytest.approx(2.0 / Z / math.tan(ALPHA) * AMP_UM * 1e-6, rel=2e-3)
    assert len(_lines(peaks, "axial")) == 1 and len(_lines(peaks, "radial")) == 2


@pytest.mark.parametrize("part, order", [("inner", 3), ("outer", 5), ("inner", 12), ("ball", 3)])
def test_orders_outside_the_table_give_no_line(part, order):
    w = {"part": part, "order": order, "amplitude_um_pp": AMP_UM}
    if part == "ball":
        w["ball"] = 1
    _, peaks, _ = _run(waviness=[w])
    assert peaks == []


def test_unequal_spacing_runout_proportional_to_axial_load():
    """One ball displaced along the pitch circle: with linear springs the radial run-out is
    proportional to the preload deflection, i.e. to the axial load."""
    out = []
    for load in (5.0, 10.0, 20.0):
        data = copy.deepcopy(BASE)
        data["operation"]["axial_load_N"] = load
        data["bearing"]["ball_spring_N_per_m"] = 2.0e7
        data["ball_position_error"] = [{"ball": 0, "angle_deg": 2.0}]
        out.append(run(parse_case(data)).runout_pp_m["radial"])
    assert out[1] / out[0] == pytest.approx(2.0, rel=1e-6)
    assert out[2] / out[0] == pytest.approx(4.0, rel=1e-6)


def test_runout_independent_of_spring_constant_while_all_balls_loaded():
    res = []
    for k in (1e7, 1e8):
        data = copy.deepcopy(BASE)
        data["bearing"]["ball_spring_N_per_m"] = k
        data["waviness"] = [{"part": "inner", "order": 9, "amplitude_um_pp": AMP_UM},
                            {"part": "outer", "order": 7, "amplitude_um_pp": AMP_UM}]
        res.append(simulate(parse_case(data)).x_m)
    np.testing.assert_allclose(res[0], res[1], atol=1e-18)


@settings(max_examples=15, deadline=None)
@given(orders=st.lists(st.integers(1, 30), min_size=1, max_size=4),
       amps=st.lists(st.floats(0.001, 0.1), min_size=4, max_size=4),
       parts=st.lists(st.sampled_from(["inner", "outer"]), min_size=4, max_size=4),
       dev=st.floats(-0.1, 0.1), rotating=st.sampled_from(["inner", "outer"]))
def test_linear_model_closed_form(orders, amps, parts, dev, rotating):
    """All balls loaded, equal spacing: the free ring sits at
    x + i y = -sigma (2/Z) sum_j u_j exp(i theta_j)  and  z = (s0 - cos(a) mean(u)) / sin(a)
    (u_j: radial interference of ball j; sigma = +1 inner ring free, -1 outer ring free)."""
    data = copy.deepcopy(BASE)
    data["operation"].update(rotating=rotating, revolutions=2, step_deg=2.0)
    data["bearing"]["ball_spring_N_per_m"] = 1.0e7
    data["waviness"] = [{"part": p, "order": o, "amplitude_um_pp": a} for o, a, p in zip(orders, amps, parts)]
    data["ball_diameter_deviation"] = [{"ball": 2, "deviation_um": dev}]
    case = parse_case(data)
    exc = excitation(case)
    tr = simulate(case)
    u = exc.race_m + exc.ball_m
    sigma = 1.0 if rotating == "inner" else -1.0
    c = -sigma * 2.0 / Z * (u * np.exp(1j * exc.ball_angle_rad)).sum(axis=1)
    np.testing.assert_allclose(tr.x_m, c.real, atol=1e-16)
    np.testing.assert_allclose(tr.y_m, c.imag, atol=1e-16)
    s0 = case.axial_load_N / (Z * 0.5e7 * math.sin(ALPHA))
    np.testing.assert_allclose(tr.z_m, (s0 - math.cos(ALPHA) * u.mean(axis=1)) / math.sin(ALPHA), rtol=1e-12)


def test_excitation_of_one_inner_waviness_by_hand():
    """Inner ring turning at f_r, ball j at theta_j = 2 pi f_c t + 2 pi j / Z: the inner raceway
    seen by ball j is (A/2) cos(l (theta_j - 2 pi f_r t) - phase)."""
    data = copy.deepcopy(BASE)
    data["waviness"] = [{"part": "inner", "order": 5, "amplitude_um_pp": 0.2, "phase_deg": 30.0}]
    case = parse_case(data)
    exc = excitation(case)
    fr = 1800 / 60.0
    gamma = 2.0 * math.cos(ALPHA) / 9.0
    fc = 0.5 * (1 - gamma) * fr
    t = exc.time_s[:, None]
    theta = 2 * np.pi * fc * t + 2 * np.pi * np.arange(Z) / Z
    np.testing.assert_allclose(exc.ball_angle_rad, theta, atol=1e-12)
    np.testing.assert_allclose(exc.race_m, 0.1e-6 * np.cos(5 * (theta - 2 * np.pi * fr * t) - math.radians(30.0)),
                               atol=1e-18)


def test_ring_equilibrium_within_the_published_tolerance():
    """Reference sec. 2: |sum_j k delta_j| / k <= 1e-12 m for the free ring at every step (here with
    raceway and ball waviness, a larger ball and a displaced ball at once)."""
    data = copy.deepcopy(BASE)
    data["bearing"]["ball_spring_N_per_m"] = 2.0e7
    data["waviness"] = [{"part": "inner", "order": 9, "amplitude_um_pp": 0.2}, {"part": "outer", "order": 5, "amplitude_um_pp": 0.1},
                        {"part": "ball", "ball": 3, "order": 2, "amplitude_um_pp": 0.1}]
    data["ball_diameter_deviation"] = [{"ball": 1, "deviation_um": 0.1}]
    data["ball_position_error"] = [{"ball": 5, "angle_deg": 1.5}]
    case = parse_case(data)
    tr = simulate(case)
    th = excitation(case).ball_angle_rad
    k = 0.5 * 2.0e7
    radial = np.hypot((tr.load_N * np.cos(th)).sum(axis=1), (tr.load_N * np.sin(th)).sum(axis=1)) * math.cos(ALPHA)
    axial = tr.load_N.sum(axis=1) * math.sin(ALPHA) - case.axial_load_N
    assert np.max(radial) / k < 1e-12
    assert np.max(np.abs(axial)) / k < 1e-12
    assert tr.load_N.min() > 0.0
