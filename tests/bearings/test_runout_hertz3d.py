"""3-D Hertz model: the published first-order frequency table for outer-ring rotation (reference
sec. 3, Table 2, standard model of Table 1), the linear limit against the 2-D model, second-order
lines that grow with the amplitude squared, and the force balance at every step."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from scipy.optimize import fsolve

from quenchsim.bearings.runout import parse_case, run
from quenchsim.bearings.runout.analysis import simulate, spectra_and_peaks
from quenchsim.bearings.runout.excitation import excitation
from quenchsim.bearings.runout.hertz3d import hertz_constant_N_m15

Z = 8
BASE = {
    "model": "hertz3d",
    "bearing": {"pitch_diameter_mm": 7.0, "ball_diameter_mm": 1.0, "balls": Z, "radial_clearance_um": 10.0,
                "youngs_modulus_Pa": 2.08e11, "poisson": 0.3},
    "operation": {"rotating": "outer", "speed_rpm": 5400, "axial_load_N": 20.0, "revolutions": 72, "samples": 4096},
}
AMP_UM = 0.01


def _case(model="hertz3d", **extra):
    data = copy.deepcopy(BASE)
    data["model"] = model
    data.update(extra)
    return parse_case(data)


def _peaks(case):
    tr = simulate(case)
    spectra, peaks, f = spectra_and_peaks(case, tr)
    return tr, spectra, peaks, f


def _at(peaks, direction, freq, tol_hz):
    return [p for p in peaks if p.direction == direction and abs(abs(p.frequency_hz) - freq) < tol_hz]


def _check_rows(case, peaks, radial_hz, axial_hz):
    """Lines in x, y exactly at radial_hz, in z (axial) exactly at axial_hz, nothing else above 1 %
    of the strongest line (first-order table; nonlinear lines are smaller, tested separately)."""
    tol = 0.3 / case.duration_s
    strongest = max(p.amplitude_pp_m for p in peaks)
    big = [p for p in peaks if p.amplitude_pp_m > 0.01 * strongest]
    for d in ("x", "y"):
        for f in radial_hz:
            assert len(_at(big, d, f, tol)) == 1, (d, f, [(p.direction, p.frequency_hz) for p in big])
        assert len([p for p in big if p.direction == d]) == len(radial_hz)
    for f in axial_hz:
        assert len(_at(big, "axial", f, tol)) == 1, ("axial", f, [(p.direction, p.frequency_hz) for p in big])
    assert len([p for p in big if p.direction == "axial"]) == len(axial_hz)


@pytest.mark.parametrize("n", [1, 2])
def test_inner_stationary_nZ_axial_only(n):
    case = _case(waviness=[{"part": "inner", "order": n * Z, "amplitude_um_pp": AMP_UM}])
    _, _, peaks, f = _peaks(case)
    _check_rows(case, peaks, [], [n * f.ball_pass_inner_hz])  # n f_i (ball-pass, = nZ f_c)


@pytest.mark.parametrize("n", [1, 2])
@pytest.mark.parametrize("sign", [-1, 1])
def test_inner_stationary_nZ_pm1_radial_only(n, sign):
    case = _case(waviness=[{"part": "inner", "order": n * Z + sign, "amplitude_um_pp": AMP_UM}])
    _, _, peaks, f = _peaks(case)
    _check_rows(case, peaks, [n * f.ball_pass_inner_hz], [])
    line = _at(peaks, "radial", n * f.ball_pass_inner_hz, 0.3 / case.duration_s)[0]
    assert line.amplitude_pp_m == pytest.approx(AMP_UM * 1e-6, rel=2e-3)


@pytest.mark.parametrize("n", [1, 2])
def test_outer_rotating_nZ_axial_only(n):
    case = _case(waviness=[{"part": "outer", "order": n * Z, "amplitude_um_pp": AMP_UM}])
    _, _, peaks, f = _peaks(case)
    _check_rows(case, peaks, [], [n * f.ball_pass_outer_hz])  # n f_o


@pytest.mark.parametrize("n", [1, 2])
@pytest.mark.parametrize("sign", [-1, 1])
def test_outer_rotating_nZ_pm1_radial_at_nfo_pm_fr(n, sign):
    case = _case(waviness=[{"part": "outer", "order": n * Z + sign, "amplitude_um_pp": AMP_UM}])
    _, _, peaks, f = _peaks(case)
    expected = n * f.ball_pass_outer_hz + sign * case.speed_hz
    _check_rows(case, peaks, [expected], [])
    line = _at(peaks, "radial", expected, 0.3 / case.duration_s)[0]
    assert line.source == f"{n * Z} f_o {'+' if sign > 0 else '-'} f_r"


@pytest.mark.parametrize("n", [1, 2])
def test_ball_2n_radial_2nfb_pm_fc_axial_2nfb(n):
    """The reference prints this row as 2n f_o -+ f_c; with f_o its outer ball-pass frequency that
    is not a ball-waviness frequency (a ball of order 2n modulates its diameter at 2n f_b). The
    lines sit at 2n f_b -+ f_c (x, y) and 2n f_b (z), as the sec. 2 table states for the same
    mechanism; for this bearing 2n f_b and 2n f_o differ by 1.6 % (several FFT bins)."""
    case = _case(waviness=[{"part": "ball", "ball": 2, "order": 2 * n, "amplitude_um_pp": AMP_UM}])
    _, _, peaks, f = _peaks(case)
    fb, fc = f.ball_spin_hz, f.cage_hz
    _check_rows(case, peaks, [2 * n * fb - fc, 2 * n * fb + fc], [2 * n * fb])
    assert abs(2 * n * fb - 2 * n * f.ball_pass_outer_hz) > 5.0 / case.duration_s


def test_all_first_order_waviness_is_exactly_linear():
    """Z-1, Z, Z+1 lobes on both rings: at Z equally spaced balls these alias to a rigid shift
    plus a uniform approach, so every ball carries the same load and the Hertz model's orbit equals
    the linear model's to rounding (the benchmark case of sec. 3)."""
    w = [{"part": p, "order": o, "amplitude_um_pp": 0.02} for p in ("inner", "outer") for o in (Z - 1, Z, Z + 1)]
    h = simulate(_case(waviness=w))
    lin = simulate(_case(model="linear2d", waviness=w))
    np.testing.assert_allclose(h.x_m, lin.x_m, rtol=0, atol=1e-18)
    np.testing.assert_allclose(h.y_m, lin.y_m, rtol=0, atol=1e-18)
    loads = h.load_N
    np.testing.assert_allclose(loads, np.broadcast_to(loads[:, :1], loads.shape), rtol=1e-9)


def _first_order_lines_and_nrro(model, amp_um):
    w = [{"part": "inner", "order": 9, "amplitude_um_pp": amp_um},
         {"part": "outer", "order": 7, "amplitude_um_pp": amp_um},
         {"part": "inner", "order": 4, "amplitude_um_pp": amp_um},
         {"part": "outer", "order": 3, "amplitude_um_pp": amp_um}]
    result = run(_case(model=model, waviness=w))
    f = result.frequencies
    tol = 0.3 / result.case.duration_s
    lines = (f.ball_pass_inner_hz, f.ball_pass_outer_hz - result.case.speed_hz)
    return [_at(result.peaks, "radial", fl, tol)[0].amplitude_pp_m for fl in lines], result.nrro_pp_m["radial"]


def test_linear_limit_first_order_radial_nrro_equals_linear_model():
    """Waviness with first-order lines (inner 9, outer 7 lobes) plus nonlinear partners (inner 4,
    outer 3 lobes: no first-order line, but unequal ball loads). The 3-D model's first-order radial
    lines equal the linear model's (= the waviness p-p, ratio 1); its total radial NRRO exceeds the
    linear one by nonlinear lines, an excess that shrinks in proportion to the amplitude."""
    excess = []
    for amp in (0.04, 0.01):
        h, nrro_h = _first_order_lines_and_nrro("hertz3d", amp)
        lin, nrro_lin = _first_order_lines_and_nrro("linear2d", amp)
        for a_h, a_l in zip(h, lin):
            assert a_l == pytest.approx(amp * 1e-6, rel=2e-3)
            assert a_h == pytest.approx(a_l, rel=1e-6)
        excess.append(nrro_h / nrro_lin - 1.0)
    assert 0.0 < excess[1] < 1e-3
    assert excess[0] / excess[1] == pytest.approx(4.0, rel=0.1)


@pytest.mark.parametrize("waviness, direction", [
    ([{"part": "inner", "order": 4}], "axial"),                                   # 8/2: j = 2 of nZ/j
    ([{"part": "inner", "order": 4}, {"part": "inner", "order": 5}], "radial"),  # 4 + 5 = nZ + 1
])
def test_second_order_line_scales_with_amplitude_squared(waviness, direction):
    amps = []
    for amp in (0.01, 0.02):
        w = [dict(x, amplitude_um_pp=amp) for x in waviness]
        case = _case(waviness=w)
        _, _, peaks, f = _peaks(case)
        line = _at(peaks, direction, Z * f.cage_hz, 0.3 / case.duration_s)
        assert len(line) == 1
        amps.append(line[0].amplitude_pp_m)
        # the linear model has no such line at all
        _, _, lin_peaks, _ = _peaks(_case(model="linear2d", waviness=w))
        assert not [p for p in lin_peaks if p.direction == direction]
    assert amps[1] / amps[0] == pytest.approx(4.0, rel=1e-2)


def test_equilibrium_satisfies_force_balance_independently_solved():
    """Re-solve a few steps with scipy's fsolve on the reference's three balance equations."""
    w = [{"part": "inner", "order": 3, "amplitude_um_pp": 0.3}, {"part": "outer", "order": 9, "amplitude_um_pp": 0.2},
         {"part": "ball", "ball": 1, "order": 2, "amplitude_um_pp": 0.2}]
    case = _case(waviness=w, ball_diameter_deviation=[{"ball": 4, "deviation_um": 0.1}])
    tr = simulate(case)
    exc = excitation(case)
    K = hertz_constant_N_m15(case)
    a = case.contact_angle_rad
    for i in (0, 1000, 3001):
        th = exc.ball_angle_rad[i]
        e = exc.race_m[i] * math.cos(a) + exc.ball_m[i]

        def balance(u, th=th, e=e):
            d = e - (u[0] * np.cos(th) + u[1] * np.sin(th)) * math.cos(a) + u[2] * 1e-6 * math.sin(a)
            q = K * np.maximum(d, 0.0) ** 1.5
            return [q @ np.cos(th) * math.cos(a), q @ np.sin(th) * math.cos(a), q.sum() * math.sin(a) - 20.0]

        guess = [0.0, 0.0, tr.z_m[i] * 1e6 * 1.01]
        x, y, zz = fsolve(lambda u: balance([u[0] * 1e-9, u[1] * 1e-9, u[2]]), [0.0, 0.0, guess[2]], xtol=1e-13)
        assert x * 1e-9 == pytest.approx(tr.x_m[i], abs=1e-14)
        assert y * 1e-9 == pytest.approx(tr.y_m[i], abs=1e-14)
        assert zz * 1e-6 == pytest.approx(tr.z_m[i], rel=1e-9)


def test_balls_that_unload_carry_nothing_and_balance_holds():
    """A ball 3 um larger than the others under 20 N (preload approach ~1.4 um): the balls
    opposite it lose contact at times; the equilibrium still balances with those balls unloaded."""
    case = _case(ball_diameter_deviation=[{"ball": 0, "deviation_um": 3.0}],
                 waviness=[{"part": "outer", "order": 5, "amplitude_um_pp": 0.5}])
    tr = simulate(case)
    th = excitation(case).ball_angle_rad
    a = case.contact_angle_rad
    assert (tr.load_N == 0.0).any(axis=1).mean() > 0.3   # a ball unloaded in a good part of the steps
    radial = np.hypot((tr.load_N * np.cos(th)).sum(axis=1), (tr.load_N * np.sin(th)).sum(axis=1)) * math.cos(a)
    axial = tr.load_N.sum(axis=1) * math.sin(a)
    # Newton stops on a 1e-15 m step: force residual ~ contact stiffness (~5e6 N/m) x 1e-15 m ~ 5e-9 N
    assert radial.max() < 1e-9 * case.axial_load_N
    np.testing.assert_allclose(axial, case.axial_load_N, rtol=1e-9)
