"""Quasi-static internal forces of a six-ball DOJ: rigid bodies, Hertz penalty contacts with clearances, no friction.

The paper (Hayama 2001, technical review No. 69 p. 97) ran an ADAMS multibody model at 10 rpm; at that speed the
joint is quasi-static, so here each rotational phase is a static equilibrium (an assumption of this model, no
inertia or damping), solved by Levenberg-Marquardt from the previous phase's solution.

Frames and kinematics (outer-race frame, mm): outer-race axis z; the shaft is articulated by the operating angle
theta about the x axis, inner-race axis d = (0, -sin theta, cos theta); the axes meet at the origin. Ball i sits
in outer track psi_i = phi + 60 i deg (phi: the rotational phase; ball 0 on the x axis at phi = 0, i.e. on the
articulation axis). Straight tracks: the ball-centre line of an outer track is parallel to z at radius PCR, that
of an inner track parallel to d at radius PCR; the two lines of one ball lie in the plane x = PCR cos psi and meet at
z = PCR sin psi tan(theta / 2): every ball is in the bisecting plane (the joint is homokinetic). The cage's sphere
centres are on its axis at the offset e either side of the window plane; at zero clearance the inner one is the
inner-race sphere centre (on d) and the outer one is on z, so the inner-race sphere centre is I = -(e / cos(theta/2)) d
and the cage centre M0 = e / (2 cos(theta/2)) (z - d) with its axis along the bisector (z + d) / |z + d|.

Bodies and unknowns (24): the inner race (held by the shaft at I and at the operating angle -- the shaft reacts the
net force on it -- free to wind up by beta about d under the torque T), the cage (3 translations, 2 tilts; its spin
about its own axis is free and does not matter: the windows' circumferential faces are not modelled, the windows
being long enough for the balls' circumferential travel), the six balls (3 translations each; no friction, so their
spin does not matter). The outer race is the fixed frame (it reacts the torque).

Contacts (each Q = K max(delta, 0)^1.5 along its normal, K from contact.py):
* ball - track flank: two flanks per track (gothic arch), each a groove of radius r_g whose centre line is
  parallel to the track, at r_g - r_b - g from the centred ball towards the ball, on the line at the contact angle
  alpha from the radial direction (g = track clearance x cos(alpha) / 2); delta = (distance to that line) - (r_g - r_b);
* ball - window: two faces normal to the cage axis, delta = +-(X - M).n - window clearance / 2;
* inner-race sphere - cage inner sphere: delta = |C_i - I| - inner-sphere clearance;
* cage outer sphere - outer-race bore: delta = (distance of C_o from the z axis) - outer-sphere clearance.
Equations: force balance of every ball and of the cage, the cage's moments about the two axes normal to its axis,
and the inner race's torque about d (kernel.py computes them; centring springs of negligible stiffness locate what
no contact holds, see REGULARISATION).

Outputs (Hayama's, sec. 1.1 of the reference notes): P_i, P_o (ball - inner / outer track, summed over the flanks),
P_p (ball - window, net, signed along the cage axis: > 0 pushes the ball towards +z, the side of the cage's outer
sphere centre),
F_ic, F_co (sphere contacts), the wedge angle (between the outer-track force on a ball and the opposite of the
inner-track force: 0 when they are collinear; undefined when either is zero) and P_n = T / (6 PCR sin alpha)
(the paper's Eq. 12) for the normalisation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import least_squares

from quenchsim.bearings.doj import kernel
from quenchsim.bearings.doj.contact import ContactStiffness, contact_stiffness
from quenchsim.bearings.doj.geometry import Clearances, DOJGeometry
from quenchsim.errors import SolverError, require

N_BALLS = kernel.N_BALLS

N_UNKNOWNS = 24
# Centring springs (a regularisation, per mm of displacement, times P_n) on the balls' and the cage's displacements:
# they locate a ball or the cage where no contact holds it (inside the clearances) and carry < 2e-4 P_n at the
# largest displacements found (~0.2 mm); softer springs leave the Jacobian too ill-conditioned for Levenberg-Marquardt
# to reach RESIDUAL_TOLERANCE (1e-5 and 1e-4 stalled at 1e-7..1e-2 of P_n, measured).
REGULARISATION = 1e-3
RESIDUAL_TOLERANCE = 1e-9  # largest equation residual accepted, relative to P_n (forces) and P_n PCR (torque)
FD_STEP_MM = 1e-6  # central-difference step of the Jacobian
MAX_EVALUATIONS = 300
MAX_HALVINGS = 8  # continuation: largest number of times a phase step is halved
START_OFFSETS_DEG = (1.3, 7.0, 13.0, 23.0)  # phases near the first one to start a revolution from when it stalls
HOMOTOPY_STEPS = 4  # first phase: from the joint without clearance at zero angle to the case in this many steps


def hayama_normal_load_N(torque_Nm: float, geo: DOJGeometry) -> float:
    """P_n = T / (6 PCR sin alpha) (the paper's Eq. 12): the ball - track force of every ball at zero operating
    angle, with T in N m, PCR in m.

    >>> from quenchsim.bearings.doj.geometry import reference_geometry
    >>> round(hayama_normal_load_N(98.1, reference_geometry()), 1)
    1017.3
    """
    return torque_Nm / (6.0 * geo.pitch_circle_radius_mm * 1e-3 * math.sin(math.radians(geo.track_contact_angle_deg)))


@dataclass
class PhaseResult:
    """Equilibrium at one phase: per ball (shape (6,)) P_i, P_o, signed P_p (N), wedge angle (deg, NaN when a track
    force is zero), ball-track contact deflections; cage sphere forces F_ic, F_co (N, magnitudes) and vectors; the
    torque the outer race reacts about its axis (N m); the net force the shaft reacts on the inner race (N);
    the inner race's wind-up (rad) and the largest equation residual (relative)."""

    phase_deg: float
    p_inner_N: np.ndarray
    p_outer_N: np.ndarray
    p_window_N: np.ndarray
    wedge_angle_deg: np.ndarray
    f_inner_cage_N: float
    f_cage_outer_N: float
    f_inner_cage_vector_N: np.ndarray
    f_cage_outer_vector_N: np.ndarray
    outer_race_torque_Nm: float
    shaft_reaction_N: np.ndarray
    wind_up_rad: float
    residual: float
    state: np.ndarray = field(repr=False)
    outer_race_axial_N: float = 0.0
    """Force the balls and the cage exert on the outer race along its axis (the plunge direction): zero without
    friction, the tracks and the bore being parallel to the axis (axial.py adds the first-order friction part)."""


class DOJModel:
    """A DOJ of geometry ``geo`` with ``clearances`` at ``operating_angle_deg`` transmitting ``torque_Nm``."""

    def __init__(self, geo: DOJGeometry, clearances: Clearances, operating_angle_deg: float, torque_Nm: float,
                 stiffness: ContactStiffness | None = None) -> None:
        require(math.isfinite(operating_angle_deg) and 0.0 <= operating_angle_deg <= 25.0, "operating_angle_deg",
                operating_angle_deg, "must be in [0, 25] deg (a DOJ articulates to ~25 deg)")
        require(math.isfinite(torque_Nm) and torque_Nm > 0.0, "torque_Nm", torque_Nm, "must be > 0")
        self.geo, self.clearances = geo, clearances
        self.k = stiffness or contact_stiffness(geo, clearances)
        self.theta = math.radians(operating_angle_deg)
        self.torque_Nmm = torque_Nm * 1e3
        self.alpha = math.radians(geo.track_contact_angle_deg)
        self.pcr = geo.pitch_circle_radius_mm
        self.rho = geo.groove_radius_mm - geo.ball_radius_mm
        self.gap = clearances.track_mm * math.cos(self.alpha) / 2.0
        self.e = geo.cage_offset_mm
        self.p_n = hayama_normal_load_N(torque_Nm, geo)
        half = self.theta / 2.0
        self.d_in = np.array([0.0, -math.sin(self.theta), math.cos(self.theta)])
        ez = np.array([0.0, 0.0, 1.0])
        self.inner_centre = -(self.e / math.cos(half)) * self.d_in
        self.cage_centre0 = self.e / (2.0 * math.cos(half)) * (ez - self.d_in)
        self.cage_axis0 = (ez + self.d_in) / np.linalg.norm(ez + self.d_in)
        self.tilt_basis = np.array([[1.0, 0.0, 0.0], np.cross(self.cage_axis0, [1.0, 0.0, 0.0])])
        self.r_tilt = geo.cage_outer_sphere_radius_mm
        self.par = kernel.pack(self.theta, self.alpha, self.pcr, self.rho, self.gap, self.e, self.k.track,
                               self.k.window, self.k.inner_sphere, self.k.outer_sphere, clearances.window_mm / 2.0,
                               clearances.inner_sphere_mm, clearances.outer_sphere_mm, self.torque_Nmm, self.p_n,
                               self.r_tilt, REGULARISATION, self.d_in, self.inner_centre, self.cage_centre0,
                               self.cage_axis0, self.tilt_basis[0], self.tilt_basis[1])

    # -- geometry and equations ---------------------------------------------------------------------------
    def nominal_balls(self, phase: float) -> np.ndarray:
        """Ball centres (6, 3) of the rigid joint without clearance at phase ``phase`` (rad)."""
        psi = phase + 2.0 * np.pi * np.arange(N_BALLS) / N_BALLS
        return self.pcr * np.stack([np.cos(psi), np.sin(psi), np.sin(psi) * math.tan(self.theta / 2.0)], axis=-1)

    def residual(self, phase: float, q: np.ndarray) -> np.ndarray:
        """Equilibrium equations (24,): ball forces / P_n (18), cage forces / P_n (3), cage moments about the two
        axes normal to its axis / (P_n PCR) (2), inner-race torque about d / (P_n PCR) (1). Unknowns ``q``: the
        inner race's wind-up times PCR, the cage translation, its two tilts times its outer radius, the balls'
        displacements from :meth:`nominal_balls` (mm)."""
        return kernel.residual(np.asarray(q, dtype=float), float(phase), self.par)

    def initial_state(self) -> np.ndarray:
        """A start for the first phase: the wind-up that closes both flank gaps and the Hertz approach of P_n."""
        q = np.zeros(N_UNKNOWNS)
        approach = (self.p_n / self.k.track) ** (2.0 / 3.0)
        q[0] = 2.0 * (self.gap + approach) / math.sin(self.alpha)
        return q

    # -- solution -----------------------------------------------------------------------------------------
    def solve(self, phase_deg: float, start: np.ndarray | None = None) -> PhaseResult:
        """Equilibrium at ``phase_deg`` from ``start`` (default :meth:`initial_state`, and when that fails the
        homotopy of :meth:`homotopy_start`): Levenberg-Marquardt (MINPACK, scipy.optimize.least_squares) on the
        central-difference Jacobian of the kernel, restarted once from where it stalled (a contact opening or
        closing at the solution makes the Jacobian jump), accepted when every equation is below
        RESIDUAL_TOLERANCE."""
        phase = math.radians(phase_deg)
        q0 = self.initial_state() if start is None else np.array(start, dtype=float)
        try:
            return self._result(phase_deg, self._least_squares(phase, phase_deg, q0))
        except SolverError:
            if start is not None:
                raise
        return self.homotopy_start(phase_deg)

    def _least_squares(self, phase: float, phase_deg: float, q0: np.ndarray) -> np.ndarray:
        worst, q, evaluations = math.inf, q0, 0
        for scale in (1.0, "jac"):   # the restart rescales the unknowns by the Jacobian's columns
            sol = least_squares(lambda q: kernel.residual(q, phase, self.par), q, method="lm",
                                jac=lambda q: kernel.jacobian(q, phase, self.par, FD_STEP_MM), xtol=1e-15,
                                ftol=1e-15, gtol=1e-15, max_nfev=MAX_EVALUATIONS, x_scale=scale)
            q, evaluations = sol.x, evaluations + sol.nfev
            worst = float(np.abs(sol.fun).max())
            if worst <= RESIDUAL_TOLERANCE:
                return q
        raise SolverError(f"DOJ equilibrium not found at phase {phase_deg:g} deg (largest residual {worst:.2g} "
                          f"of P_n after {evaluations} evaluations)")

    def homotopy_start(self, phase_deg: float) -> PhaseResult:
        """Equilibrium at ``phase_deg`` reached from the joint without clearance at zero operating angle (every
        ball at P_n, :meth:`initial_state` solves it) by scaling the clearances and the angle up together in
        HOMOTOPY_STEPS steps, each halved on failure up to MAX_HALVINGS times; the same unknowns throughout (the
        balls' displacements from their nominal positions at each angle)."""
        angle = math.degrees(self.theta)

        def model(f: float) -> DOJModel:
            return DOJModel(self.geo, self.clearances.scaled(f), angle * f, self.torque_Nmm * 1e-3, self.k)

        def reach(q: np.ndarray, f0: float, f1: float, depth: int) -> np.ndarray:
            try:
                return model(f1)._least_squares(math.radians(phase_deg), phase_deg, q)
            except SolverError:
                if depth >= MAX_HALVINGS:
                    raise
            middle = reach(q, f0, 0.5 * (f0 + f1), depth + 1)
            return reach(middle, 0.5 * (f0 + f1), f1, depth + 1)

        q = model(0.0)._least_squares(math.radians(phase_deg), phase_deg, self.initial_state())
        for k in range(HOMOTOPY_STEPS):
            q = reach(q, k / HOMOTOPY_STEPS, (k + 1) / HOMOTOPY_STEPS, 0)
        return self._result(phase_deg, q)

    def _result(self, phase_deg: float, q: np.ndarray) -> PhaseResult:
        res = np.empty(N_UNKNOWNS)
        f_out, f_in = np.empty((2, N_BALLS, 3)), np.empty((2, N_BALLS, 3))
        p_window, f_ic, f_co = np.empty(N_BALLS), np.empty(3), np.empty(3)
        x, frame = np.empty((N_BALLS, 3)), np.empty((5, 3))
        kernel.evaluate(q, math.radians(phase_deg), self.par, res, f_out, f_in, p_window, f_ic, f_co, x, frame)
        fo, fi = f_out.sum(axis=0), f_in.sum(axis=0)
        no, ni = np.linalg.norm(fo, axis=-1), np.linalg.norm(fi, axis=-1)
        loaded = (no > 1e-9 * self.p_n) & (ni > 1e-9 * self.p_n)
        cosw = np.sum(fo * -fi, axis=-1) / np.where(loaded, no * ni, 1.0)
        wedge = np.where(loaded, np.degrees(np.arccos(np.clip(cosw, -1.0, 1.0))), np.nan)
        t_out = float(np.cross(x, -fo).sum(axis=0)[2]) * 1e-3
        shaft = fi.sum(axis=0) + f_ic  # minus the forces on the inner race (from the balls and the cage)
        axial = -float(fo[:, 2].sum() + f_co[2])   # reaction on the outer race of its forces on balls and cage
        return PhaseResult(phase_deg, np.linalg.norm(f_in, axis=-1).sum(axis=0),
                           np.linalg.norm(f_out, axis=-1).sum(axis=0), p_window, wedge, float(np.linalg.norm(f_ic)),
                           float(np.linalg.norm(f_co)), f_ic, f_co, t_out, shaft, float(frame[4, 0]),
                           float(np.abs(res).max()), q.copy(), axial)

    def _continue(self, previous: PhaseResult, phase_deg: float, depth: int = 0) -> PhaseResult:
        """Equilibrium at ``phase_deg`` continued from ``previous``; when the step is too long for the solver (a
        contact opening or closing on the way), through the half-way phase first (up to MAX_HALVINGS times)."""
        try:
            return self.solve(phase_deg, previous.state)
        except SolverError:
            if depth >= MAX_HALVINGS:
                raise
        middle = self._continue(previous, 0.5 * (previous.phase_deg + phase_deg), depth + 1)
        return self._continue(middle, phase_deg, depth + 1)

    def revolution(self, phases_deg: np.ndarray) -> list[PhaseResult]:
        """Equilibria along ``phases_deg`` (continuation: each from the previous one). The first phase is solved
        directly or, where the solver stalls there (a ball exactly where a contact opens), reached by continuation
        from a nearby phase of START_OFFSETS_DEG; a SolverError names the phases tried when none converges."""
        out = [self._first(float(phases_deg[0]))]
        for phase in phases_deg[1:]:
            out.append(self._continue(out[-1], float(phase)))
        return out

    def _first(self, phase_deg: float) -> PhaseResult:
        try:
            return self.solve(phase_deg)
        except SolverError as exc:
            first_error = exc
        for offset in START_OFFSETS_DEG:
            try:
                return self._continue(self.solve(phase_deg + offset), phase_deg)
            except SolverError:
                continue
        raise SolverError(f"DOJ: no equilibrium to start the revolution at phase {phase_deg:g} deg, nor by "
                          f"continuation from {', '.join(f'{phase_deg + d:g}' for d in START_OFFSETS_DEG)} deg "
                          f"({first_error}); this geometry and clearance set are outside what the solver handles")
