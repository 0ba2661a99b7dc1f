"""The standard Jominy (end-quench) bar computed with quenchsim's own thermal solver.

ASTM A255 / ISO 642 geometry (25 mm x 100 mm, axisymmetric), a water jet on the end face z = 0 and still
air (convection + radiation) on the other faces; bar data and their sources in ``materials/data/jominy_bar.toml``.
The latent heat of the steel's transformations is included (the thermal solver advances the steel's
kinetics at every quadrature point). :func:`cooling_histories` returns T(t) at the hardness track (just below
the surface, at given distances from the quenched end); the kinetics fitter integrates ``advance`` along them.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import skfem
from tqdm import tqdm

from quenchsim.errors import InputError
from quenchsim.inputs.reader import read_toml
from quenchsim.materials import materials_dir, thermal_properties
from quenchsim.metallurgy import Kinetics, PhaseModel
from quenchsim.thermal import AxisymmetricP2, TableHTC, ThermalSolver
from quenchsim.thermal.steps import StepController

SIGMA_W_m2K4 = 5.670374e-8
"""Stefan-Boltzmann constant (CODATA)."""
KELVIN = 273.15
BAR_DT_START_S = 0.01
BAR_STEPS = StepController(growth=1.3, dt_max_s=5.0, max_dT_K=10.0, hold_over_limit=True)
"""The bar's steps: from 10 ms, growing 1.3x while a step changes no node by 10 K or more (else held), at most 5 s."""


@dataclass(frozen=True)
class JominyBar:
    diameter_m: float
    length_m: float
    measure_depth_m: float
    water_C: float
    air_C: float
    end_T_C: np.ndarray
    end_h_W_m2K: np.ndarray
    emissivity: float
    convection_W_m2K: float


def load_bar(path: Path | None = None) -> JominyBar:
    """The bar description (materials/data/jominy_bar.toml)."""
    path = path or materials_dir() / "data" / "jominy_bar.toml"
    raw = read_toml(path, "jominy bar")
    v = lambda key, table=raw: float(table[key]["value"])  # noqa: E731
    end, free = raw["quenched_end"], raw["free_faces"]
    return JominyBar(diameter_m=v("diameter_mm") * 1e-3, length_m=v("length_mm") * 1e-3,
                     measure_depth_m=v("measure_depth_mm") * 1e-3, water_C=v("water_C"), air_C=v("air_C"),
                     end_T_C=np.asarray(end["T_C"], float), end_h_W_m2K=np.asarray(end["h_W_m2K"], float),
                     emissivity=v("emissivity", free), convection_W_m2K=v("convection_W_m2K", free))


def air_h_W_m2K(bar: JominyBar, T_C: np.ndarray) -> np.ndarray:
    """Convection + linearised radiation: h = h_c + eps sigma (T^2 + T_inf^2)(T + T_inf), T in K."""
    T, Ta = np.asarray(T_C, float) + KELVIN, bar.air_C + KELVIN
    return bar.convection_W_m2K + bar.emissivity * SIGMA_W_m2K4 * (T * T + Ta * Ta) * (T + Ta)


def _mesh(bar: JominyBar, n_r: int, n_z: int) -> skfem.MeshTri:
    R, L = 0.5 * bar.diameter_m, bar.length_m
    z = L * np.linspace(0.0, 1.0, n_z + 1) ** 2          # graded: fine at the quenched end
    r = np.linspace(0.0, R, n_r + 1)
    return skfem.MeshTri.init_tensor(r, z)


def cooling_histories(material: dict, kin: Kinetics, distances_mm: np.ndarray, *, end_time_s: float = 900.0,
                      n_r: int = 8, n_z: int = 50, progress: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Times (s) and temperatures (steps, points) on the hardness track at ``distances_mm`` from the quenched end."""
    bar = load_bar()
    d = np.asarray(distances_mm, dtype=float) * 1e-3
    if np.any(d <= 0.0) or np.any(d > bar.length_m):
        raise InputError("jominy distance_mm", (d * 1e3).tolist(), f"must lie within 0-{bar.length_m * 1e3:g} mm")
    mesh = _mesh(bar, n_r, n_z)
    R = 0.5 * bar.diameter_m
    facets = mesh.facets_satisfying(lambda x: (x[0] > 1e-12) | (x[1] < 1e-12) | (x[1] > bar.length_m - 1e-12),
                                    boundaries_only=True)
    facets = np.setdiff1d(facets, mesh.facets_satisfying(lambda x: x[0] < 1e-12, boundaries_only=True))
    fe = AxisymmetricP2(mesh, facets)
    on_end = (fe.facet_z.reshape(-1) < 1e-9).astype(int)           # table 1: quenched end, table 0: air
    T_air = np.linspace(0.0, kin.T_aust_C + 50.0, 60)
    htc = TableHTC(["temperature", "temperature"], [T_air, bar.end_T_C], [air_h_W_m2K(bar, T_air), bar.end_h_W_m2K],
                   [bar.air_C, bar.water_C], on_end)
    phases = PhaseModel(kin)
    solver = ThermalSolver(fe, thermal_properties(material), kin.T_aust_C, phases, phases.initial_state(fe.r_qp.shape))
    probe = fe.basis.probes(np.vstack([np.full_like(d, R - bar.measure_depth_m), d]))
    times, temps = [0.0], [probe @ solver.T]
    dt, steps = BAR_DT_START_S, BAR_STEPS
    with tqdm(total=end_time_s, disable=not progress, desc="Jominy bar", unit="s") as bar_progress:
        while solver.time_s < end_time_s:
            step = solver.try_step(dt, htc)
            solver.commit(step)
            times.append(solver.time_s)
            temps.append(probe @ solver.T)
            bar_progress.update(dt)
            dt = steps.next_dt(dt, steps.ratio(step.max_dT_K))
    return np.array(times), np.array(temps)
