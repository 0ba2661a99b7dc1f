"""The staged quench: austenitise (uniform T, stress free) -> oil quench -> air cool to room temperature.

Each time step solves the thermal problem with the phase kinetics inside its fixed-point
iteration, then (when enabled) the stress problem with the same step. The step starts small,
grows under limits on the temperature and phase change per step, and is cut back and retried
when an iteration does not converge (logged). Probes and VTK frames are written as they are
produced; a run that fails keeps them and records where it stopped in ``summary.json``.
"""

from __future__ import annotations

import contextlib
import json
import logging
import math
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import skfem
import tomli_w
from tqdm import tqdm

from quenchsim import mechanics, metallurgy
from quenchsim.case import Case
from quenchsim.errors import InputError, QuenchsimError, SolverError
from quenchsim.geometry import BoundaryPoints, SectionExtent, SectionMesh, mesh_profile, profile_from_case
from quenchsim.geometry.profile import MM, Profile
from quenchsim.io import ProbeWriter, VtkSeries
from quenchsim.io.revolve import revolve_vtu
from quenchsim.materials import load_material, thermal_properties
from quenchsim.results import NodalProjection, depth_below, phase_statistics, time_to_temperature
from quenchsim.thermal import AxisymmetricP2, ThermalSolver, parse_htc_table

log = logging.getLogger("quenchsim")
# simulated seconds with one decimal (the float step sum would print as 46.931000000000004/900.0)
PROGRESS_FORMAT = "{l_bar}{bar}| {n:.1f}/{total:.0f} s simulated [{elapsed}<{remaining}]"
from quenchsim.fem import INTORDER  # noqa: E402 (re-export for callers of the old location)
HRC_THRESHOLD = 58.0


class _Kinetics:
    """Adapter: the metallurgy package as the thermal solver's phase model."""

    def __init__(self, kin: Any) -> None:
        self.kin = kin

    def advance(self, state: Any, T_old_C: np.ndarray, T_new_C: np.ndarray, dt_s: float) -> Any:
        return metallurgy.advance(state, self.kin, T_old_C, T_new_C, dt_s)

    def fractions(self, state: Any) -> dict[str, np.ndarray]:
        return state.fractions


class _SteadyHTC:
    """A boundary HTC that depends on the surface temperature only (bath model curves)."""

    def __init__(self, curves: Any) -> None:
        self.curves = curves
        self.ambient_C = np.asarray(curves.ambient_C)

    def __call__(self, T_surface_C: np.ndarray, time_s: float) -> np.ndarray:
        return self.curves(T_surface_C)


def boundary_points(fe: AxisymmetricP2, section: SectionMesh) -> BoundaryPoints:
    """The facet quadrature points of the cooled surface, labelled by segment, with arc length."""
    seg_of_facet = np.empty(section.mesh.facets.shape[1], dtype=object)
    for name, facets in section.boundaries.items():
        seg_of_facet[facets] = name
    nq = fe.facet_r.shape[1]
    segment = np.repeat(seg_of_facet[fe.facets], nq).astype(str)
    r, z = fe.facet_r.ravel(), fe.facet_z.ravel()
    s = np.zeros_like(r)
    length = np.zeros_like(r)
    for seg in section.profile.segments:
        idx = np.flatnonzero(segment == seg.name)
        if seg.center is None:
            s_seg = np.hypot(r[idx] - seg.start[0], z[idx] - seg.start[1])
        else:
            a0 = math.atan2(seg.start[1] - seg.center[1], seg.start[0] - seg.center[0])
            a = np.arctan2(z[idx] - seg.center[1], r[idx] - seg.center[0])
            radius = math.dist(seg.center, seg.start)
            s_seg = radius * np.abs((a - a0 + np.pi) % (2 * np.pi) - np.pi)
        # a name may cover several segments (e.g. chamfers): keep the nearest segment's values
        near = seg.distance(r[idx], z[idx]) < 1e-9 + 1e-6 * seg.length()
        s[idx[near]] = s_seg[near]
        length[idx[near]] = seg.length()
    r0, r1, z0, z1 = section.profile.bounds()
    return BoundaryPoints(r_m=r, z_m=z, normal_r=fe.facet_normals[0].ravel(), normal_z=fe.facet_normals[1].ravel(),
                          segment=segment, s_m=s, segment_length_m=length,
                          extent=SectionExtent(r_min_m=r0, r_max_m=r1, z_min_m=z0, z_max_m=z1))


def stage_htc(case: Case, stage: str, points: BoundaryPoints) -> Any:
    """The HTC of the quench or air stage as ``htc(T_surface, t)`` with ``ambient_C`` per point."""
    if stage == "quench":
        if case.get("quench.htc_model", "table") == "table":
            return parse_htc_table(case.get("quench.htc_table"), points.segment, "quench.htc_table")
        from quenchsim import bath

        return _SteadyHTC(bath.boundary_htc(bath.parse_bath(case.get("quench.bath", {}), "quench.bath"), points))
    if case.get("air.htc_model") == "table":
        return parse_htc_table(case.get("air.htc_table"), points.segment, "air.htc_table")
    from quenchsim import bath

    return _SteadyHTC(bath.air_htc(points, case.number("air.temperature_C"), case.number("air.emissivity", minimum=0.0,
                                                                                          maximum=1.0)))


@dataclass
class RunResult:
    out_dir: Path
    summary: dict[str, Any]
    time_s: np.ndarray = field(repr=False, default_factory=lambda: np.zeros(0))
    probe_T_C: dict[str, np.ndarray] = field(repr=False, default_factory=dict)


class QuenchRun:
    """Everything of one run: mesh, solvers, output writers. Use :func:`run_case`."""

    def __init__(self, case: Case, out_dir: Path, progress: bool = True) -> None:
        self.case = case
        self.out = Path(out_dir)
        self.out.mkdir(parents=True, exist_ok=True)
        (self.out / "case.toml").write_text(tomli_w.dumps(case.resolved()))
        self.progress = progress
        self.material = load_material(str(case.data["material"]))
        self.T_aust = case.number("process.austenitising_temperature_C")
        self.T_room = case.number("process.room_temperature_C")
        self.profile_before: Profile = profile_from_case(case.get("geometry", {}))
        self.profile = self.profile_before
        self.section = mesh_profile(self.profile_before, case.number("mesh.size_mm") * MM,
                                    case.number("mesh.surface_size_mm") * MM, case.number("mesh.surface_layer_mm") * MM,
                                    msh_path=self.out / "mesh.msh")
        self.mech_model = None
        self.before_mesh = self.section.mesh
        reference_state = case.get("geometry.reference_state", "annealed")
        if reference_state not in ("annealed", "austenitised"):
            raise InputError("geometry.reference_state", reference_state, "must be 'annealed' or 'austenitised'")
        mech_options = {k: v for k, v in case.get("mechanics", {}).items() if k not in ("enabled", "fixed_point_mm")}
        self.case_to_hot = 1.0
        if "mechanics" in self.material:
            solve_stress = bool(case.get("mechanics.enabled", True))
            # a thermal-only run needs the free strains (for the hot section) but no flow or TRIP data
            options = mech_options if solve_stress else {"plasticity": False, "trip": False}
            mech_model = mechanics.load_mechanics(self.material, {**options, "austenitizing_T_C": self.T_aust})
            if solve_stress:
                self.mech_model = mech_model
            # the quench starts from the austenitised section whether or not the stress is solved; the "before"
            # section is the room-temperature annealed one, smaller by the free strain between the two states.
            # The case file gives one of them.
            scale = mechanics.austenitized_scale(mech_model)
            mesh = self.section.mesh
            if reference_state == "annealed":
                self.case_to_hot = scale
                self.profile = self.profile_before.scaled(scale)
                hot = skfem.MeshTri(mesh.p * scale, mesh.t)
            else:
                self.profile, hot = self.profile_before, mesh
                self.profile_before = self.profile.scaled(1.0 / scale)
                self.before_mesh = skfem.MeshTri(mesh.p / scale, mesh.t)
            self.section = SectionMesh(mesh=hot, boundaries=self.section.boundaries, profile=self.profile)
        cooled = np.concatenate([f for n, f in self.section.boundaries.items() if n != "axis"])
        self.fe = AxisymmetricP2(self.section.mesh, cooled, intorder=INTORDER)
        self.points = boundary_points(self.fe, self.section)
        self.kin = metallurgy.load_kinetics(self.material, self.T_aust)
        self.phase_model = _Kinetics(self.kin)
        self.thermal = ThermalSolver(self.fe, thermal_properties(self.material), self.T_aust, self.phase_model,
                                     metallurgy.initial_state(self.fe.r_qp.shape, self.kin))
        self.projection = NodalProjection(self.section.mesh, INTORDER)
        fixed = case.get("mechanics.fixed_point_mm")
        if fixed is not None and not (isinstance(fixed, list) and len(fixed) == 2):
            raise InputError("mechanics.fixed_point_mm", fixed, "must be [r, z] in mm (case geometry)")
        fixed_m = None if fixed is None else (fixed[0] * MM * self.case_to_hot, fixed[1] * MM * self.case_to_hot)
        self.mech = mechanics.MechanicsSolver(self.section.mesh, self.mech_model, fixed_m) if self.mech_model else None
        self._setup_probes()
        self.timings: dict[str, float] = {}

    def _setup_probes(self) -> None:
        probes = self.case.get("probes", [])
        self.probe_names = [p["name"] for p in probes]
        given = self.profile if self.case_to_hot == 1.0 else self.profile_before
        pts = np.array([[p["r_mm"] * MM, p["z_mm"] * MM] for p in probes]).reshape(-1, 2)
        for i, (r, z) in enumerate(pts):
            if not given.contains(r, z) and given.distance(r, z) > 1e-9:
                raise InputError(f"probes[{i}]", f"{self.probe_names[i]} at ({r / MM:g}, {z / MM:g}) mm",
                                 "lies outside the section")
        # probe positions are given on the case's section; they move with it to the austenitised geometry
        self.probe_matrix = self.fe.basis.probes(pts.T * self.case_to_hot) if len(pts) else None

    def probe_temperatures(self) -> np.ndarray:
        return self.probe_matrix @ self.thermal.T if self.probe_matrix is not None else np.zeros(0)

    def nodal_fields(self) -> dict[str, np.ndarray]:
        nv = self.section.mesh.p.shape[1]
        state = self.thermal.phase_state
        data = {"temperature_C": self.thermal.T[:nv].copy()}
        for phase, X in state.fractions.items():
            data[phase] = self.projection(X)
        hv = metallurgy.hardness_HV(state, self.kin)
        data["hardness_HV"] = self.projection(hv)
        data["hardness_HRC"] = metallurgy.hv_to_hrc(data["hardness_HV"])
        if self.mech is not None:
            data.update(self.mech.nodal_fields())
        return data

    def run(self) -> RunResult:
        case, out = self.case, self.out
        wall0 = time.perf_counter()
        vtk = VtkSeries(out, self.section.mesh.p, self.section.mesh.t)
        probes = ProbeWriter(out / "probes.csv", self.probe_names)
        times, probe_rows = [0.0], [self.probe_temperatures()]
        probes.write(0.0, probe_rows[0])
        vtk.write(0.0, self.nodal_fields())
        self._last_frame_T = self.thermal.T.copy()
        ctl = case.get("time")
        dt = float(ctl["dt_initial_s"])
        steps, rejected, energy_out, latent = 0, 0, 0.0, 0.0
        frame_dT = (self.T_aust - self.T_room) / case.get("output.frames")
        status, error = "ok", None
        stages = [("quench", case.number("quench.time_s")), ("air", case.number("air.time_s", positive=True))]
        try:
            for stage, duration in stages:
                with self.timer("bath_htc_s"):
                    htc = stage_htc(case, stage, self.points)
                t_end = self.thermal.time_s + duration
                until = case.number("air.until_max_C") if stage == "air" else -math.inf
                bar = tqdm(total=round(duration, 3), desc=f"{case.name}[{case.condition}] {stage}", unit="s",
                           bar_format=PROGRESS_FORMAT, disable=not self.progress, leave=False)
                while self.thermal.time_s < t_end - 1e-9 and float(np.max(self.thermal.T)) > until:
                    dt = min(dt, t_end - self.thermal.time_s)
                    try:
                        with self.timer("thermal_metallurgy_s"):
                            step = self.thermal.try_step(dt, htc)
                    except SolverError as exc:
                        if dt / 2 < float(ctl["dt_min_s"]):
                            raise
                        log.warning("%s; cutting the step to %.3g s", exc, dt / 2)
                        dt, rejected = dt / 2, rejected + 1
                        continue
                    limit = max(step.max_dT_K / float(ctl["max_dT_K"]), step.max_dX / float(ctl["max_dX"]))
                    if limit > 2.0 and dt / 2 >= float(ctl["dt_min_s"]):
                        dt, rejected = dt / 2, rejected + 1
                        continue
                    with self.timer("mechanics_s"):
                        converged = self._mechanics_step(step.T_qp, step.phase_state.fractions)
                    if not converged:
                        if dt / 2 < float(ctl["dt_min_s"]):
                            raise SolverError(f"the stress solver did not converge at t = {self.thermal.time_s:.4g} s "
                                              f"even with the smallest step {dt:.3g} s")
                        log.warning("stress Newton did not converge (dt = %.3g s at t = %.4g s); cutting the step",
                                    dt, self.thermal.time_s)
                        dt, rejected = dt / 2, rejected + 1
                        continue
                    self.thermal.commit(step)
                    steps += 1
                    energy_out += step.heat_out_J
                    latent += step.latent_J
                    times.append(self.thermal.time_s)
                    probe_rows.append(self.probe_temperatures())
                    probes.write(self.thermal.time_s, probe_rows[-1])
                    # a frame per 1/frames of the whole cooling, measured by the mean nodal change (the
                    # max-norm counted the fast surface swings: ~260 frames for 40 requested)
                    if float(np.mean(np.abs(self.thermal.T - self._last_frame_T))) >= frame_dT:
                        with self.timer("output_s"):
                            vtk.write(self.thermal.time_s, self.nodal_fields())
                        self._last_frame_T = self.thermal.T.copy()
                    bar.update(round(step.dt_s, 3))
                    grow = float(ctl["growth"]) if limit < 1e-12 else min(float(ctl["growth"]), 0.9 / limit)
                    dt = float(np.clip(dt * grow, float(ctl["dt_min_s"]), float(ctl["dt_max_s"])))
                bar.close()
            self._equilibrate_at_room_temperature()
        except QuenchsimError as exc:
            status, error = "failed", str(exc)
            log.error("run stopped at t = %.4g s: %s", self.thermal.time_s, exc)
        finally:
            probes.close()
        last = vtk.write(self.thermal.time_s, self.nodal_fields())
        revolve_vtu(last, out / "final_3d.vtu")     # 270-degree sector of the final state for ParaView
        time_arr = np.asarray(times)
        probe_T = {n: np.array([row[i] for row in probe_rows]) for i, n in enumerate(self.probe_names)}
        try:
            summary = self.summary(time_arr, probe_T, wall0, steps, rejected, energy_out, latent)
        except Exception as exc:  # keep what was computed: record the failure, then re-raise
            (out / "summary.json").write_text(json.dumps({"case": case.name, "condition": case.condition,
                                                          "status": "failed", "error": f"post-processing: {exc!r}"}))
            raise
        summary["status"] = status
        if error:
            summary["error"] = error
            summary["stopped_at_s"] = self.thermal.time_s
        (out / "summary.json").write_text(json.dumps(summary, indent=2))
        if error:
            raise SolverError(f"{error} (results up to t = {self.thermal.time_s:.4g} s are in {out})")
        return RunResult(out, summary, time_arr, probe_T)

    @contextlib.contextmanager
    def timer(self, key: str) -> Iterator[None]:
        """Accumulate the wall time of a block into ``self.timings[key]`` (reported in summary.json)."""
        t0 = time.perf_counter()
        try:
            yield
        finally:
            self.timings[key] = self.timings.get(key, 0.0) + time.perf_counter() - t0

    def _mechanics_step(self, T_qp: np.ndarray, fractions: dict[str, np.ndarray]) -> bool:
        if self.mech is None:
            return True
        info = self.mech.step(T_qp, fractions, self.thermal.T_qp, self.thermal.fractions())
        return bool(info.converged)

    def _equilibrate_at_room_temperature(self) -> None:
        """Final state: the whole ring at room temperature (the air stage ends when the hottest point
        is below air.until_max_C; the last few kelvin are one step, with the martensite they still form).

        The step takes no time for the diffusional reactions (dt = 0): its length is not modelled, and an
        assumed hour at 20-40 C had let the peer's bainite law, extrapolated far below its 240-440 C data,
        form 0.02 bainite out of retained austenite after the quench had ended."""
        T_room = np.full(self.thermal.T.shape, self.T_room)
        T_qp = self.fe.at_qp(T_room)
        state = self.phase_model.advance(self.thermal.phase_state, self.thermal.T_qp, T_qp, 0.0)
        if not self._mechanics_step(T_qp, state.fractions):
            raise SolverError("the stress solver did not converge in the final step to room temperature")
        self.thermal.T, self.thermal.T_qp, self.thermal.phase_state = T_room, T_qp, state

    def mechanics_summary(self) -> dict[str, Any]:
        """Dimensions before/after, residual stresses at mid-width, traverse and outline files."""
        before = mechanics.ring_dimensions(self.before_mesh)
        after = mechanics.ring_dimensions(self.section.mesh, self.mech.displacement_m)
        r0, r1, z0, z1 = self.profile.bounds()
        z_mid = 0.5 * (z0 + z1)
        r_bore = _surface_r_at(self.profile, z_mid, inner=True)
        r_od = _surface_r_at(self.profile, z_mid, inner=False)
        r = np.linspace(r_bore + 1e-6, r_od - 1e-6, 200)
        fields = self.mech.nodal_fields()
        probe = self.projection.p1.probes(np.vstack([r, np.full_like(r, z_mid)]))
        hoop = probe @ fields["stress_tt_Pa"] / 1e6
        axial = probe @ fields["stress_zz_Pa"] / 1e6
        np.savetxt(self.out / "residual_hoop_traverse.csv", np.column_stack([r / MM, hoop, axial]), delimiter=",",
                   header="r_mm,hoop_MPa,axial_MPa", comments="", fmt="%.6g")
        outline_before = mechanics.section_outline(self.before_mesh)
        outline_after = mechanics.section_outline(self.section.mesh, self.mech.displacement_m)
        np.savetxt(self.out / "outline.csv", np.column_stack([outline_before / MM, outline_after / MM]), delimiter=",",
                   header="r_before_mm,z_before_mm,r_after_mm,z_after_mm", comments="", fmt="%.6f")
        at = {"od_surface_mid": -1, "bore_surface_mid": 0, "core_mid": len(r) // 2}
        return {"dimensions_mm": mechanics.dimension_change(before, after),
                "residual_stress_MPa": {"hoop": {k: float(hoop[i]) for k, i in at.items()},
                                        "axial": {k: float(axial[i]) for k, i in at.items()}}}

    # -- summary --------------------------------------------------------------------------------
    def hardness_traverse(self, side: str, hrc_nodal: np.ndarray, n: int = 400) -> tuple[np.ndarray, np.ndarray]:
        """HRC along mid-width from the bore ("bore") or OD ("od") surface into the wall: (depth_mm, HRC)."""
        r0, r1, z0, z1 = self.profile.bounds()
        z_mid = 0.5 * (z0 + z1)
        r_bore = _surface_r_at(self.profile, z_mid, inner=True)
        r_od = _surface_r_at(self.profile, z_mid, inner=False)
        wall = r_od - r_bore
        depth = np.linspace(1e-6, wall - 1e-6, n)   # 1 um inside: the traverse ends on the surfaces
        r = r_bore + depth if side == "bore" else r_od - depth
        probe = self.projection.p1.probes(np.vstack([r, np.full_like(r, z_mid)]))
        return depth / MM, probe @ hrc_nodal

    def summary(self, time_s: np.ndarray, probe_T: dict[str, np.ndarray], wall0: float, steps: int,
                rejected: int, energy_out: float, latent: float) -> dict[str, Any]:
        r0, r1, z0, z1 = self.profile.bounds()
        z_mid = 0.5 * (z0 + z1)
        fields = self.nodal_fields()
        hrc = fields["hardness_HRC"]
        p1 = self.projection.p1
        out: dict[str, Any] = {"case": self.case.name, "condition": self.case.condition}
        out["probes"] = {n: {"t_to_500C_s": time_to_temperature(time_s, T, 500.0),
                             "t_to_300C_s": time_to_temperature(time_s, T, 300.0),
                             "t8_5_s": _t_between(time_s, T, 800.0, 500.0)} for n, T in probe_T.items()}
        depth, traverse = {}, {}
        for side in ("bore", "od"):
            d, h = self.hardness_traverse(side, hrc)
            traverse[side] = (d, h)
            depth[f"HRC58_{side}_mid"] = depth_below(d, h, HRC_THRESHOLD)
        np.savetxt(self.out / "hardness_traverse.csv",
                   np.column_stack([traverse["bore"][0], traverse["bore"][1], traverse["od"][1]]),
                   delimiter=",", header="depth_mm,HRC_from_bore,HRC_from_od", comments="", fmt="%.5g")
        surface = {}
        for seg in self.profile.segments:
            if seg.name == "axis" or seg.name.startswith(("chamfer", "radius")):
                continue
            a, mid, b = seg.points(3)
            tangent = (b - a) / np.linalg.norm(b - a)
            pt = mid + 1e-6 * np.array([-tangent[1], tangent[0]])   # left of a counter-clockwise outline = inside
            surface[f"{seg.name}_mid"] = float((p1.probes(pt.reshape(2, 1)) @ hrc)[0])
        core_r = 0.5 * (_surface_r_at(self.profile, z_mid, True) + _surface_r_at(self.profile, z_mid, False))
        core = float((p1.probes(np.array([[core_r], [z_mid]])) @ hrc)[0])
        out["hardness"] = {"depth_mm": depth, "surface_HRC": surface, "core_HRC": core,
                           "threshold_HRC": HRC_THRESHOLD, "through_hardened": bool(np.nanmin(hrc) >= HRC_THRESHOLD)}
        out["phases_final"] = phase_statistics(self.thermal.fractions(), self.fe.r_dx)
        if self.mech is not None:
            out.update(self.mechanics_summary())
        out["energy"] = {"heat_extracted_J": energy_out, "latent_released_J": latent}
        out["solver"] = {"wall_time_s": time.perf_counter() - wall0, "stage_time_s": dict(self.timings), "steps": steps, "rejected_steps": rejected,
                         "dofs": int(self.fe.n_dofs), "elements": int(self.section.n_elements),
                         "end_time_s": float(self.thermal.time_s)}
        return out


def _t_between(time_s: np.ndarray, T: np.ndarray, upper: float, lower: float) -> float | None:
    a, b = time_to_temperature(time_s, T, upper), time_to_temperature(time_s, T, lower)
    return None if a is None or b is None else b - a


def _surface_r_at(profile: Profile, z: float, inner: bool) -> float:
    """Radius where the horizontal line at height z meets the bore (inner) or the OD surface."""
    poly = profile.polygon(512)
    x, y = poly[:, 0], poly[:, 1]
    x2, y2 = np.roll(x, -1), np.roll(y, -1)
    hit = (y - z) * (y2 - z) <= 0
    hit &= y != y2
    rs = x[hit] + (z - y[hit]) * (x2[hit] - x[hit]) / (y2[hit] - y[hit])
    return float(rs.min() if inner else rs.max())


def run_case(case: Case, out_dir: str | Path, progress: bool = True) -> RunResult:
    """Run ``case`` and write everything into ``out_dir`` (see DESIGN.md, output contract)."""
    run = QuenchRun(case, Path(out_dir), progress=progress)
    return run.run()
