"""The thermal solver against closed forms (the same studies tests/test_thermal_verification.py asserts on):
a long solid cylinder with a Robin boundary (series solution, Carslaw & Jaeger 7.7), a long hollow cylinder
(eigenfunction series) and the steady log profile of a hollow cylinder."""

from __future__ import annotations

from pathlib import Path
from typing import Any

TITLE = "Verification of the thermal solver (closed forms)"
SLOW = False
DT_S = (2.0, 1.0, 0.5)
ELEMENTS_ACROSS = (2, 4, 8)


def run(workdir: Path) -> dict[str, Any]:
    from quenchsim.thermal import verification as v

    solid = [v.solid_cylinder_error(24, dt) for dt in DT_S]
    euler = [v.solid_cylinder_error(24, dt, order=1) for dt in DT_S]
    return {"solid_cylinder_error_vs_dt": solid, "solid_cylinder_order_in_dt": _order(solid),
            "solid_cylinder_error_vs_dt_backward_euler": euler, "solid_cylinder_order_in_dt_backward_euler": _order(euler),
            "hollow_cylinder_error": v.hollow_cylinder_error(),
            "log_profile_error_K_vs_elements": [v.log_profile_error(n) for n in ELEMENTS_ACROSS]}


def _order(errors: list[float]) -> float:
    import math

    return math.log2(errors[-2] / errors[-1])


def page(metrics: dict[str, Any]) -> str:
    return "\n".join([
        "Errors as fractions of the initial temperature drop (transient) or in K (steady); the tests in "
        "tests/test_thermal_verification.py assert the same quantities, tests/test_energy_balance.py the energy "
        "balance with latent heat (< 1 %), the metallurgy and mechanics tests their closed forms "
        "(see materials/cct and mechanics/verification).", "",
        "| problem | result |", "|---|---|",
        "| long solid cylinder, Robin, series solution (Carslaw & Jaeger 7.7), 24 P2 elements, dt = 2 / 1 / 0.5 s, "
        "BDF2 (the run's march) | " + " / ".join(f"{e:.2e}" for e in metrics["solid_cylinder_error_vs_dt"])
        + f" (order {metrics['solid_cylinder_order_in_dt']:.2f} in dt) |",
        "| the same, backward Euler (`order=1`) | " + " / ".join(
            f"{e:.2e}" for e in metrics["solid_cylinder_error_vs_dt_backward_euler"])
        + f" (order {metrics['solid_cylinder_order_in_dt_backward_euler']:.2f}) |",
        f"| long hollow cylinder, Robin on bore and OD, eigenfunction series | {metrics['hollow_cylinder_error']:.2e} |",
        "| steady hollow cylinder, log profile, 2 / 4 / 8 elements across (K) | "
        + " / ".join(f"{e:.2e}" for e in metrics["log_profile_error_K_vs_elements"]) + " |"])
