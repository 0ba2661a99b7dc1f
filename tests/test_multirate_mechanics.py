"""Multirate stepping: the rate-independent stress solver takes one step over as many thermal steps as keep the
change since its last step within ``time.mechanics_max_dT_K`` and ``time.mechanics_max_dX``.

Checked on a small SUJ2 ring held in a 250 C bath (bainite forms over ~190 thermal steps limited by
``time.max_dX`` = 0.002, a tenth of the default): with the limits at 0 every thermal step is a stress step; at the defaults the stress solver takes
about a third of the steps and ends at the same dimensions (within 1e-4 mm: 4.8e-5 mm ID at the 30 K default, below
1e-5 mm at the former 20 K) and stresses (within 0.05 MPa: 0.03 MPa at 30 K, below 0.01 MPa at 20 K); a stress step that does not converge while catching up
is split along the path between the two states; a thermal step beyond the limits is split into stress steps along
its own path."""

import numpy as np
import pytest
from test_run_resume import plastic_ring

import quenchsim as qs
from quenchsim.case import case_from_dict
from quenchsim.mechanics.solver import MechanicsSolver, StepInfo


def bainitic_ring(**time_control: float) -> dict:
    case = plastic_ring()
    case["material"] = "SUJ2"
    case["quench"]["time_s"] = 300.0
    case["quench"]["htc_table"].update(h_W_m2K=[800.0, 800.0], ambient_C=250.0)
    case["time"] = {"max_dX": 0.002, **time_control}  # many thermal steps for the stress solver to merge
    return case


def results(summary: dict) -> dict[str, float]:
    out = {f"{k}_mm": float(v) for k, v in summary["dimensions_mm"]["change"].items()}
    for direction, points in summary["residual_stress_MPa"].items():
        out.update({f"{direction}_{k}_MPa": float(v) for k, v in points.items()})
    return out


@pytest.fixture(scope="module")
def every_step(tmp_path_factory):
    case = case_from_dict(bainitic_ring(mechanics_max_dT_K=0.0, mechanics_max_dX=0.0))
    return qs.run(case, tmp_path_factory.mktemp("every_step"), progress=False).summary


def test_with_zero_limits_every_thermal_step_is_a_stress_step(every_step):
    # one stress step per committed thermal step, plus the closing step to room temperature
    assert every_step["solver"]["stress_steps"] == every_step["solver"]["steps"] + 1


def test_stress_steps_over_several_thermal_steps_end_at_the_same_part(every_step, tmp_path):
    summary = qs.run(case_from_dict(bainitic_ring()), tmp_path, progress=False).summary
    assert summary["solver"]["steps"] == every_step["solver"]["steps"]   # the thermal steps are not touched
    assert summary["solver"]["stress_steps"] < 0.5 * every_step["solver"]["steps"]
    merged, reference = results(summary), results(every_step)
    for key, value in reference.items():
        assert merged[key] == pytest.approx(value, abs=1e-4 if key.endswith("_mm") else 5e-2), key


def test_a_catch_up_step_that_does_not_converge_is_split_along_the_path(tmp_path, monkeypatch, caplog):
    """The stress solver is made to refuse any step whose temperature change exceeds 6 K while the limit lets the
    pending change grow to 15 K: catching up then needs sub-steps, and ends at the part of the same run whose
    stress steps all converge."""
    case = case_from_dict(bainitic_ring(max_dT_K=5.0, mechanics_max_dT_K=15.0))
    reference = results(qs.run(case, tmp_path / "reference", progress=False).summary)
    step, taken = MechanicsSolver.step, []

    def refusing(solver, T_C, fractions, T_prev_C, fractions_prev, *args, **kwargs):
        change = float(np.max(np.abs(np.asarray(T_C) - np.asarray(T_prev_C))))
        if change > 6.0:
            return StepInfo(False, 0, np.inf, 0, 0.0)
        taken.append(change)
        return step(solver, T_C, fractions, T_prev_C, fractions_prev, *args, **kwargs)

    monkeypatch.setattr(MechanicsSolver, "step", refusing)
    summary = qs.run(case, tmp_path / "split", progress=False).summary
    assert summary["status"] == "ok"
    assert "catching up" in caplog.text and "sub-steps of 0.25 of the change" in caplog.text
    assert max(taken) <= 6.0
    split = results(summary)
    for key, value in reference.items():
        assert split[key] == pytest.approx(value, abs=1e-4 if key.endswith("_mm") else 0.05), key


def split_ring_results(tmp_path, **time_control: float) -> tuple[dict, dict[str, float]]:
    case = plastic_ring()          # SUJ3: martensite through the small section, plasticity and TRIP
    case["time"] = dict(time_control)
    summary = qs.run(case_from_dict(case), tmp_path / "_".join(f"{k}{v:g}" for k, v in time_control.items()),
                     progress=False).summary
    return summary["solver"], results(summary)


def test_a_thermal_step_beyond_the_stress_limits_is_split_along_its_own_path(tmp_path):
    """Thermal steps of up to 80 K, stress limits of 10 K / 0.02: each thermal step is taken in as many stress steps
    as keep within the limits, with the phases the kinetics form on the step's path (martensite is not linear in
    T). The part ends within 3e-4 mm of a run whose thermal steps are 10 K (measured 2e-5 mm ID, 1.3e-4 mm OD); one
    stress step per 80 K thermal step (limits 0) ends 7e-3 mm away in ID."""
    split_solver, split = split_ring_results(tmp_path, max_dT_K=80.0, mechanics_max_dT_K=10.0)
    _, fine = split_ring_results(tmp_path, max_dT_K=10.0, mechanics_max_dT_K=10.0)
    whole_solver, whole = split_ring_results(tmp_path, max_dT_K=80.0, mechanics_max_dT_K=0.0, mechanics_max_dX=0.0)
    assert split_solver["steps"] == whole_solver["steps"] and split_solver["stress_steps"] > 3 * split_solver["steps"]
    for key in ("id_mm", "od_mm", "width_mm"):
        assert abs(split[key] - fine[key]) < 3e-4, key
    assert abs(whole["id_mm"] - fine["id_mm"]) > 10 * abs(split["id_mm"] - fine["id_mm"])
