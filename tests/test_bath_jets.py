"""Impinging jets, forced-flow critical flux and the collapse of the vapour film: each correlation against its
published form and numbers, and the bath's response to each jet's speed."""

import math

import numpy as np
import pytest

from quenchsim.bath import boundary_htc, parse_bath
from quenchsim.bath import correlations as c
from quenchsim.bath.flow import circumferential_jet_shape, local_flow
from quenchsim.bath.htc import convective_htc, critical_heat_flux, film_collapse_temperature
from quenchsim.bath.outline import ring_section_points
from quenchsim.bath.quenchant import load_oil
from quenchsim.fitting.probe import ProbeModel
from reference_cases import case_a_bath_spec

G = 9.80665
RING_A = ring_section_points(0.2183, 0.301, 0.173, chamfer_m=0.002, spacing_m=4e-3)


def test_martin_single_nozzle_formula():
    # Incropera & DeWitt sec. 7.7 (Martin 1977): Nu/Pr^0.42 = G F_1, A_r = D^2/(4 r^2),
    # G = 2 A_r^0.5 (1 - 2.2 A_r^0.5)/(1 + 0.2 (H/D - 6) A_r^0.5), F_1 = 2 Re^0.5 (1 + 0.005 Re^0.55)^0.5
    Re, Pr, r_D, H_D = 2.0e4, 0.7, 5.0, 8.0
    Ar = 1.0 / (4.0 * r_D**2)
    G_ = 2 * Ar**0.5 * (1 - 2.2 * Ar**0.5) / (1 + 0.2 * (H_D - 6) * Ar**0.5)
    F1 = 2 * Re**0.5 * (1 + 0.005 * Re**0.55) ** 0.5
    assert float(c.martin_srn_nusselt(Re, Pr, r_D, H_D)) == pytest.approx(Pr**0.42 * G_ * F1, rel=1e-12)
    # hand value: D/r = 0.2, G = 0.2 * 0.78 / 1.04 = 0.15, F_1 = 2 * 141.42 * sqrt(1 + 0.005 * 232.5) = 415.8
    assert float(c.martin_srn_geometry(r_D, H_D)) == pytest.approx(0.15, rel=1e-12)
    assert float(c.martin_reynolds_function(Re)) == pytest.approx(415.8, rel=2e-3)


def test_martin_array_formula():
    Re, Pr, Ar, H_D = 1.0e4, 2.0, 0.01, 6.0
    K = (1 + (H_D / (0.6 / Ar**0.5)) ** 6) ** -0.05
    G_ = 2 * Ar**0.5 * (1 - 2.2 * Ar**0.5) / (1 + 0.2 * (H_D - 6) * Ar**0.5)
    assert float(c.martin_arn_nusselt(Re, Pr, Ar, H_D)) == pytest.approx(Pr**0.42 * K * G_ * 0.5 * Re ** (2 / 3))


@pytest.mark.parametrize("H_D", [2.0, 6.0, 10.0, 12.0])
def test_local_shape_has_martins_disc_mean_beyond_2_5_diameters(H_D):
    """d(x^2 G)/dx = 2 x l: the disc integral of the local shape between r/D = 2.5 and x equals the change of
    x^2 G (Martin's mean), so the shape carries Martin's measured average over any annulus in his range."""
    x = np.linspace(2.5, 7.5, 20001)
    l = c.martin_srn_local_shape(x, H_D)
    integral = np.trapezoid(2 * x * l, x)
    Gm = c.martin_srn_geometry(np.array([2.5, 7.5]), H_D)
    assert integral == pytest.approx(7.5**2 * Gm[1] - 2.5**2 * Gm[0], rel=1e-6)
    # continuous at r/D = 2.5, falling outward, highest at the stagnation point
    inner = c.martin_srn_local_shape(np.array([0.0, 1.0, 2.5 - 1e-9, 2.5]), H_D)
    assert inner[2] == pytest.approx(inner[3], rel=1e-6)
    assert inner[0] > inner[1] > inner[2] and np.all(np.diff(l) < 0)


@pytest.mark.parametrize("H_D", [6.0, 7.75, 10.0, 12.0])
@pytest.mark.parametrize("Re", [6.1e4, 1.24e5])
def test_stagnation_nusselt_against_goldstein_measurements(Re, H_D):
    """The stagnation Nusselt number of the local model (Martin's level at r/D = 2.5 carried inward with Goldstein's
    shape) against Goldstein, Behbahani & Heppelmann's (1986) fit to their air-jet measurements,
    Nu_0 = Re^0.76 (24 - |H/D - 7.75|)/533 (Re 6.1e4-1.24e5, H/D 6-12): within 10 % (the model's magnitude is
    Martin's, not Goldstein's)."""
    model = float(c.martin_srn_local_shape(0.0, H_D) * c.martin_reynolds_function(Re) * 0.71**0.42)
    assert model == pytest.approx(float(c.goldstein_local_nusselt(Re, 0.0, H_D)), rel=0.10)


def test_circumferential_mean_of_the_shape():
    # on the impact line (s = 0) the mean over a pitch of 8 D is the mean of l over r/D in [0, 4]
    D, P = 0.01, 0.08
    x = (np.arange(4000) + 0.5) / 4000 * 4.0
    expected = c.martin_srn_local_shape(x, 10.0).mean()
    assert float(circumferential_jet_shape(np.array([0.0]), D, P, 10.0)[0]) == pytest.approx(expected, rel=5e-3)
    # far from the row the mean tends to the shape at the distance s (the pitch shrinks beside it)
    far = float(circumferential_jet_shape(np.array([1.0]), D, P, 10.0)[0])
    assert far == pytest.approx(float(c.martin_srn_local_shape(100.0, 10.0)), rel=0.01)


def test_od_rows_carry_martins_array_mean():
    """The reference OD rows form an array (A_r = 0.0115): the cell mean of their coefficient is Martin's array
    correlation, with the local shape only distributing it."""
    cfg = parse_bath(case_a_bath_spec("1"))
    pts = ring_section_points(0.2183, 0.301, 0.173, chamfer_m=0.0, spacing_m=0.5e-3)
    flow = local_flow(cfg, pts)
    od = (pts.segment == "od")
    i = cfg.rows.index(next(r for r in cfg.rows if r.name == "od_upper"))
    assert flow.jet_area_ratio[i] == pytest.approx(math.pi * 0.01**2 / 4 / (math.pi * 0.301 / 12 * 0.173 / 2), rel=1e-3)
    upper = od & (pts.z_m > 0.173 / 2)    # the upper row's cell: the upper half of the OD
    assert flow.jet_shape[i][upper].mean() == pytest.approx(1.0, rel=0.02)
    # the ID row (A_r = 0.0034 < 0.004) stays a single-jet row
    assert flow.jet_area_ratio[cfg.rows.index(next(r for r in cfg.rows if r.side == "id"))] == 0.0


def test_katto_kurata_formula_and_hand_value():
    rho_l, rho_v, hfg, sigma, U, l = 860.0, 5.59, 2.0e5, 0.010, 1.0, 0.05
    Gm = rho_l * U
    expected = 0.186 * Gm * hfg * (rho_v / rho_l) ** 0.559 * (sigma * rho_l / (Gm**2 * l)) ** 0.264
    got = float(c.katto_kurata_critical_heat_flux(U, l, rho_l, rho_v, hfg, sigma))
    assert got == pytest.approx(expected, rel=1e-12)
    assert got == pytest.approx(2.10e5, rel=0.01)       # 0.186 x 1.72e8 x 0.0599 x 0.1098
    assert float(c.katto_kurata_critical_heat_flux(0.0, l, rho_l, rho_v, hfg, sigma)) == 0.0
    # q_c ~ U^(1 - 2 x 0.264) = U^0.472
    assert float(c.katto_kurata_critical_heat_flux(4.0, l, rho_l, rho_v, hfg, sigma)) / got == pytest.approx(4**0.472)


def test_berenson_formula_and_oil_hand_value():
    # dT_min = 0.127 (rho_v h_fg/k_v) [g drho/(rho_l+rho_v)]^(2/3) [sigma/(g drho)]^(1/2) [mu_v/(g drho)]^(1/3)
    # (Berenson 1961; units s K/m2 . m^(2/3)/s^(4/3) . m . (m s)^(1/3) = K), with the reference oil's light end
    # (rho_v 5.59 at 343 C): 0.127 x 3.19e7 x 4.54 x 1.09e-3 x 1.06e-3 = 21.3 K. (The g of the last bracket was
    # missing until 2026-11: 45.6 K, a non-dimensional result.)
    rho_l, rho_v, hfg, kv, mu_v, sigma = 860.0, 5.59, 2.0e5, 0.035, 1.0e-5, 0.010
    drho = rho_l - rho_v
    expected = 0.127 * rho_v * hfg / kv * (G * drho / (rho_l + rho_v)) ** (2 / 3) * (sigma / (G * drho)) ** 0.5 \
        * (mu_v / (G * drho)) ** (1 / 3)
    got = c.berenson_minimum_film_superheat(rho_l, rho_v, hfg, kv, mu_v, sigma)
    assert got == pytest.approx(expected, rel=1e-12)
    assert got == pytest.approx(21.3, rel=0.01)


def test_subcooled_collapse_is_linear_in_subcooling_like_dhir_purohit():
    # Dhir & Purohit (1978): dT_min = 101 + 8 dT_sub (water, spheres): the form a + b dT_sub
    dT = c.subcooled_film_collapse_superheat(101.0, np.array([2000.0]), 25.0, 8.0 / 2000.0)
    assert float(dT[0]) == pytest.approx(101.0 + 8.0 * 25.0)
    assert float(c.subcooled_film_collapse_superheat(101.0, np.array([2000.0]), -5.0, 1e-3)[0]) == 101.0


def test_film_collapse_calibration_on_the_still_probe():
    """Declared calibration of R_c: still oil at 40 C on the ISO 9950 probe collapses at leidenfrost_still_C."""
    model = ProbeModel(bath_temperature_C=40.0)
    points = model.boundary_points()
    cfg = parse_bath({"quenchant": "reference_quench_oil", "oil_temperature_C": 40.0, "agitation": "still",
                      "support": "hanging"})
    T_L = film_collapse_temperature(cfg.liquid, local_flow(cfg, points), 40.0)
    side = np.flatnonzero(points.segment == "od")
    assert T_L[side].mean() == pytest.approx(cfg.liquid.leidenfrost_still_C, abs=1.0)


def curves(**speeds):
    spec = case_a_bath_spec("1")
    spec.update(T_step_K=5.0, **speeds)
    cfg = parse_bath(spec)
    return cfg, local_flow(cfg, RING_A), boundary_htc(cfg, RING_A)


def seg_mean(htc, seg, T):
    idx = htc.segment == seg
    return float(np.mean([np.interp(T, htc.T_grid_C, h) for h in htc.h_W_m2K[idx]]))


def test_id_jets_move_the_bore_and_od_jets_the_od():
    _, _, slow_id = curves(id_jet_speed_mm_s=540.0)
    _, _, fast_id = curves(id_jet_speed_mm_s=1440.0)
    _, _, slow_od = curves(od_jet_speed_mm_s=1470.0)
    _, _, fast_od = curves(od_jet_speed_mm_s=3280.0)
    for T in (200.0, 600.0):
        assert seg_mean(fast_id, "bore", T) > 1.3 * seg_mean(slow_id, "bore", T)     # ID jets: the bore
        assert seg_mean(fast_id, "od", T) == pytest.approx(seg_mean(slow_id, "od", T), rel=1e-9)
        assert seg_mean(fast_od, "od", T) > 1.3 * seg_mean(slow_od, "od", T)         # OD jets: the OD
        assert seg_mean(fast_od, "bore", T) == pytest.approx(seg_mean(slow_od, "bore", T), rel=1e-9)


def test_convection_scales_as_martins_reynolds_functions():
    oil = load_oil("reference_quench_oil")
    cfg1, flow1, _ = curves(od_jet_speed_mm_s=3000.0, id_jet_speed_mm_s=0.0, rotation_rpm=0.0)
    cfg2, flow2, _ = curves(od_jet_speed_mm_s=6000.0, id_jet_speed_mm_s=0.0, rotation_rpm=0.0)
    T = np.array([100.0])
    od = np.flatnonzero(RING_A.segment == "od")
    h1 = convective_htc(oil, flow1, T, 60.0)[od, 0]
    h2 = convective_htc(oil, flow2, T, 60.0)[od, 0]
    # the OD rows are an array (F_2 = 0.5 Re^(2/3)): doubled jets give 2^(2/3) = 1.587 on the forced part (natural
    # convection blended in lowers the ratio a little)
    assert np.median(h2 / h1) == pytest.approx(2 ** (2 / 3), rel=0.05)


def test_peak_and_collapse_rise_with_speed_and_subcooling():
    cfg_s, flow_s, htc_s = curves(id_jet_speed_mm_s=400.0)
    cfg_f, flow_f, htc_f = curves(id_jet_speed_mm_s=2000.0)
    bore = RING_A.segment == "bore"
    oil = cfg_s.liquid
    assert np.all(critical_heat_flux(oil, flow_f, 60.0)[bore] >= critical_heat_flux(oil, flow_s, 60.0)[bore])
    assert htc_f.leidenfrost_C[bore].mean() > htc_s.leidenfrost_C[bore].mean() + 50.0
    assert htc_f.peak_C[bore].mean() >= htc_s.peak_C[bore].mean()
    # colder oil (more subcooling) collapses the film earlier and raises the critical flux
    cold = local_flow(parse_bath(dict(case_a_bath_spec("1"), oil_temperature_C=40.0)), RING_A)
    hot = local_flow(parse_bath(dict(case_a_bath_spec("1"), oil_temperature_C=100.0)), RING_A)
    assert np.all(film_collapse_temperature(oil, cold, 40.0) > film_collapse_temperature(oil, hot, 100.0))
    assert np.all(critical_heat_flux(oil, cold, 40.0) > critical_heat_flux(oil, hot, 100.0))


def test_per_surface_htc_factor_scales_each_face_and_chamfers_by_the_geometric_mean():
    """``htc_factor`` multiplies h(T_s) of the named faces exactly; a chamfer chamfer_<a>_<b> takes sqrt(f_a f_b),
    a face not named keeps its h; the constants file's nominal factors (1) leave h unchanged."""
    base = boundary_htc(parse_bath(case_a_bath_spec("1")), RING_A)
    spec = dict(case_a_bath_spec("1"), htc_factor={"od": 0.5, "top": 2.0})
    scaled = boundary_htc(parse_bath(spec), RING_A)
    seg = RING_A.segment
    expected = {"od": 0.5, "top": 2.0, "bore": 1.0, "bottom": 1.0, "chamfer_od_top": 1.0, "chamfer_od_bottom": 0.5 ** 0.5,
                "chamfer_id_top": 2.0 ** 0.5, "chamfer_id_bottom": 1.0}
    for name, f in expected.items():
        idx = np.flatnonzero(seg == name)
        assert idx.size > 0
        np.testing.assert_allclose(scaled.h_W_m2K[idx], f * base.h_W_m2K[idx], rtol=1e-12)
    assert parse_bath(case_a_bath_spec("1")).htc_factor == {"bore": 1.0, "od": 1.0, "top": 1.0, "bottom": 1.0}


def test_htc_factor_out_of_range_is_one_line_naming_the_field():
    from quenchsim.errors import InputError

    with pytest.raises(InputError, match=r"quench\.bath\.htc_factor\.od = 0\.0: must be >= 0\.05"):
        parse_bath(dict(case_a_bath_spec("1"), htc_factor={"od": 0.0}))
