"""The closing step of a run (the whole part set to room temperature) adds only athermal martensite."""

import numpy as np

from quenchsim.case import case_from_dict
from quenchsim.pipeline import QuenchRun


def warm_ring() -> dict:
    """A 5 mm wall 100Cr6 ring (the peer's kinetics) whose air stage ends while it is still ~150-250 C."""
    htc = {"T_C": [0.0, 900.0], "h_W_m2K": [1500.0, 1500.0], "ambient_C": 60.0}
    return {
        "name": "warm_ring", "material": "100Cr6_furlan",
        "geometry": {"type": "rectangular", "inner_diameter_mm": 40.0, "outer_diameter_mm": 50.0,
                     "width_mm": 10.0, "chamfer_mm": 0.5},
        "mesh": {"size_mm": 2.5, "surface_size_mm": 1.25, "surface_layer_mm": 2.5},
        "process": {"austenitising_temperature_C": 850.0, "room_temperature_C": 20.0},
        "quench": {"time_s": 10.0, "htc_model": "table", "htc_table": htc},
        "air": {"time_s": 1.0, "htc_model": "table", "htc_table": {**htc, "h_W_m2K": [10.0, 10.0]}},
        "output": {"frames": 3},
        "mechanics": {"enabled": False},
        "probes": [{"name": "mid", "r_mm": 22.5, "z_mm": 5.0}],
    }


def test_closing_step_forms_martensite_but_no_diffusional_product(tmp_path, monkeypatch):
    seen = {}
    closing = QuenchRun._equilibrate_at_room_temperature

    def recorded(run):
        seen["T_C"] = run.thermal.T_qp.copy()
        seen["before"] = {p: v.copy() for p, v in run.thermal.fractions().items()}
        closing(run)
        seen["after"] = run.thermal.fractions()

    monkeypatch.setattr(QuenchRun, "_equilibrate_at_room_temperature", recorded)
    QuenchRun(case_from_dict(warm_ring()), tmp_path, progress=False).run()
    before, after = seen["before"], seen["after"]
    assert seen["T_C"].max() > 150.0 and seen["T_C"].min() < 229.0   # warm, partly below Ms: KM still to go
    for phase in ("bainite", "pearlite"):
        assert np.array_equal(after[phase], before[phase])
    assert after["martensite"].mean() > before["martensite"].mean() + 0.2
