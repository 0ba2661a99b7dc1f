"""Linearised gas film: frequency-dependent stiffness and damping by first-order perturbation (Lund's method).

Lund (1968, "Calculation of stiffness and damping properties of gas bearings", J. Lubr. Technol. 90, 793-803)
perturbs the compressible Reynolds equation about the static film: the rotor centre moves by a small
harmonic displacement (da, db) exp(i tau T) about its static position, P = P0 + dP exp(i tau T), and the
first-order equation for dP is linear with complex coefficients; the film force of dP gives the
impedance. Here the perturbation is taken of the *discrete* equations the static and orbit solvers use
(finite volumes, reynolds.py / transient.py, semi-discrete form Lambda d(V P)/dT + Flux(P; H) = 0 per control
volume):

    [dFlux/dP + i tau Lambda diag(V0)] dP = -(dFlux/da_k + i tau Lambda (dV/da_k) P0)     (k = a, b)

with dFlux/dP and dFlux/da_k the derivatives of the full discrete flux, the upwind weights' dependence on P and
H included (central differences, step 1e-7: the Jacobian by a 12-colouring of the 9-point stencil, 24 flux
evaluations). One complex sparse LU per frequency.

Dimensionless impedance (sleeve frame): F = -Z e with F = force / (pa L D), e = displacement / c,
Z = K + i gamma C, gamma = whirl frequency / rotor speed (tau = 2 gamma in T = omega t / 2); K = k c / (pa L D),
C = d omega c / (pa L D) (Lund's normalisation).

Grooved rotor: the film is steady only in the rotor frame, and only at the concentric position (a grooved
rotor off-centre has a film periodic in time); there the impedance is computed in the (mirrored) rotor grid
frame and carried to the sleeve frame: a forward whirl exp(i tau T) of the sleeve frame is a forward whirl
exp(i (2 - tau) T) of the mirrored rotor frame, and with N_g >= 3 grooves the rotor-frame impedance is
isotropic, so Z_forward(gamma) = conj(Zg_forward(2 - 2 gamma)) and Z_backward(gamma) = Zg_forward(2 + 2 gamma)
(forward / backward: the eigenvalues of the 2 x 2 impedance on the eigenvectors (1, -i) / (1, i)).
"""

from __future__ import annotations

import cmath
import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from quenchsim.bearings.gas_journal.film import FilmFrame, film_hierarchy
from quenchsim.bearings.gas_journal.forces import attitude_deg, film_force
from quenchsim.bearings.gas_journal.geometry import Bearing, grid_for_level
from quenchsim.bearings.gas_journal.reynolds import check_inputs, operator_hierarchy, solve
from quenchsim.bearings.gas_journal.operator import Operator
from quenchsim.bearings.gas_journal.solvers import newton_direct
from quenchsim.bearings.gas_journal.transient import film_frame
from quenchsim.errors import SolverError, require

BASE_TOLERANCE = 1e-10  # ||R||_2 of the static film the perturbation is taken about
FD_STEP = 1e-7  # central-difference step of the flux derivatives (P ~ 1, displacement ~ 1)
ISOTROPY_TOLERANCE = 1e-6  # grooved rotor: largest relative anisotropy of the rotor-frame impedance accepted


@dataclass(frozen=True)
class DynamicCoefficients:
    """Stiffness K and damping C (2 x 2, F = -(K e + C de/dt), rows/columns x, y of the frame they are given
    in) at whirl ratio gamma; K = k c / (pa L D), C = d omega c / (pa L D)."""

    whirl_ratio: float
    stiffness: np.ndarray
    damping: np.ndarray

    @property
    def impedance(self) -> np.ndarray:
        return self.stiffness + 1j * self.whirl_ratio * self.damping


def concentric_impedance(bearing_number: float, length_to_diameter: float, whirl_ratio: complex) -> tuple[complex, complex]:
    """Forward and backward whirl impedance (Z_f, Z_b) of the concentric plain bearing, closed form: the
    eigenvalues of its 2 x 2 impedance on the eigenvectors (1, -i) (forward) and (1, i) (backward).

    The first-order (linearised "ph", Ausman 1961, J. Basic Eng. 83, 188) perturbation of P = 1, H = 1 by a
    circular whirl e = eps exp(i gamma omega t): p1 = Re(f(Z) exp(i (theta - 2 gamma T))) with
    f'' - (1 + i L') f = -i L' eps, L' = Lambda (1 - 2 gamma) (the whirl removes 2 gamma of the rotor's
    wedge: at half-frequency whirl the film carries no force), f = 0 at the ends. With
    g(l) = i l / (1 + i l) (1 - tanh(k L/D) / (k L/D)), k = sqrt(1 + i l):
    Z_f = (pi / 2) conj(g(Lambda (1 - 2 gamma))), Z_b = (pi / 2) g(Lambda (1 + 2 gamma)); written here in the
    form analytic in gamma, so a complex ``whirl_ratio`` gives the growing or decaying whirl. At gamma = 0
    this is Ausman's small-eccentricity load F / eps = |Z_f(0)| (0.3745 Lambda for L/D = 1 at small Lambda).

    >>> zf, zb = concentric_impedance(1.0, 1.0, 0.5)
    >>> abs(zf) < 1e-15
    True
    """
    def g(l: complex, sign: float) -> complex:
        if l == 0:
            return 0j
        k = cmath.sqrt(1.0 + sign * 1j * l)
        kl = k * length_to_diameter
        return 0.5 * math.pi * sign * 1j * l / (1.0 + sign * 1j * l) * (1.0 - cmath.tanh(kl) / kl)

    return (g(bearing_number * (1.0 - 2.0 * whirl_ratio), -1.0), g(bearing_number * (1.0 + 2.0 * whirl_ratio), 1.0))


class LinearisedFilm:
    """The static film of ``bearing`` at ``eccentricity`` (rotor displaced towards ``displacement_angle_deg``,
    sleeve frame) and its first-order perturbation on grid ``level``.

    ``load``, ``force`` and ``attitude_deg`` are those of the static film (force = film force on the rotor,
    the external load is its opposite).
    """

    def __init__(self, bearing: Bearing, bearing_number: float, eccentricity: float,
                 displacement_angle_deg: float = -90.0, level: int = 4) -> None:
        check_inputs(bearing_number, eccentricity)
        require(bearing_number > 0.0, "bearing_number", bearing_number, "must be > 0 (a film without rotation "
                "has no stiffness)")
        self.rotor_frame = bearing.grooved_rotor
        if self.rotor_frame:
            assert bearing.grooves is not None   # a grooved rotor has grooves
            require(eccentricity == 0.0, "eccentricity", eccentricity, "must be 0 for grooves on the rotor (the "
                    "film of an off-centre grooved rotor is periodic in time, not steady)")
            require(bearing.grooves.count >= 3, "grooves.count", bearing.grooves.count,
                    "must be >= 3 for the linearised grooved rotor (an isotropic rotor-frame impedance)")
        self.bearing = bearing
        self.lam = float(bearing_number)
        self.grid = grid_for_level(level, bearing)
        angle = math.radians(displacement_angle_deg)
        self.displacement = (eccentricity * math.cos(angle), eccentricity * math.sin(angle))
        frame = film_frame(bearing, 0.0)
        ops = operator_hierarchy(bearing, self.grid, self.lam, self.displacement, frame)
        first = solve(ops, "multigrid")
        polished = newton_direct(ops[0], first.p, np.zeros(first.p.shape), tol=BASE_TOLERANCE)
        if not polished.converged:
            raise SolverError(f"static film not converged to ||R||_2 <= {BASE_TOLERANCE:g} "
                              f"(stopped at {polished.residual:.3g})")
        self.p0 = polished.p
        self.force = film_force(self.grid, self.p0, frame)
        self.load = float(np.hypot(*self.force))
        self.attitude_deg = attitude_deg(np.array(self.displacement), self.force) if eccentricity > 0 else float("nan")
        geo = film_hierarchy(self.grid, bearing.grooves)[0]
        self._geo = geo
        self._grid_displacement = frame.grid_displacement(self.displacement)
        self._jacobian = self._flux_jacobian()
        h = FD_STEP
        dflux = []
        for k in range(2):
            plus, minus = list(self._grid_displacement), list(self._grid_displacement)
            plus[k] += h
            minus[k] -= h
            dflux.append(((self._flux(self.p0, (plus[0], plus[1])) - self._flux(self.p0, (minus[0], minus[1])))
                          / (2.0 * h))[1:].ravel())
        self._dflux = np.array(dflux)
        self._dvolume_p0 = np.array([(dv * self.p0)[1:].ravel() for dv in geo.volume_derivatives()])
        self._volume = geo.volume(self.displacement, frame)[1:].ravel()

    def _flux(self, p: np.ndarray, grid_displacement: tuple[float, float] | None = None) -> np.ndarray:
        """Outflow of every control volume (the steady operator, upwind weights from ``p``), grid-frame film."""
        disp = self._grid_displacement if grid_displacement is None else grid_displacement
        op = Operator(self.grid, self._geo.coefficients(disp, FilmFrame()), self.lam, np.zeros(p.shape))
        op.update_weights(p)
        return op.apply(p)

    def _flux_jacobian(self) -> sp.csc_matrix:
        """dFlux/dP on the unknowns (rows 1..n_eta, row-major) by central differences, one colour at a time:
        nodes 3 rows and 4 columns apart share no cell, so one perturbed evaluation gives all their columns."""
        ny, nx = self.p0.shape
        require(nx % 4 == 0, "level", self.grid, "must be >= 2 (the colouring needs a multiple of 4 cells around)")
        jj, ii = np.meshgrid(np.arange(ny), np.arange(nx), indexing="ij")
        rows, cols, vals = [], [], []
        for cj in range(3):
            for ci in range(4):
                colour = (jj % 3 == cj) & (ii % 4 == ci) & (jj >= 1)
                if not colour.any():
                    continue
                h = FD_STEP
                diff = (self._flux(self.p0 + h * colour) - self._flux(self.p0 - h * colour)) / (2.0 * h)
                cj_, ci_ = jj[colour], ii[colour]
                for dj in (-1, 0, 1):
                    for di in (-1, 0, 1):
                        rj, ri = cj_ + dj, (ci_ + di) % nx
                        ok = (rj >= 1) & (rj < ny)
                        rows.append((rj[ok] - 1) * nx + ri[ok])
                        cols.append((cj_[ok] - 1) * nx + ci_[ok])
                        vals.append(diff[rj[ok], ri[ok]])
        n = (ny - 1) * nx
        return sp.csc_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))

    def grid_impedance(self, tau: complex) -> np.ndarray:
        """2 x 2 complex impedance in the grid frame at frequency ``tau`` (per unit T), F_grid = -Zg e_grid."""
        mass = 1j * tau * self.lam
        matrix = (self._jacobian + sp.diags(mass * self._volume)).tocsc()
        rhs = -(self._dflux + mass * self._dvolume_p0).T
        # minimum-degree ordering on A + A^T: COLAMD (the default) fills in badly on this periodic, skewed
        # stencil (level 5: 7 s against 0.2 s per factorisation, measured)
        dp = spla.splu(matrix, permc_spec="MMD_AT_PLUS_A").solve(rhs.astype(complex))
        z = np.empty((2, 2), dtype=complex)
        shape = (self.p0.shape[0] - 1, self.p0.shape[1])
        for k in range(2):
            field = np.zeros(self.p0.shape, dtype=complex)
            field[1:] = dp[:, k].reshape(shape)
            f_re = film_force(self.grid, 1.0 + field.real, FilmFrame())
            f_im = film_force(self.grid, 1.0 + field.imag, FilmFrame())
            z[:, k] = -(f_re + 1j * f_im)
        return z

    def _rotor_forward(self, tau_grid: complex) -> complex:
        z = self.grid_impedance(tau_grid)
        v = z @ np.array([1.0, -1j])
        lam = v[0]
        defect = abs(v[1] + 1j * lam) / max(abs(lam), 1e-300)
        if defect > ISOTROPY_TOLERANCE:
            raise SolverError(f"rotor-frame impedance not isotropic (relative defect {defect:.2g}): the groove "
                              "count must divide the grid's cells around")
        return complex(lam)

    def impedance(self, whirl_ratio: complex) -> np.ndarray:
        """2 x 2 complex impedance Z = K + i gamma C in the sleeve frame at whirl ratio ``whirl_ratio`` (complex:
        its analytic continuation, a whirl exp(i 2 gamma T) growing at the rate -2 Im(gamma) per unit T)."""
        tau = 2.0 * whirl_ratio
        if not self.rotor_frame:
            return self.grid_impedance(tau)
        zf = np.conj(self._rotor_forward(np.conj(2.0 - tau)))
        zb = self._rotor_forward(2.0 + tau)
        a, b = 0.5 * (zf + zb), 0.5j * (zf - zb)
        return np.array([[a, b], [-b, a]])

    def coefficients(self, whirl_ratio: float, frame_angle_deg: float = 0.0) -> DynamicCoefficients:
        """Stiffness and damping at ``whirl_ratio`` (> 0) in axes turned by ``frame_angle_deg`` from the sleeve's
        x axis (e.g. the load direction, for Lund's axes: x along the load)."""
        require(whirl_ratio > 0.0, "whirl_ratio", whirl_ratio, "must be > 0 (damping is the imaginary part / gamma)")
        c, s = math.cos(math.radians(frame_angle_deg)), math.sin(math.radians(frame_angle_deg))
        rot = np.array([[c, -s], [s, c]])
        z = rot.T @ self.impedance(whirl_ratio) @ rot
        return DynamicCoefficients(whirl_ratio, z.real, z.imag / whirl_ratio)
