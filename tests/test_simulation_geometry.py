"""The quench starts from the austenitised (hot, larger) section whether or not the stress is solved."""

import numpy as np
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
