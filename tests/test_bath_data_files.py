"""The bath model's declared constants and nozzle layouts live in data files (materials/baths/) with priors the
calibration can address; a case names them, and its own keys override them."""

import numpy as np
import pytest

from quenchsim.bath import boundary_htc, parse_bath
from quenchsim.bath.outline import ring_section_points
from quenchsim.calibration.inputs import declared_priors, derived_files, free_input, used_by
from quenchsim.case import load_case
from quenchsim.errors import InputError
from reference_cases import CASE_A, case_a_bath_spec

POINTS = ring_section_points(0.2183, 0.301, 0.173, chamfer_m=0.002, spacing_m=8e-3)


def test_reference_case_reads_its_layout_and_constants():
    cfg = parse_bath(case_a_bath_spec("1"))
    rows = {r.name: r for r in cfg.rows}
    assert set(rows) == {"id", "od_upper", "od_lower"}
    assert rows["od_lower"].inclination_rad == pytest.approx(np.radians(15.0))
    assert rows["od_upper"].height_above_bottom_m(0.173) == pytest.approx(0.75 * 0.173)
    assert rows["id"].jet_speed_m_s == pytest.approx(1.0)          # condition 1's ID jet speed from the case
    assert cfg.corner_carryover == 0.3 and cfg.crossflow_up_m_s["id"] == 0.2 and cfg.bore_swirl_fraction == 0.5


def test_case_key_overrides_a_declared_constant():
    spec = case_a_bath_spec("1")
    spec["corner_carryover"] = 0.6
    assert parse_bath(spec).corner_carryover == 0.6


@pytest.mark.parametrize("change, field", [
    ({"nozzles": {"id": {"diameter_mm": 8.0, "count": 8, "standoff_mm": 60.0, "height_mm": 86.5}}},
     "quench.bath.layout"),
    ({"layout": "no_such_layout"}, "quench.bath.layout"),
    ({"constants": "reference_nozzles"}, "quench.bath.constants"),
    ({"layout": "jet_bath"}, "quench.bath.layout"),
    ({"jet_speeds": 3.0}, "quench.bath.jet_speeds"),
    ({"bore_swirl_fraction": 1.5}, "quench.bath.bore_swirl_fraction"),
])
def test_bad_bath_data_names_the_field(change, field):
    spec = case_a_bath_spec("1")
    spec.update(change)
    with pytest.raises(InputError) as err:
        parse_bath(spec)
    assert err.value.field == field


def test_row_needs_one_height():
    spec = {"quenchant": "reference_quench_oil", "oil_temperature_C": 60.0, "od_jet_speed_mm_s": 1000.0,
            "nozzles": {"od": {"diameter_mm": 10.0, "count": 4, "standoff_mm": 50.0}}}
    with pytest.raises(InputError, match="height_mm or height_fraction"):
        parse_bath(spec)
    spec["nozzles"]["od"]["height_mm"] = 30.0
    spec["nozzles"]["od"]["nozzle_angle"] = 3.0
    with pytest.raises(InputError, match="nozzles.od.nozzle_angle"):
        parse_bath(spec)


@pytest.mark.parametrize("path, field", [
    ("bath.jet_bath.flow.corner_carryover", "quench.bath.constants"),
    ("layout.reference_nozzles.nozzles.od_upper.standoff_mm", "quench.bath.layout"),
])
def test_calibration_addresses_bath_files_and_a_scaled_file_moves_the_htc(tmp_path, path, field):
    inp = free_input(path)
    assert inp.factor_bounds[0] < 1.0 < inp.factor_bounds[1]
    case = load_case(CASE_A, "1")
    assert used_by(inp, case)
    overrides = derived_files([inp], [inp.factor_bounds[1]], tmp_path)
    assert set(overrides) == {field}
    moved = load_case(CASE_A, "1", overrides)
    base_htc = boundary_htc(case.bath, POINTS)
    new_htc = boundary_htc(moved.bath, POINTS)
    assert not np.allclose(base_htc.h_W_m2K, new_htc.h_W_m2K)


def test_every_declared_bath_prior_is_found():
    paths = {inp.path for inp in declared_priors("bath", "jet_bath")}
    assert {"bath.jet_bath.flow.corner_carryover", "bath.jet_bath.flow.bore_swirl_fraction",
            "bath.jet_bath.flow.id_crossflow_up_m_s", "bath.jet_bath.flow.oil_swirl_fraction"} <= paths
    layout = {inp.path for inp in declared_priors("layout", "reference_nozzles")}
    assert "layout.reference_nozzles.nozzles.od_lower.inclination_deg" in layout
    oil = {inp.path for inp in declared_priors("quenchant", "reference_quench_oil")}
    assert "quenchant.reference_quench_oil.boiling.film_collapse_resistance_m2K_W" in oil


def test_a_case_with_default_constants_reads_them():
    """A bath case that names no constants file reads jet_bath.toml: the calibration knows it."""
    inp = free_input("bath.jet_bath.flow.corner_carryover")
    case = load_case(CASE_A, "1")
    data = case.data
    del data["quench"]["bath"]["constants"]
    assert used_by(inp, case)
