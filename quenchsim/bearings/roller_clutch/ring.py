"""Outer ring of a roller clutch in plane stress: the Lame thick ring under a uniform bore pressure and the
exact series solution for n equally spaced roller loads (Michell's solution of the annulus).

Lame (S. Timoshenko & J. N. Goodier, *Theory of Elasticity*, 3rd ed. 1970, sec. 28), bore radius a,
outer radius b, bore pressure p, plane stress:

    sigma_rr = A + B/r^2,  sigma_tt = A - B/r^2,  A = p a^2/(b^2 - a^2),  B = -p a^2 b^2/(b^2 - a^2)
    u_r = ((1 - nu) A r - (1 + nu) B / r) / E
    bore: sigma_tt = p f, u_r = p a (f + nu) / E,  f = (b^2 + a^2)/(b^2 - a^2)

Discrete loads (J. H. Michell, Proc. Lond. Math. Soc. 31 (1899) 100; the stress function and stresses of
J. R. Barber, *Elasticity*, 3rd ed., Springer 2010, ch. 8, Table 8.1): n rollers at theta_j = 2 pi j / n press
the bore with Hertz strips of half-width c (angle beta = c/a) carrying W per unit axial width, with the
tangential traction ``traction_ratio`` x the pressure (friction of the wedged roller, drive direction +theta);
the torque is reacted by a uniform shear on the outer surface. The bore tractions expand in the harmonics
k = 0, n, 2n, ...; the pressure harmonics of a train of semi-elliptical strips are

    q_0 = n W / (2 pi a),   q_k = 2 q_0 * 2 J1(k beta)/(k beta)

For k >= 2 each harmonic takes phi = (A r^(k+2) + B r^(2-k) + C r^k + D r^-k) cos(k theta) (and its sine
twin for the shear tractions), four constants from the four traction conditions; displacements follow by
integrating the plane-stress strains (no rigid-body term for k >= 2). k = 0 is Lame plus the torsion field
sigma_rt = C0 / r^2. The powers are scaled by the bore or outer radius so that no term overflows.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.special import j1

from quenchsim.errors import require

STRIP_SERIES_END = 80.0
"""Harmonics are summed up to k beta = 80: the strip coefficients 2 J1(x)/x have fallen below 2e-3 of q_0."""


@dataclass(frozen=True)
class LameRing:
    """Lame thick ring under bore pressure ``pressure_Pa`` (plane stress)."""

    pressure_Pa: float
    bore_displacement_m: float
    bore_hoop_Pa: float
    outer_displacement_m: float
    outer_hoop_Pa: float
    hoop_factor: float


def lame_ring(bore_radius_m: float, outer_radius_m: float, pressure_Pa: float, E_Pa: float, nu: float) -> LameRing:
    """Bore and outer-surface radial displacement and hoop stress of the Lame ring (module docstring).

    >>> r = lame_ring(0.0475, 0.064, 40e6, 2.08e11, 0.3)
    >>> round(r.hoop_factor, 3), round(r.bore_hoop_Pa / 1e6, 1), round(r.bore_displacement_m * 1e6, 2)
    (3.453, 138.1, 34.28)
    """
    a, b = bore_radius_m, outer_radius_m
    require(math.isfinite(a) and a > 0.0, "bore_radius_m", a, "must be a positive length")
    require(math.isfinite(b) and b > a, "outer_radius_m", b, f"must exceed bore_radius_m = {a}")
    require(math.isfinite(pressure_Pa), "pressure_Pa", pressure_Pa, "must be finite")
    f = (b * b + a * a) / (b * b - a * a)
    return LameRing(pressure_Pa=pressure_Pa, bore_displacement_m=pressure_Pa * a * (f + nu) / E_Pa,
                    bore_hoop_Pa=pressure_Pa * f, outer_displacement_m=2.0 * pressure_Pa * a * a * b / (E_Pa * (b * b - a * a)),
                    outer_hoop_Pa=2.0 * pressure_Pa * a * a / (b * b - a * a), hoop_factor=f)


@dataclass(frozen=True)
class RingField:
    """Displacements (m) and stresses (Pa) at the requested points (arrays of the broadcast shape)."""

    u_r: np.ndarray
    u_t: np.ndarray
    s_rr: np.ndarray
    s_tt: np.ndarray
    s_rt: np.ndarray


class DiscreteLoadRing:
    """Michell series solution of a plane-stress annulus loaded at the bore by n Hertz strips (module docstring).

    ``load_per_width_N_m``: W, the normal load of one roller per unit axial width; ``strip_half_width_m``: c;
    ``traction_ratio``: tangential / normal traction at the strips (>= 0, drive direction +theta).
    """

    def __init__(self, bore_radius_m: float, outer_radius_m: float, rollers: int, load_per_width_N_m: float,
                 strip_half_width_m: float, E_Pa: float, nu: float, traction_ratio: float = 0.0) -> None:
        a, b = bore_radius_m, outer_radius_m
        require(math.isfinite(a) and a > 0.0, "bore_radius_m", a, "must be a positive length")
        require(math.isfinite(b) and b > a, "outer_radius_m", b, f"must exceed bore_radius_m = {a}")
        require(isinstance(rollers, int) and rollers >= 2, "rollers", rollers, "must be an integer >= 2")
        require(math.isfinite(strip_half_width_m) and 0.0 < strip_half_width_m < math.pi * a / rollers,
                "strip_half_width_m", strip_half_width_m, f"must lie in (0, pi a / n = {math.pi * a / rollers:.4g} m)")
        require(math.isfinite(traction_ratio) and traction_ratio >= 0.0, "traction_ratio", traction_ratio,
                "must be >= 0")
        self.a, self.b, self.n, self.E, self.nu = a, b, rollers, E_Pa, nu
        self.beta = strip_half_width_m / a
        q0 = rollers * load_per_width_N_m / (2.0 * math.pi * a)
        t0 = traction_ratio * q0
        # k = 0: Lame (sigma_rr(a) = -q0, sigma_rr(b) = 0) and torsion (sigma_rt(a) = -t0)
        self.A0 = q0 * a * a / (b * b - a * a)
        self.B0 = -q0 * a * a * b * b / (b * b - a * a)
        self.C0 = -t0 * a * a
        m = np.arange(1, max(2, int(math.ceil(STRIP_SERIES_END / (rollers * self.beta)))) + 1)
        self.k = (rollers * m).astype(float)
        x = self.k * self.beta
        qk = 2.0 * q0 * 2.0 * j1(x) / x
        tk = traction_ratio * qk
        # boundary rows: sigma_rr amplitude at a and b, sigma_rt amplitude at a and b
        ea, aa, _, ca = self._basis(a)
        eb, ab, _, cb = self._basis(b)
        M = np.stack([aa, ab, ca, cb], axis=1)  # (K, 4 conditions, 4 constants)
        rhs_cos = np.zeros((self.k.size, 4))
        rhs_cos[:, 0] = -qk                      # sigma_rr(a) = -q_k cos
        rhs_sin = np.zeros((self.k.size, 4))
        rhs_sin[:, 2] = tk                       # sine twin: sigma_rt = -(c . D) cos, = -t_k cos at a
        self.c_cos = np.linalg.solve(M, rhs_cos[..., None])[..., 0]
        self.c_sin = np.linalg.solve(M, rhs_sin[..., None])[..., 0]

    def _basis(self, r: np.ndarray | float) -> tuple[np.ndarray, ...]:
        """Exponents e and the amplitudes of sigma_rr, sigma_tt, sigma_rt per unit (scaled) constant,
        shaped (..., K, 4) for r of shape (...)."""
        k = self.k
        e = np.stack([k + 2.0, 2.0 - k, k, -k], axis=-1)
        a_ = np.stack([-(k + 1) * (k - 2), -(k + 2) * (k - 1), -k * (k - 1), -k * (k + 1)], axis=-1)
        b_ = np.stack([(k + 2) * (k + 1), (k - 1) * (k - 2), k * (k - 1), k * (k + 1)], axis=-1)
        c_ = np.stack([k * (k + 1), -k * (k - 1), k * (k - 1), -k * (k + 1)], axis=-1)
        rs = np.array([self.b, self.a, self.b, self.a])
        r = np.asarray(r, dtype=float)[..., None, None]
        s = (r / rs) ** (e - 2.0)
        return e, a_ * s, b_ * s, c_ * s

    def field(self, r: np.ndarray | float, theta: np.ndarray | float) -> RingField:
        """u_r, u_theta, sigma_rr, sigma_tt, sigma_rt at (r, theta) (theta = 0 at a roller)."""
        r, theta = np.broadcast_arrays(np.asarray(r, dtype=float), np.asarray(theta, dtype=float))
        E, nu, G = self.E, self.nu, self.E / (2.0 * (1.0 + self.nu))
        u_r = ((1.0 - nu) * self.A0 * r - (1.0 + nu) * self.B0 / r) / E
        u_t = -self.C0 / (2.0 * G * r)
        s_rr = self.A0 + self.B0 / r**2
        s_tt = self.A0 - self.B0 / r**2
        s_rt = self.C0 / r**2
        e, sa, sb, sc = self._basis(r)
        rr = r[..., None, None]
        f = (sa - nu * sb) / E * rr / (e - 1.0)                  # u_r amplitude per constant
        h = ((sb - nu * sa) / E * rr - f) / self.k[:, None]      # u_theta amplitude per constant
        kt = self.k * theta[..., None]
        ck, sk = np.cos(kt), np.sin(kt)

        def amp(x: np.ndarray, coef: np.ndarray) -> np.ndarray:
            return np.einsum("...kj,kj->...k", x, coef)

        u_r = u_r + np.sum(amp(f, self.c_cos) * ck + amp(f, self.c_sin) * sk, axis=-1)
        u_t = u_t + np.sum(amp(h, self.c_cos) * sk - amp(h, self.c_sin) * ck, axis=-1)
        s_rr = s_rr + np.sum(amp(sa, self.c_cos) * ck + amp(sa, self.c_sin) * sk, axis=-1)
        s_tt = s_tt + np.sum(amp(sb, self.c_cos) * ck + amp(sb, self.c_sin) * sk, axis=-1)
        s_rt = s_rt + np.sum(amp(sc, self.c_cos) * sk - amp(sc, self.c_sin) * ck, axis=-1)
        return RingField(u_r, u_t, s_rr, s_tt, s_rt)


@dataclass(frozen=True)
class RingResponse:
    """The measures a designer reads off the ring: bore radial displacement under a roller and midway between
    two, hoop stress at the bore midway and at the outer surface under a roller and midway, and their
    largest tensile value (the contact zone itself, a Hertz field, is not a ring stress)."""

    bore_u_at_roller_m: float
    bore_u_between_m: float
    bore_hoop_between_Pa: float
    outer_hoop_at_roller_Pa: float
    outer_hoop_between_Pa: float
    max_hoop_Pa: float


def ring_response(ring: DiscreteLoadRing) -> RingResponse:
    """The :class:`RingResponse` of a discrete-load ring (theta = 0 under a roller, pi/n midway)."""
    mid = math.pi / ring.n
    f = ring.field(np.array([ring.a, ring.a, ring.b, ring.b]), np.array([0.0, mid, 0.0, mid]))
    hoops = (float(f.s_tt[1]), float(f.s_tt[2]), float(f.s_tt[3]))
    return RingResponse(bore_u_at_roller_m=float(f.u_r[0]), bore_u_between_m=float(f.u_r[1]),
                        bore_hoop_between_Pa=hoops[0], outer_hoop_at_roller_Pa=hoops[1],
                        outer_hoop_between_Pa=hoops[2], max_hoop_Pa=max(hoops))
