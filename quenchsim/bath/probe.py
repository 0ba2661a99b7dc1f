"""The ISO 9950 probe test run through the project's thermal solver: a cylinder of Inconel 600 (12.5 x 60 mm,
centre thermocouple; materials/quenchants/iso9950_probe_inconel600.toml) quenched in a still bath of the
given quenchant, with the bath model's still-oil HTC(T_s) curves. Standard: ISO 9950:1995, Industrial quenching
oils -- Determination of cooling characteristics -- Nickel-alloy probe test method.

The thermal solver is imported inside :func:`iso9950_probe` only (the bath package does not depend on it
at import time).
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from quenchsim.bath.config import parse_bath
from quenchsim.bath.htc import boundary_htc
from quenchsim.errors import SolverError


def iso9950_probe(quenchant: str = "reference_quench_oil", size_m: float = 2.0e-3, surface_size_m: float = 0.6e-3,
                  t_end_s: float = 90.0) -> dict[str, Any]:
    """Quench the ISO 9950 probe (materials/quenchants/iso9950_probe_inconel600.toml) in still oil with the
    project's thermal solver; centre temperature history and its cooling-rate figures."""
    from quenchsim.geometry.mesher import mesh_profile
    from quenchsim.geometry.profile import general_profile
    from quenchsim.materials import load_data_file, thermal_properties
    from quenchsim.geometry import boundary_points
    from quenchsim.thermal import AxisymmetricP2, NoTransformation, SurfaceTemperatureHTC, ThermalSolver

    probe = load_data_file("iso9950_probe_inconel600", "quenchants", "probe")
    R, L = 0.5 * probe["diameter_mm"], probe["length_mm"]
    prof = general_profile({"start_mm": [0.0, 0.0], "segments": [
        {"to_mm": [R, 0.0], "name": "bottom"}, {"to_mm": [R, L], "name": "od"},
        {"to_mm": [0.0, L], "name": "top"}, {"to_mm": [0.0, 0.0], "name": "axis"}]})
    section = mesh_profile(prof, size_m, surface_size_m, 3 * surface_size_m)
    cooled = np.concatenate([f for name, f in section.boundaries.items() if name != "axis"])
    fe = AxisymmetricP2(section.mesh, cooled)
    points = boundary_points(section, fe.facets, fe.facet_r, fe.facet_z, fe.facet_normals)
    cfg = parse_bath({"quenchant": quenchant, "oil_temperature_C": float(probe["oil_temperature_C"]),
                      "turntable_open_fraction": 1.0, "T_step_K": 1.0})
    t0 = time.perf_counter()
    curves = boundary_htc(cfg, points)
    build_s = time.perf_counter() - t0

    htc = SurfaceTemperatureHTC(curves)
    solver = ThermalSolver(fe, thermal_properties(probe), float(probe["start_temperature_C"]), NoTransformation(),
                           np.ones(fe.r_qp.shape))
    centre = fe.basis.probes(np.array([[0.0], [0.5 * L * 1e-3]]))
    times, T_c = [0.0], [float(probe["start_temperature_C"])]
    dt, cutbacks = 0.01, 0
    while solver.time_s < t_end_s and T_c[-1] > 150.0:
        try:
            step = solver.try_step(dt, htc)
        except SolverError:
            dt *= 0.5
            cutbacks += 1
            continue
        solver.commit(step)
        times.append(solver.time_s)
        T_c.append(float((centre @ solver.T)[0]))
        dt = min(0.25, dt * 1.2) if step.max_dT_K < 5.0 else 0.7 * dt
    t, T = np.array(times), np.array(T_c)
    rate = -np.gradient(T, t)
    i = int(np.argmax(rate))
    down = -T  # increasing for interpolation
    mid = points.segment == "od"
    j = np.flatnonzero(mid)[np.argmin(np.abs(points.z_m[mid] - 0.5 * L * 1e-3))]
    return {"time_s": t, "T_centre_C": T, "rate_C_s": rate, "CRmax_C_s": float(rate[i]), "T_CRmax_C": float(T[i]),
            "t_to_600C_s": float(np.interp(-600.0, down, t)), "t_to_400C_s": float(np.interp(-400.0, down, t)),
            "t_to_200C_s": float(np.interp(-200.0, down, t)), "CR_300C_C_s": float(np.interp(-300.0, down, rate)),
            "elements": int(section.mesh.t.shape[1]), "steps": len(times) - 1, "cutbacks": cutbacks,
            "bath_build_s": build_s, "T_grid_C": curves.T_grid_C, "h_mid_W_m2K": curves.h_W_m2K[j],
            "leidenfrost_C": float(curves.leidenfrost_C[j]), "peak_C": float(curves.peak_C[j])}


def time_to(time_s: np.ndarray, T_C: np.ndarray, T_target: float) -> float:
    """First time T falls to T_target (linear between samples); NaN if it never does."""
    below = np.flatnonzero(T_C <= T_target)
    if below.size == 0:
        return math.nan
    k = int(below[0])
    if k == 0:
        return float(time_s[0])
    t0, t1, T0, T1 = time_s[k - 1], time_s[k], T_C[k - 1], T_C[k]
    return float(t0 + (t1 - t0) * (T0 - T_target) / (T0 - T1))
