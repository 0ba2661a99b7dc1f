"""The ISO 9950 / ASTM D6200 cooling-curve probe on quenchsim's own thermal solver (the one forward model: the
quenchant fitter drives it with a tabulated h(T_s), the bath validation with the bath model's curves on
:meth:`ProbeModel.boundary_points`).

The probe is a cylinder of Inconel 600, 12.5 mm diameter x 60 mm, with a thermocouple at its geometric
centre, heated to 850 C and quenched into 2 L of the quenchant (ISO 9950:1995, ASTM D6200; dimensions and
material in ``materials/quenchants/iso9950_probe_inconel600.toml``). Inconel 600 does not transform, so
the conduction is that of :class:`quenchsim.thermal.ThermalSolver` with :class:`NoTransformation`.

Model choices (each checked in ``validation/quenchants/probe_fit``):

* Section: the half probe r in [0, R], z in [0, L/2], z = 0 the cooled end face and z = L/2 the
  mid-length plane, a symmetry plane (insulated) on which the thermocouple sits at r = 0. Both the
  side and the end face see the same h(T_surface); the support tube of the real probe is not modelled
  (the thermocouple is 30 mm = 4.8 radii from either end, so the ends do not reach it within the
  quench: checked by the axial-length term of the mesh study).
* Mesh: a tensor-product triangle mesh graded toward the cooled surfaces (P2 elements): a coarse mesh
  is enough because h(T) is smooth on the element scale; mesh convergence of the centre curve is a
  test (``tests/test_fitting_quenchant_slow.py``) and a metric of ``validation/quenchants/probe_fit``.
* Time steps: a fixed schedule that depends only on the measured curve (so that a fitted parameter never
  changes the step sequence, and finite-difference sensitivities are smooth): the step starts at
  ``dt_start_s`` and grows by ``growth`` per step, limited so that the measured centre temperature changes
  by at most ``centre_step_K`` per step; the model is read at the measurement times by linear
  interpolation between step ends.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass
from typing import Any

import numpy as np
import skfem

from quenchsim.errors import InputError, SolverError
from quenchsim.geometry.boundary import BoundaryPoints, SectionExtent
from quenchsim.inputs.quenchant import ProbeFile, read_quenchant
from quenchsim.materials import ThermalProperties, find_data_file, thermal_properties_of
from quenchsim.thermal import AxisymmetricP2, NoTransformation, TableHTC, ThermalSolver
from quenchsim.thermal.steps import StepController

MM = 1e-3
PROBE_FILE = "iso9950_probe_inconel600"


@dataclass(frozen=True)
class ProbeSpec:
    """Dimensions, test conditions and thermal properties of a cooling-curve probe (SI, T in C)."""

    name: str
    radius_m: float
    length_m: float
    start_temperature_C: float
    bath_temperature_C: float
    properties: ThermalProperties
    source: str


def load_probe(name: str = PROBE_FILE) -> ProbeSpec:
    """The probe of ``materials/quenchants/NAME.toml`` (``kind = "probe"``, :class:`quenchsim.inputs.quenchant.ProbeFile`)."""
    data = read_quenchant(find_data_file(name, "quenchants", "probe"), "probe")
    if not isinstance(data, ProbeFile):
        raise InputError("probe", name, f"is a {data.kind} file; a probe (kind = \"probe\") is needed")
    return ProbeSpec(name=data.name or name, radius_m=0.5 * data.diameter_mm * MM, length_m=data.length_mm * MM,
                     start_temperature_C=data.start_temperature_C, bath_temperature_C=data.oil_temperature_C,
                     properties=thermal_properties_of(data.thermal), source=data.source)


def graded_nodes(length_m: float, n: int, ratio: float) -> np.ndarray:
    """``n + 1`` nodes on [0, length] whose spacing shrinks geometrically by ``ratio`` from 0 toward ``length``
    (the ratio of the last element to the first is ``ratio``; 1 is uniform)."""
    q = ratio ** (1.0 / max(n - 1, 1))
    widths = q ** np.arange(n)
    return np.concatenate([[0.0], np.cumsum(widths)]) / widths.sum() * length_m


@dataclass(frozen=True)
class ProbeMesh:
    """Element counts of the half-probe mesh: radial (graded toward the side), axial (toward the end face)
    over ``axial_extent_m`` from the end (the rest of the half length is one coarse block), and the ratio of
    the largest to the smallest element."""

    n_radial: int = 4
    n_axial: int = 6
    grading: float = 0.4


def probe_section(spec: ProbeSpec, mesh: ProbeMesh) -> tuple[skfem.MeshTri, np.ndarray]:
    """The half-probe triangle mesh (metres, x = r, y = z) and its cooled facets (side r = R, end z = 0)."""
    r = graded_nodes(spec.radius_m, mesh.n_radial, mesh.grading)
    # axial: fine at the end face z = 0 and coarse toward the mid-length plane
    z = spec.length_m / 2 - graded_nodes(spec.length_m / 2, mesh.n_axial, mesh.grading)[::-1]
    tri = skfem.MeshTri.init_tensor(r, z)
    cooled = tri.facets_satisfying(lambda x: np.isclose(x[0], spec.radius_m) | np.isclose(x[1], 0.0),
                                   boundaries_only=True)
    return tri, cooled


@dataclass(frozen=True)
class ProbeCurve:
    """A simulated probe quench: step-end times, centre (thermocouple) and mid-length surface temperatures."""

    time_s: np.ndarray
    centre_C: np.ndarray
    surface_C: np.ndarray


def step_schedule(time_s: np.ndarray, centre_C: np.ndarray, *, dt_start_s: float = 0.005, growth: float = 1.25,
                  centre_step_K: float = 2.0, dt_max_s: float = 1.0, window_s: float = 0.5) -> np.ndarray:
    """Step-end times from 0 to the last measurement time (see the module docstring). The measured rate is
    taken as a difference over ``window_s`` so that thermocouple noise does not shorten the steps."""
    t_end = float(time_s[-1])
    grid = np.arange(0.0, t_end + window_s, window_s)
    T_grid = np.interp(grid, time_s, centre_C)
    rate = np.abs(np.diff(T_grid)) / window_s
    steps = StepController(growth, dt_max_s=dt_max_s)
    ends, t, dt = [], 0.0, dt_start_s
    while t < t_end - 1e-12:
        local = float(rate[min(int(t / window_s), rate.size - 1)])
        dt = steps.ahead(dt, centre_step_K / max(local, 1e-9))
        t = min(t + dt, t_end)
        ends.append(t)
    return np.asarray(ends)


class ProbeModel:
    """The probe's thermal model: ``cool(T_nodes, h_nodes, step_ends_s)`` gives the centre curve.

    h(T_surface) is piecewise linear through (T_nodes, h_nodes), constant beyond the ends (the
    :class:`TableHTC` of the thermal solver), with the bath at ``bath_temperature_C``.
    """

    def __init__(self, spec: ProbeSpec | None = None, mesh: ProbeMesh = ProbeMesh(),
                 start_temperature_C: float | None = None, bath_temperature_C: float | None = None) -> None:
        self.spec = spec or load_probe()
        self.mesh_settings = mesh
        self.start_C = self.spec.start_temperature_C if start_temperature_C is None else float(start_temperature_C)
        self.bath_C = self.spec.bath_temperature_C if bath_temperature_C is None else float(bath_temperature_C)
        tri, cooled = probe_section(self.spec, mesh)
        self.fe = AxisymmetricP2(tri, cooled)
        R, half = self.spec.radius_m, self.spec.length_m / 2
        self._read = self.fe.basis.probes(np.array([[0.0, R], [half, half]]))  # centre, mid-length surface

    def htc(self, T_nodes_C: np.ndarray, h_nodes_W_m2K: np.ndarray) -> TableHTC:
        n = self.fe.facet_r.size
        return TableHTC(["temperature"], [np.asarray(T_nodes_C, float)], [np.asarray(h_nodes_W_m2K, float)],
                        [self.bath_C], np.zeros(n, dtype=int))

    def start(self) -> ThermalSolver:
        return ThermalSolver(self.fe, self.spec.properties, self.start_C, NoTransformation(), np.ones(self.fe.r_qp.shape))

    def read(self, solver: ThermalSolver) -> tuple[float, float]:
        centre, surface = self._read @ solver.T
        return float(centre), float(surface)

    def march(self, solver: ThermalSolver, htc: Any, step_ends_s: np.ndarray,
              checkpoints: list[Any] | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Advance ``solver`` through ``step_ends_s`` (all after its present time); returns the centre and
        surface temperature at each step end. With ``checkpoints`` (a list), a copy of the solver before every
        step is appended (restart points for sensitivities)."""
        centre, surface = np.empty(len(step_ends_s)), np.empty(len(step_ends_s))
        for k, t_end in enumerate(step_ends_s):
            if checkpoints is not None:
                checkpoints.append(copy.copy(solver))
            self._advance(solver, htc, float(t_end) - solver.time_s)
            centre[k], surface[k] = self.read(solver)
        return centre, surface

    def _advance(self, solver: ThermalSolver, htc: Any, dt_s: float, depth: int = 0) -> None:
        """One scheduled step; if its fixed-point iteration fails (a trial h of the optimiser far from the
        solution), the step is done as four sub-steps instead (at most three levels deep)."""
        try:
            solver.commit(solver.try_step(dt_s, htc))
        except SolverError:
            if depth >= 3:
                raise
            for _ in range(4):
                self._advance(solver, htc, dt_s / 4, depth + 1)

    def boundary_points(self) -> BoundaryPoints:
        """The cooled facets' quadrature points (the order the solver's HTC is called with) as the bath model sees
        them: the side "od" and the end face "bottom", in the whole probe's extent (z from 0 to L, so that the
        bath's natural-convection and film-boiling lengths are the probe's, not the half model's)."""
        fe, R, L = self.fe, self.spec.radius_m, self.spec.length_m
        r, z = fe.facet_r.ravel(), fe.facet_z.ravel()
        side = np.abs(fe.facet_normals[0].ravel()) > 0.5
        return BoundaryPoints(r_m=r, z_m=z, normal_r=fe.facet_normals[0].ravel(), normal_z=fe.facet_normals[1].ravel(),
                              segment=np.where(side, "od", "bottom"), s_m=np.where(side, z, r),
                              segment_length_m=np.where(side, L / 2, R), extent=SectionExtent(0.0, R, 0.0, L))

    def run(self, htc: Any, step_ends_s: np.ndarray) -> ProbeCurve:
        """Quench the probe from its start temperature with any boundary HTC ``htc(T_surface_C, time_s)`` (one value
        per point of :meth:`boundary_points`, with ``ambient_C``); values at t = 0 included."""
        solver = self.start()
        c0, s0 = self.read(solver)
        centre, surface = self.march(solver, htc, np.asarray(step_ends_s, float))
        return ProbeCurve(np.concatenate([[0.0], step_ends_s]), np.concatenate([[c0], centre]),
                          np.concatenate([[s0], surface]))

    def cool(self, T_nodes_C: np.ndarray, h_nodes_W_m2K: np.ndarray, step_ends_s: np.ndarray) -> ProbeCurve:
        """Quench the probe from its start temperature with h(T_surface) through the nodes; values at t = 0 included."""
        return self.run(self.htc(T_nodes_C, h_nodes_W_m2K), step_ends_s)
