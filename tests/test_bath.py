"""Bath model: public API, bad inputs, the interpolation of BoundaryHTC, air cooling."""

import numpy as np
import pytest

from quenchsim.bath import BoundaryHTC, air_htc, boundary_htc, parse_bath
from quenchsim.bath.outline import probe_points, ring_section_points
from reference_cases import case_a_bath_spec
from quenchsim.errors import InputError

RING_A = ring_section_points(0.2183, 0.301, 0.173, chamfer_m=0.002, spacing_m=4e-3)


def spec(**changes):
    s = case_a_bath_spec("1")
    s.update(changes)
    return s


def test_api_shapes_and_interpolation():
    cfg = parse_bath(spec())
    htc = boundary_htc(cfg, RING_A)
    assert isinstance(htc, BoundaryHTC)
    n, m = len(RING_A), htc.T_grid_C.size
    assert htc.h_W_m2K.shape == (n, m)
    assert htc.ambient_C.shape == htc.velocity_m_s.shape == htc.segment.shape == (n,)
    assert np.all(htc.ambient_C == 60.0)
    # on grid nodes the interpolation returns the stored values; between them it is linear
    j = 100
    assert np.allclose(htc(np.full(n, htc.T_grid_C[j])), htc.h_W_m2K[:, j])
    mid = 0.5 * (htc.T_grid_C[j] + htc.T_grid_C[j + 1])
    assert np.allclose(htc(np.full(n, mid)), 0.5 * (htc.h_W_m2K[:, j] + htc.h_W_m2K[:, j + 1]))
    # clamped outside the grid
    assert np.allclose(htc(np.full(n, 5000.0)), htc.h_W_m2K[:, -1])
    assert np.allclose(htc(np.full(n, -40.0)), htc.h_W_m2K[:, 0])
    assert np.all(htc.h_W_m2K > 0)


@pytest.mark.parametrize("changes, field", [
    ({"od_jet_speed_mm_s": -1.0}, "quench.bath.od_jet_speed_mm_s"),
    ({"id_jet_speed_mm_s": -5.0}, "quench.bath.id_jet_speed_mm_s"),
    ({"oil_temperature_C": 400.0}, "quench.bath.oil_temperature_C"),
    ({"quenchant": "no_such_oil"}, "quench.bath.quenchant"),
    ({"quenchant": "air"}, "quench.bath.quenchant"),
    ({"rotation_rpm": -11.0}, "quench.bath.rotation_rpm"),
    ({"turntable_open_fraction": 1.5}, "quench.bath.turntable_open_fraction"),
])
def test_bad_inputs_name_the_field(changes, field):
    with pytest.raises(InputError) as err:
        parse_bath(spec(**changes))
    assert err.value.field == field
    assert str(err.value).startswith(field)


def nozzle_spec():
    """Case A's bath with an explicit nozzles table (instead of the reference layout file)."""
    s = spec()
    del s["layout"]
    s["nozzles"] = {"id": {"diameter_mm": 8.0, "count": 8, "standoff_mm": 60.0, "height_mm": 86.5},
                    "od_upper": {"diameter_mm": 10.0, "count": 12, "standoff_mm": 100.0, "height_mm": 129.75}}
    return s


def test_explicit_nozzles_equal_the_layout_file():
    s = nozzle_spec()
    s["nozzles"]["od_lower"] = {"diameter_mm": 10.0, "count": 12, "standoff_mm": 100.0, "height_mm": 43.25,
                                "inclination_deg": 15.0}
    assert np.allclose(boundary_htc(parse_bath(s), RING_A).h_W_m2K, boundary_htc(parse_bath(spec()), RING_A).h_W_m2K)


def test_bad_nozzle_row():
    s = nozzle_spec()
    s["nozzles"]["od_upper"]["diameter_mm"] = 0.0
    with pytest.raises(InputError, match="nozzles.od_upper.diameter_mm"):
        parse_bath(s)
    s = nozzle_spec()
    s["nozzles"]["od_upper"]["count"] = 2.5
    with pytest.raises(InputError, match="nozzles.od_upper.count"):
        parse_bath(s)
    s = nozzle_spec()
    s["nozzles"]["sideways"] = dict(s["nozzles"]["od_upper"])
    with pytest.raises(InputError, match="nozzles.sideways.side"):
        parse_bath(s)
    s = spec()
    s["layout"] = "reference_nozzles.toml"
    with pytest.raises(InputError, match="quench.bath.layout"):
        parse_bath(s)


def test_oil_boiling_point_message():
    with pytest.raises(InputError, match="below the boiling point"):
        parse_bath(spec(oil_temperature_C=343.0))


def test_air_htc_radiation_and_convection():
    pts = probe_points()
    air = air_htc(pts, 25.0, 0.8)
    h = air(np.full(len(pts), 800.0))
    Ts, Ta = 800 + 273.15, 25 + 273.15
    h_rad = 0.8 * 5.670374419e-8 * (Ts**4 - Ta**4) / (Ts - Ta)
    assert np.all(h > h_rad) and np.all(h < h_rad + 40.0)  # natural convection in air is 5-25 W/m2K
    with pytest.raises(InputError, match="emissivity"):
        air_htc(pts, 25.0, 1.5)


def test_slope_is_the_derivative_of_the_interpolant():
    htc = boundary_htc(parse_bath(spec()), RING_A)
    n = len(RING_A)
    T = np.full(n, 553.3)
    eps = 1e-4
    numeric = (htc(T + eps) - htc(T - eps)) / (2 * eps)
    assert np.allclose(htc.slope(T), numeric, rtol=1e-6, atol=1e-6)
    assert np.all(htc.slope(np.full(n, 5000.0)) == 0.0)
