"""The bath model on the project's one ISO 9950 probe model (quenchsim.fitting.probe.ProbeModel)."""

import numpy as np
import pytest

from quenchsim.bath import boundary_htc, parse_bath
from quenchsim.bath.outline import ring_section_points
from quenchsim.bath.quenchant import load_probe_quenchant
from quenchsim.fitting.probe import ProbeModel
from quenchsim.fitting.quenchant import cooling_figures
from quenchsim.thermal import SurfaceTemperatureHTC
from reference_cases import case_a_bath_spec

STEPS = np.concatenate([np.arange(0.02, 30.0, 0.02), np.arange(30.0, 50.0 + 1e-9, 0.25)])


def test_steady_htc_is_the_curves_at_any_time():
    points = ring_section_points(0.2183, 0.301, 0.173, chamfer_m=0.002, spacing_m=8e-3)
    curves = boundary_htc(parse_bath(case_a_bath_spec("1")), points)
    h = SurfaceTemperatureHTC(curves)
    T = np.full(len(points), 700.0)
    assert np.array_equal(h(T, 0.0), curves(T)) and np.array_equal(h(T, 50.0), curves(T))
    assert h.ambient_C is curves.ambient_C


def test_probe_points_are_the_solvers_cooled_facets_in_the_whole_probes_extent():
    model = ProbeModel()
    points = model.boundary_points()
    assert len(points) == model.fe.facet_r.size
    assert set(points.segment) == {"od", "bottom"}
    assert np.allclose(points.r_m[points.segment == "od"], model.spec.radius_m)
    assert np.allclose(points.z_m[points.segment == "bottom"], 0.0)
    assert points.extent.z_max_m == pytest.approx(model.spec.length_m)


def test_still_bath_of_a_library_oil_on_the_probe_gives_the_oils_own_curve():
    """The bath model's still bath (hanging, no flow) with a library oil drives the probe as the oil's table does:
    the two routes to the same h(T_s) agree within the bath grid's interpolation."""
    oil = load_probe_quenchant("astm_d6200_fast_oil")
    model = ProbeModel(bath_temperature_C=oil.bath_temperature_C)
    cfg = parse_bath({"quenchant": "astm_d6200_fast_oil", "oil_temperature_C": oil.bath_temperature_C,
                      "agitation": "still", "support": "hanging", "T_step_K": 1.0})
    via_bath = cooling_figures(*_curve(model.run(SurfaceTemperatureHTC(boundary_htc(cfg, model.boundary_points())),
                                                 STEPS)))
    via_table = cooling_figures(*_curve(model.cool(oil.T_C, oil.h_W_m2K, STEPS)))
    assert via_bath["CRmax_C_s"] == pytest.approx(via_table["CRmax_C_s"], rel=0.01)
    assert via_bath["T_CRmax_C"] == pytest.approx(via_table["T_CRmax_C"], abs=3.0)
    assert via_bath["t_to_400C_s"] == pytest.approx(via_table["t_to_400C_s"], rel=0.01)


def test_reference_oil_probe_cools_monotonically_with_consistent_figures():
    model = ProbeModel(bath_temperature_C=40.0)
    cfg = parse_bath({"quenchant": "reference_quench_oil", "oil_temperature_C": 40.0, "agitation": "still",
                      "support": "hanging"})
    curve = model.run(SurfaceTemperatureHTC(boundary_htc(cfg, model.boundary_points())), STEPS)
    assert np.all(np.diff(curve.centre_C) <= 1e-3)  # P2 start-up wiggle at the centre: < 1e-4 K
    got = cooling_figures(curve.time_s, curve.centre_C)
    assert got["t_to_600C_s"] < got["t_to_400C_s"] < got["t_to_200C_s"]
    assert got["CRmax_C_s"] == pytest.approx(np.max(-np.gradient(curve.centre_C, curve.time_s)), rel=0.02)


def _curve(c):
    return c.time_s, c.centre_C
