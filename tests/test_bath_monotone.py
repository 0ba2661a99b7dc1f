"""Monotone response: faster jets never give a lower HTC at the same surface temperature."""

import numpy as np
from hypothesis import given, settings, strategies as st

from quenchsim.bath import boundary_htc, parse_bath
from quenchsim.bath.outline import ring_section_points
from reference_cases import case_a_bath_spec

POINTS = ring_section_points(0.2183, 0.301, 0.173, chamfer_m=0.002, spacing_m=8e-3)
speed = st.floats(min_value=0.0, max_value=10000.0, allow_nan=False)   # x5 stays within the 50 m/s limit
factor = st.floats(min_value=1.0, max_value=5.0, allow_nan=False)


def curves(id_speed, od_speed, rpm=11.0):
    spec = case_a_bath_spec("1")
    spec.update(id_jet_speed_mm_s=id_speed, od_jet_speed_mm_s=od_speed, rotation_rpm=rpm, T_step_K=10.0)
    return boundary_htc(parse_bath(spec), POINTS)


@settings(max_examples=25, deadline=None)
@given(id_speed=speed, od_speed=speed, f_id=factor, f_od=factor)
def test_faster_jets_never_lower_htc(id_speed, od_speed, f_id, f_od):
    slow = curves(id_speed, od_speed)
    fast = curves(id_speed * f_id, od_speed * f_od)
    assert np.all(fast.h_W_m2K >= slow.h_W_m2K * (1 - 1e-9))
    assert np.all(fast.velocity_m_s >= slow.velocity_m_s * (1 - 1e-12))


@settings(max_examples=10, deadline=None)
@given(rpm=st.floats(min_value=0.0, max_value=60.0), f=factor)
def test_faster_rotation_never_lowers_htc(rpm, f):
    assert np.all(curves(1000.0, 5340.0, rpm * f).h_W_m2K >= curves(1000.0, 5340.0, rpm).h_W_m2K * (1 - 1e-9))
