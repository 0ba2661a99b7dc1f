"""Code-to-code check of the stress solver against CalculiX (ccx): the section of case A (cases/crb_outer_ring.toml)
quenched without transformation (all austenite: SUJ3's austenite thermal and elastic-plastic data), once
under a uniform film coefficient and once under different coefficients on the OD, the bore and the faces.

quenchsim's thermal solver computes one temperature history; both stress solvers take it node by node at
the same steps (quenchsim: :class:`~quenchsim.mechanics.MechanicsSolver`; CalculiX: a CAX6 deck written from
the same P2 mesh by :mod:`quenchsim.io.calculix`, ``*TEMPERATURE`` per step), with the same elastic-plastic
tables and the same axially fixed node.  Compared: the dimension change (ID, OD, width, measured the same way
on both displacement fields) and the residual hoop stress at the OD and the bore at mid-width (the same
traverse over both codes' vertex stresses).

The study needs the ``ccx`` executable (Debian/Ubuntu: ``apt-get install calculix-ccx``); without it the
study reports ``skipped: ccx not found`` and its targets are not evaluated.  Nothing is installed here.
"""

from __future__ import annotations

import shutil
from pathlib import Path
from typing import Any

import numpy as np

from quenchsim.validation import ROOT

TITLE = "Mechanics verification: quenchsim against CalculiX (thermal-only elastic-plastic ring)"
SLOW = True
CASE_A = ROOT / "cases" / "crb_outer_ring.toml"
HTC_CASES = {
    "uniform": {"od": 3000.0, "bore": 3000.0, "faces": 3000.0},
    "non_uniform": {"od": 4000.0, "bore": 1000.0, "faces": 2000.0},
}
"""Film coefficients (W/m2K) per surface: the two cases of issue 21."""
OIL_C = 60.0
QUENCH_S = 1800.0
MAX_STEPS = 400


def ccx_executable() -> str | None:
    return shutil.which("ccx")


def _section(mesh_mm: float | None = None) -> tuple[Any, Any, Any, Any]:
    """Case A's material, case, hot section and "before" mesh (optionally a coarser mesh for tests)."""
    from quenchsim.case import load_case
    from quenchsim.materials import load_material
    from quenchsim.quench_setup import build_section

    overrides = None if mesh_mm is None else {"mesh.size_mm": mesh_mm, "mesh.surface_size_mm": mesh_mm}
    case = load_case(CASE_A, "1", overrides)
    material = load_material(case.material)
    built = build_section(case, None)
    return material, case, built.hot, built.before_mesh


def temperature_history(section: Any, material: dict[str, Any], htc_W_m2K: dict[str, float], T_start_C: float,
                        T_room_C: float, quench_s: float = QUENCH_S) -> tuple[list[float], list[np.ndarray], Any]:
    """quenchsim's thermal solution without transformation (austenite throughout): the step end times and the
    nodal (P2) temperatures after each step, closed by a uniform step to room temperature."""
    from quenchsim.fem import INTORDER
    from quenchsim.materials import thermal_properties
    from quenchsim.quench_setup import cooled_surface_points
    from quenchsim.thermal import AxisymmetricP2, NoTransformation, ThermalSolver, parse_htc_table

    cooled = np.concatenate([f for n, f in section.boundaries.items() if n != "axis"])
    fe = AxisymmetricP2(section.mesh, cooled, intorder=INTORDER)
    points = cooled_surface_points(fe, section)
    names = sorted(set(points.segment))
    segments = {n: {"T_C": [0.0, 2000.0], "h_W_m2K": [htc_W_m2K[_surface(n)]] * 2} for n in names}
    htc = parse_htc_table({"ambient_C": OIL_C, "segments": segments}, points.segment, "calculix.htc")
    solver = ThermalSolver(fe, thermal_properties(material), T_start_C, NoTransformation(), np.ones_like(fe.r_qp))
    times, temps = [], []
    dt = 0.05
    while solver.time_s < quench_s - 1e-9 and len(times) < MAX_STEPS:
        dt = min(dt, quench_s - solver.time_s)
        step = solver.try_step(dt, htc)
        if step.max_dT_K > 40.0 and dt > 1e-3:
            dt /= 2
            continue
        solver.commit(step)
        times.append(solver.time_s)
        temps.append(solver.T.copy())
        dt = min(dt * (1.5 if step.max_dT_K < 20.0 else 1.0), 60.0)
    times.append(solver.time_s + 60.0)
    temps.append(np.full_like(solver.T, T_room_C))
    return times, temps, fe


def _surface(segment: str) -> str:
    """The surface a profile segment belongs to: the OD, the bore, or a face (faces and chamfers)."""
    if segment == "od":
        return "od"
    if segment == "bore":
        return "bore"
    return "faces"


def quenchsim_stress(section: Any, model: Any, fe: Any, T_start_C: float, temps: list[np.ndarray]) -> Any:
    """quenchsim's stress solver driven through the history (all austenite)."""
    from quenchsim.mechanics import MechanicsSolver

    solver = MechanicsSolver(section.mesh, model)
    X = {"austenite": np.ones_like(fe.r_qp)}
    T_prev = np.full_like(fe.r_qp, T_start_C)
    for k, T in enumerate(temps):
        T_qp = fe.at_qp(T)
        info = solver.step(T_qp, X, T_prev, X)
        if not info.converged:
            raise RuntimeError(f"quenchsim's stress solver did not converge in step {k}")
        T_prev = T_qp
    return solver


def calculix_stress(section: Any, model: Any, solver: Any, T_start_C: float, T_room_C: float, times: list[float],
                    temps: list[np.ndarray], workdir: Path, ccx: str) -> tuple[np.ndarray, np.ndarray]:
    """CalculiX on the same mesh, history, material tables and fixed node: (vector-P2 displacement, nodal
    stresses (n, 6))."""
    from quenchsim.io import calculix

    fixed_node = int(solver.fixed_dofs[solver.fixed_dofs % 2 == 1][0] // 2)
    grid = calculix.temperature_grid(model, "austenite", min(T_room_C, OIL_C) - 10.0, T_start_C + 10.0)
    tables = calculix.material_tables(model, "austenite", grid)
    deck = calculix.write_inp(workdir / "ring.inp", section.mesh, tables, T_start_C, temps, times, fixed_node)
    calculix.run_ccx(deck, ccx)
    n = len(temps[0])
    u = calculix.read_dat_displacements(workdir / "ring.dat", n)
    stress = calculix.read_frd_block(workdir / "ring.frd", "STRESS", n)
    return u.ravel(), stress


def compare(htc_W_m2K: dict[str, float], workdir: Path, ccx: str, mesh_mm: float | None = None) -> dict[str, Any]:
    """Both codes on one history: dimension changes (mm) and residual hoop stresses (MPa) side by side."""
    from quenchsim.mechanics import load_mechanics, ring_dimensions, section_outline
    from quenchsim.results.summary import FinalSection, residual_stress_summary, residual_traverse

    material, case, section, before_mesh = _section(mesh_mm)
    T_start, T_room = case.process.austenitising_temperature_C, case.process.room_temperature_C
    model = load_mechanics(material, {"trip": False, "austenitizing_T_C": T_start})
    times, temps, fe = temperature_history(section, material, htc_W_m2K, T_start, T_room)
    ours = quenchsim_stress(section, model, fe, T_start, temps)
    workdir.mkdir(parents=True, exist_ok=True)
    u_ccx, s_ccx = calculix_stress(section, model, ours, T_start, T_room, times, temps, workdir, ccx)
    before = ring_dimensions(before_mesh)
    # both codes' stresses sampled along the same mid-width line of the section they share
    shared = FinalSection.of(section.mesh.p, section.mesh.t, section_outline(section.mesh))
    nv = section.mesh.p.shape[1]
    out: dict[str, Any] = {"steps": len(times)}
    fields = {"quenchsim": ours.nodal_fields(),
              "calculix": {"stress_tt_Pa": s_ccx[:nv, 2], "stress_zz_Pa": s_ccx[:nv, 1]}}
    for code, u in (("quenchsim", ours.displacement_m), ("calculix", u_ccx)):
        after = ring_dimensions(section.mesh, u)
        rs = residual_stress_summary(*residual_traverse(shared, fields[code])[1:])
        out[code] = {"dimension_change_mm": {k: after[k] - before[k] for k in ("id", "od", "width")},
                     "hoop_MPa": {"od": rs["hoop"]["od_surface_mid"], "bore": rs["hoop"]["bore_surface_mid"]}}
    out["difference"] = {
        "dimension_change_mm": {k: abs(out["quenchsim"]["dimension_change_mm"][k] - out["calculix"]["dimension_change_mm"][k])
                                for k in ("id", "od", "width")},
        "hoop_MPa": {k: abs(out["quenchsim"]["hoop_MPa"][k] - out["calculix"]["hoop_MPa"][k]) for k in ("od", "bore")}}
    out["difference"]["max_dimension_mm"] = max(out["difference"]["dimension_change_mm"].values())
    out["difference"]["max_hoop_MPa"] = max(out["difference"]["hoop_MPa"].values())
    return out


def run(workdir: Path) -> dict[str, Any]:
    ccx = ccx_executable()
    if ccx is None:
        return {"skipped": "skipped: ccx not found (install CalculiX, e.g. apt-get install calculix-ccx)"}
    return {name: compare(htc, Path(workdir) / name, ccx) for name, htc in HTC_CASES.items()}


def page(metrics: dict[str, Any]) -> str:
    if "skipped" in metrics:
        return f"{metrics['skipped']}: the comparison was not run and its targets are not evaluated.\n"
    lines = ["Case A's section quenched without transformation (SUJ3 austenite data) under two sets of film "
             "coefficients; quenchsim's thermal solution drives both stress solvers node by node (CalculiX: CAX6 "
             "elements written from quenchsim's P2 mesh, `*TEMPERATURE` per step, the same elastic-plastic tables "
             "and fixed node). Dimension changes are measured the same way on both displacement fields; hoop "
             "stresses are read at mid-width on both codes' vertex stresses.", "",
             "| HTC case | quantity | quenchsim | CalculiX | difference |", "|---|---|---|---|---|"]
    for name, m in metrics.items():
        htc = HTC_CASES[name]
        label = f"{name} (OD/bore/faces {htc['od']:.0f}/{htc['bore']:.0f}/{htc['faces']:.0f} W/m2K)"
        for k in ("id", "od", "width"):
            a, b = m["quenchsim"]["dimension_change_mm"][k], m["calculix"]["dimension_change_mm"][k]
            lines.append(f"| {label} | {k.upper()} change (mm) | {a:.4f} | {b:.4f} | {a - b:+.4f} |")
        for k in ("od", "bore"):
            a, b = m["quenchsim"]["hoop_MPa"][k], m["calculix"]["hoop_MPa"][k]
            lines.append(f"| {label} | residual hoop stress, {k} mid-width (MPa) | {a:.1f} | {b:.1f} | {a - b:+.1f} |")
    return "\n".join(lines) + "\n"
