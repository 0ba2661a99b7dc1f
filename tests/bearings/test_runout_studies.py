"""Run-out studies: the waviness-order rule of the 2-D table for every Z = 3..20 and order 1..20,
ball diameter differences adjacent vs spread, all balls wavy with phase differences, unequal
ball spacing against the axial load."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from quenchsim.bearings.runout import studies


def test_frequency_map_rule_for_Z_3_to_20_and_orders_to_20():
    """Inner rotating (sec. 2): inner order l -> radial iff l = nZ +- 1 (at l f_i +- f_c), axial iff
    l = nZ; outer order l -> radial iff l = nZ +- 1 with n >= 1 (at nZ f_c), axial iff l = nZ."""
    base = copy.deepcopy(studies.STANDARD_3D)
    del base["bearing"]["radial_clearance_um"]
    base["bearing"]["contact_angle_deg"] = 25.0
    base["operation"].update(rotating="inner", revolutions=8, samples=512)
    records = studies.frequency_map(base, range(3, 21), range(1, 21), parts=("inner", "outer"))
    found = {(r.balls, r.part, r.order, r.direction): r for r in records}
    assert len(found) == len(records)  # at most one line per direction
    for z in range(3, 21):
        for order in range(1, 21):
            n_radial = (order + 1) // z if (order + 1) % z == 0 else (order - 1) // z if (order - 1) % z == 0 else None
            for part in ("inner", "outer"):
                radial = found.get((z, part, order, "radial"))
                axial = found.get((z, part, order, "axial"))
                want_radial = n_radial is not None and not (part == "outer" and n_radial == 0)
                assert (radial is not None) == want_radial, (z, part, order)
                assert (axial is not None) == (order % z == 0), (z, part, order)
                if radial is not None:
                    assert radial.amplitude_ratio == pytest.approx(1.0, rel=5e-3)
                    if part == "outer":
                        assert radial.source == f"{n_radial * z} f_c"


def test_diameter_differences_adjacent_vs_spread_match_closed_form():
    rows = studies.diameter_difference_study(studies.BEARING_695, 0.1, counts=(1, 2, 3), models=("linear2d",))
    for row in rows:
        assert row["linear2d_radial_um"] == pytest.approx(row["linear_closed_form_um"], rel=1e-3, abs=1e-9)
    by = {(r["balls_larger"], r["placement"]): r["linear2d_radial_um"] for r in rows}
    assert by[(2, "adjacent")] > by[(1, "adjacent")] > by[(3, "spread")]
    assert by[(2, "spread")] < 1e-9  # two opposite balls: no radial run-out


def test_all_balls_wavy_phase_patterns_add_as_phasors():
    amp = 0.1
    rows = studies.wavy_balls_study(studies.BEARING_695, 2, amp)
    one_axial = 2.0 / 8 * amp / np.tan(np.radians(19.8))        # (2/Z) cot(alpha) per ball (sec. 2)
    one_side = 2.0 / 8 * amp                                   # each sideband of one ball: (4/Z)/2
    for r in rows:
        assert r["axial_kfb_um"] == pytest.approx(one_axial * r["sum_axial"], rel=5e-3, abs=1e-9)
        assert r["radial_kfb_minus_fc_um"] == pytest.approx(one_side * r["sum_minus"], rel=5e-3, abs=1e-9)
        assert r["radial_kfb_plus_fc_um"] == pytest.approx(one_side * r["sum_plus"], rel=5e-3, abs=1e-9)


def test_unequal_spacing_runout_grows_with_load_linear_vs_hertz():
    """Linear springs: run-out proportional to the axial load; Hertz: to the preload approach,
    i.e. ~ F^(2/3) while the contact angle is fixed."""
    base = copy.deepcopy(studies.BEARING_695)
    base["bearing"]["ball_spring_N_per_m"] = 2.0e7
    loads = np.array([4.0, 32.0])
    rows = studies.spacing_study(base, loads, {"one ball +2 deg": (8, [2.0] + [0.0] * 7)})
    lin = [r["linear2d_radial_um"] for r in rows]
    hz = [r["hertz3d_radial_um"] for r in rows]
    assert lin[1] / lin[0] == pytest.approx(8.0, rel=1e-6)
    assert hz[1] / hz[0] == pytest.approx(8.0 ** (2.0 / 3.0), rel=0.05)


def test_crown_cage_positions():
    err = studies.crown_cage_errors(8, 7)
    pos = np.array([360.0 * j / 7 + e for j, e in enumerate(err)])
    np.testing.assert_allclose(pos, 45.0 * np.arange(7))
