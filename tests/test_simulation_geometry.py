"""The quench starts from the austenitised (hot, larger) section whether or not the stress is solved."""

import numpy as np
import pytest
from test_simulation_final_step import warm_ring

from quenchsim.case import case_from_dict
from quenchsim.pipeline import QuenchRun


def test_thermal_section_and_cooling_do_not_depend_on_solving_the_stress(tmp_path):
    thermal_only_case = warm_ring()                      # mechanics disabled, ring given annealed at 20 C
    with_stress_case = {**warm_ring(), "mechanics": {"enabled": True, "plasticity": False, "trip": False}}
    with_stress = QuenchRun(case_from_dict(with_stress_case), tmp_path / "on", progress=False)
    thermal_only = QuenchRun(case_from_dict(thermal_only_case), tmp_path / "off", progress=False)
    cold, hot = with_stress.before_mesh.p, thermal_only.section.mesh.p
    # the austenitised ring is larger than the annealed one (free thermal + structural strain, ~1 %)
    assert 1.005 < np.max(hot[0]) / np.max(cold[0]) < 1.03
    np.testing.assert_array_equal(hot, with_stress.section.mesh.p)
    t_on = with_stress.run().probe_T_C["mid"]
    t_off = thermal_only.run().probe_T_C["mid"]
    np.testing.assert_allclose(t_off, t_on, rtol=1e-12)


def test_outputs_are_on_the_final_part_at_room_temperature(tmp_path):
    """A through-hardened small ring: the HRC58 depth is measured from the final surface and never exceeds
    the final wall; the last VTK frame is the "before" section displaced to the final part; the final
    part carries no rigid axial translation (its volume centroid stays at the "before" height)."""
    import meshio

    from quenchsim.results import load

    case = warm_ring()
    case["mechanics"] = {"enabled": True, "plasticity": False, "trip": False}   # the peer steel is elastic
    case["air"] = {"time_s": 20000.0, "temperature_C": 20.0, "until_max_C": 40.0, "htc_model": "table",
                   "htc_table": {"T_C": [0.0, 900.0], "h_W_m2K": [400.0, 400.0], "ambient_C": 20.0}}
    run = QuenchRun(case_from_dict(case), tmp_path, progress=False)
    summary = run.run().summary
    assert summary["end_state"]["at_room_temperature"]
    after = summary["dimensions_mm"]["after"]
    wall_mm = 0.5 * (after["od"] - after["id"])
    depth = summary["hardness"]["depth_mm"]["HRC58_bore_mid"]
    assert summary["hardness"]["through_hardened"] and abs(depth - wall_mm) < 2e-3   # the whole final wall
    assert summary["hardness"]["through_hardened_mid"]       # which the terminal says as "through-hardened"
    traverse = load(tmp_path).hardness_traverse
    assert traverse["depth_mm"].max() <= wall_mm
    final = run.final_part.vertices()
    assert abs(run.final_part.rigid_axial_shift_m(final)) < 1e-12
    last = meshio.read(sorted(tmp_path.glob("results_*.vtu"))[-1])
    np.testing.assert_allclose(last.points[:, :2].T, run.before_mesh.p, atol=1e-15)
    np.testing.assert_allclose((last.points[:, :2] + last.point_data["displacement_m"][:, :2]).T, final, atol=1e-15)


def test_the_core_of_a_solid_bar_is_its_axis(tmp_path):
    """A solid SUJ2 bar (20 mm, oil): the summary's core hardness is the hardness on the axis at mid-length
    (the start of the "bore" traverse, which for a solid section runs from the axis), and there is no bore-side
    HRC58 depth (no bore surface to measure it from)."""
    from pathlib import Path

    import quenchsim as qs

    case_file = Path(__file__).resolve().parents[1] / "validation" / "materials" / "SUJ2_rounds" / "round_bar_oil.toml"
    case = qs.load_case(case_file, overrides={"geometry.outer_diameter_mm": 20.0, "geometry.width_mm": 40.0,
                                              "mesh.size_mm": 4.0, "mesh.surface_size_mm": 1.0})
    summary = qs.run(case, tmp_path, progress=False).summary
    traverse = qs.load_results(tmp_path).hardness_traverse
    assert summary["hardness"]["depth_mm"]["HRC58_bore_mid"] is None
    assert summary["hardness"]["core_HRC"] == pytest.approx(traverse["HRC_from_bore"][0], abs=0.05)
    # the axis, not mid-radius: the traverse from the axis reaches the core value at its start only
    assert traverse["depth_mm"][0] < 0.01
