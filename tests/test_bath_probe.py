"""quenchsim.bath.probe: the ISO 9950 probe quench through the thermal solver, and its helpers."""

import math

import numpy as np
import pytest

from quenchsim.bath import boundary_htc, parse_bath
from quenchsim.bath.outline import ring_section_points
from quenchsim.bath.probe import iso9950_probe, time_to
from quenchsim.thermal import SurfaceTemperatureHTC
from reference_cases import case_a_bath_spec


def test_time_to_interpolates_linearly_and_says_never():
    t = np.array([0.0, 1.0, 2.0])
    T = np.array([850.0, 650.0, 450.0])
    assert time_to(t, T, 500.0) == pytest.approx(1.75)
    assert time_to(t, T, 850.0) == 0.0
    assert math.isnan(time_to(t, T, 100.0))


def test_steady_htc_is_the_curves_at_any_time():
    points = ring_section_points(0.2183, 0.301, 0.173, chamfer_m=0.002, spacing_m=8e-3)
    curves = boundary_htc(parse_bath(case_a_bath_spec("1")), points)
    h = SurfaceTemperatureHTC(curves)
    T = np.full(len(points), 700.0)
    assert np.array_equal(h(T, 0.0), curves(T)) and np.array_equal(h(T, 50.0), curves(T))
    assert h.ambient_C is curves.ambient_C


@pytest.mark.slow
def test_probe_cools_monotonically_and_reports_consistent_rates():
    p = iso9950_probe(size_m=4e-3, surface_size_m=1.5e-3, t_end_s=60.0)
    assert np.all(np.diff(p["T_centre_C"]) <= 1e-9)
    assert p["t_to_600C_s"] < p["t_to_400C_s"] < p["t_to_200C_s"]
    assert p["CRmax_C_s"] == pytest.approx(p["rate_C_s"].max())
