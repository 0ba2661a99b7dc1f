"""The bath model acting on a probe-fitted library oil (issue 17 item 3): still bath, agitation, support, errors."""

import numpy as np
import pytest

from quenchsim.bath import boundary_htc, parse_bath
from quenchsim.bath.htc import still_curve_features
from quenchsim.bath.outline import probe_points, ring_section_points
from quenchsim.bath.quenchant import load_probe_quenchant
from quenchsim.errors import InputError

OIL = "astm_d6200_fast_oil"
PROBE = probe_points()
RING = ring_section_points(0.2183, 0.301, 0.173, chamfer_m=0.002, spacing_m=4e-3)


def bath(**changes):
    spec = {"quenchant": OIL, "oil_temperature_C": 60.0}
    spec.update(changes)
    return parse_bath(spec)


def test_still_bath_returns_the_oils_still_curve_on_every_open_face():
    """agitation = "still", hanging: h(T_s) is the library curve itself (to the 2 K grid's interpolation)."""
    oil = load_probe_quenchant(OIL)
    htc = boundary_htc(bath(agitation="still", support="hanging"), PROBE)
    T = htc.T_grid_C[1:]
    assert np.max(np.abs(htc.h_W_m2K[:, 1:] / oil.h(T)[None, :] - 1.0)) < 0.01
    assert np.allclose(htc.leidenfrost_C, still_curve_features(oil)[1])


def test_turntable_covers_half_the_bottom_face_and_hanging_none():
    on_table = bath(agitation="still", support="turntable", support_open_fraction=0.5)
    hanging = bath(agitation="still", support="hanging")
    bottom = RING.segment == "bottom"
    h_table, h_hang = boundary_htc(on_table, RING).h_W_m2K, boundary_htc(hanging, RING).h_W_m2K
    assert np.allclose(h_table[bottom], 0.5 * h_hang[bottom])
    assert np.allclose(h_table[~bottom], h_hang[~bottom])


def test_agitation_raises_the_collapse_temperature_and_the_convection():
    """Faster bulk oil: the vapour film collapses hotter (T_L rises monotonically), convection at 200 C rises, and h
    never falls below the still curve (the still curve is the U = 0 limit)."""
    still = boundary_htc(bath(agitation="still", support="hanging"), PROBE)
    previous = still
    for U in (0.25, 0.5, 1.0):
        htc = boundary_htc(bath(agitation_m_s=U, support="hanging"), PROBE)
        assert np.all(htc.leidenfrost_C > previous.leidenfrost_C)
        assert np.all(htc.h_W_m2K >= previous.h_W_m2K * (1.0 - 1e-9))
        j = int(np.searchsorted(htc.T_grid_C, 200.0))
        assert np.all(htc.h_W_m2K[:, j] > previous.h_W_m2K[:, j])
        previous = htc


def test_jets_act_on_a_library_oil_too():
    """The reference ring's nozzle layout with the library oil: the jet-facing OD gets more than the still curve."""
    from reference_cases import case_a_bath_spec

    spec = case_a_bath_spec("1")
    spec.update(quenchant=OIL)
    jets = boundary_htc(parse_bath(spec), RING)
    still = boundary_htc(bath(agitation="still"), RING)
    od = RING.segment == "od"
    j = int(np.searchsorted(jets.T_grid_C, 650.0))
    assert np.all(jets.h_W_m2K[od, j] > 1.5 * still.h_W_m2K[od, j])


@pytest.mark.parametrize("changes, field", [
    ({"agitation_m_s": -0.5}, "quench.bath.agitation_m_s"),
    ({"agitation": "still", "rotation_rpm": 11.0}, "quench.bath.rotation_rpm"),
    ({"agitation": "still", "nozzles": {}}, "quench.bath.nozzles"),
    ({"agitation": "still", "agitation_m_s": 0.3}, "quench.bath.agitation_m_s"),
    ({"agitation": "stirred"}, "quench.bath.agitation"),
    ({"support": "table"}, "quench.bath.support"),
    ({"support": "hanging", "support_open_fraction": 0.5}, "quench.bath.support_open_fraction"),
    ({"quenchant": "no_such_oil"}, "quench.bath.quenchant"),
    ({"liquid_properties": "air"}, "quench.bath.liquid_properties"),
    ({"quenchant": "reference_quench_oil", "liquid_properties": "reference_quench_oil"}, "quench.bath.liquid_properties"),
])
def test_bad_bath_inputs_name_the_field_and_value(changes, field):
    with pytest.raises(InputError) as err:
        bath(**changes)
    assert str(err.value).startswith(field)
    assert "\n" not in str(err.value)
