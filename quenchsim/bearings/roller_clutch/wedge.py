"""Two-way roller clutch: roller load from the transmitted torque through the wedge (cam) geometry,
with the elastic take-up of both roller contacts and of the outer ring.

Geometry (one roller of radius r between a cam flat and the outer-race bore of radius R). The flat
lies at the distance h from the clutch axis; the roller touches the bore along the radius through its
centre and the flat along the flat's normal. The wedge angle eps between those two normals obeys

    cos(eps) = (h + r) / (R - r)                                                  (rigid)
    cos(eps) = (h + r - delta_i) / (R + u - r + delta_o)                          (loaded)

with delta_i, delta_o the roller-flat and roller-bore approaches and u the radial expansion of the
bore. A roller loaded only at its two contacts is a two-force member: the two contact forces are
collinear along the chord joining the contact points, which makes the angle eps/2 with each contact
normal, so at both contacts tangential / normal force = tan(eps/2) and the normal loads are equal (N).
The torque about the axis (from the bore contact; the flat contact gives the same) is

    T = n N tan(eps/2) R                                                                          (1)

(n rollers). The roller stays wedged while tan(eps/2) <= mu at both contacts (the design criterion of
frictionally engaged clutches, tan(clamping angle) = F_t / F_n <= mu: N. Nagler, A. Lohrengel, Forsch.
Ingenieurwes. 85 (2021) 1015, eq. 1). Elastic take-up makes eps grow with the load, so the roller load per
unit torque falls as the torque rises -- and the friction the wedge needs rises: :func:`wedge_hold` gives the
margin mu / tan(eps/2) and the torque at which the wedge opens to tan(eps/2) = mu and the rollers slip.

Approach of a steel roller on a steel raceway (per contact; Palmgren's empirical line-contact law,
A. Palmgren, *Ball and Roller Bearing Engineering*, 3rd ed., SKF Industries 1959; as given in
T. A. Harris & M. N. Kotzalas, *Rolling Bearing Analysis*, 5th ed. 2007, vol. 1 ch. 6):

    delta = 3.84e-5 Q^0.9 / l^0.8      (delta in mm, Q in N, l in mm)                             (2)

Bore expansion u: the Lame thick ring under the rollers' radial loads spread as a uniform pressure
p = n N / (2 pi R B) over the ring width B (:func:`quenchsim.bearings.roller_clutch.ring.lame_ring`).

Line-contact stresses: :func:`quenchsim.bearings.hertz.line_contact` (flat: radius 1/0; bore: -R).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from scipy.optimize import brentq

from quenchsim.bearings import hertz
from quenchsim.bearings.roller_clutch.ring import lame_ring
from quenchsim.errors import InputError, SolverError, require

PALMGREN_COEFFICIENT = 3.84e-5
"""mm N^-0.9 mm^0.8: delta = 3.84e-5 Q^0.9 / l^0.8 (Palmgren 1959, Harris & Kotzalas 2007 vol. 1 ch. 6)."""
FLAT_RADIUS_M = 1.0e12
"""Radius standing for the cam flat in the Hertz line contact (curvature 1e-12 1/m: flat to 1e-10 relative)."""


@dataclass(frozen=True)
class ClutchGeometry:
    """A two-way roller clutch with cam flats on the inner race and a cylindrical outer race.

    ``free_wedge_angle_rad`` is the wedge angle eps0 between the flat normal and the bore radius through
    the roller centre with the roller touching both races and no load (it fixes the cam offset h).
    ``ring_width_m`` is the axial width B of the outer ring over which the roller loads spread
    (plane-stress ring)."""

    rollers: int
    roller_diameter_m: float
    roller_length_m: float
    bore_diameter_m: float
    outer_diameter_m: float
    ring_width_m: float
    free_wedge_angle_rad: float
    E_Pa: float
    nu: float

    def __post_init__(self) -> None:
        require(isinstance(self.rollers, int) and not isinstance(self.rollers, bool) and 2 <= self.rollers <= 200,
                "rollers", self.rollers, "must be an integer in [2, 200]")
        for name in ("roller_diameter_m", "roller_length_m", "bore_diameter_m", "outer_diameter_m", "ring_width_m"):
            v = getattr(self, name)
            require(math.isfinite(v) and v > 0.0, name, v, "must be a positive finite length")
        require(self.bore_diameter_m > 2.0 * self.roller_diameter_m, "bore_diameter_m", self.bore_diameter_m,
                f"must exceed twice roller_diameter_m = {self.roller_diameter_m}")
        require(self.outer_diameter_m > self.bore_diameter_m, "outer_diameter_m", self.outer_diameter_m,
                f"must exceed bore_diameter_m = {self.bore_diameter_m}")
        require(math.isfinite(self.free_wedge_angle_rad) and 0.0 < self.free_wedge_angle_rad < math.radians(60.0),
                "free_wedge_angle_rad", self.free_wedge_angle_rad, "must lie in (0, 60 deg)")
        pitch = 2.0 * math.pi * (self.bore_radius_m - self.roller_radius_m)
        require(self.rollers * self.roller_diameter_m < pitch, "rollers", self.rollers,
                f"{self.rollers} rollers of {self.roller_diameter_m} m do not fit on the {pitch:.4g} m pitch circle")
        require(math.isfinite(self.E_Pa) and self.E_Pa > 0.0, "E_Pa", self.E_Pa, "must be a positive modulus")
        require(-1.0 < self.nu < 0.5, "nu", self.nu, "Poisson's ratio must lie in (-1, 0.5)")

    @property
    def roller_radius_m(self) -> float:
        return self.roller_diameter_m / 2.0

    @property
    def bore_radius_m(self) -> float:
        return self.bore_diameter_m / 2.0

    @property
    def cam_offset_m(self) -> float:
        """h = (R - r) cos(eps0) - r: distance of the flat from the clutch axis."""
        return (self.bore_radius_m - self.roller_radius_m) * math.cos(self.free_wedge_angle_rad) - self.roller_radius_m


@dataclass(frozen=True)
class Engagement:
    """A clutch transmitting ``torque_Nm``: roller normal load (the same at both contacts), wedge angle,
    the take-up that opened it, the two Hertz line contacts and the ring's Lame response."""

    torque_Nm: float
    roller_load_N: float
    wedge_angle_rad: float
    traction_ratio: float
    load_per_torque_N_per_Nm: float
    approach_flat_m: float
    approach_bore_m: float
    bore_expansion_m: float
    bore_pressure_Pa: float
    ring_bore_hoop_Pa: float
    inner: hertz.LineContact
    outer: hertz.LineContact


def palmgren_approach_m(load_N: float, length_m: float) -> float:
    """Approach of a steel roller and raceway, delta = 3.84e-5 Q^0.9 / l^0.8 (mm, N, mm), eq. (2).

    >>> round(palmgren_approach_m(29812.0, 0.0209) * 1e3, 4)
    0.0359
    """
    require(math.isfinite(load_N) and load_N >= 0.0, "load_N", load_N, "must be a finite load >= 0")
    require(math.isfinite(length_m) and length_m > 0.0, "length_m", length_m, "must be a positive length")
    return PALMGREN_COEFFICIENT * load_N**0.9 / (length_m * 1e3) ** 0.8 * 1e-3


def roller_contacts(geometry: ClutchGeometry, load_N: float) -> tuple[hertz.LineContact, hertz.LineContact]:
    """Hertz line contacts roller-flat (inner) and roller-bore (outer) under the normal load ``load_N``."""
    g = geometry
    inner = hertz.line_contact(load_N, g.roller_length_m, g.roller_radius_m, FLAT_RADIUS_M, g.E_Pa, g.nu, g.E_Pa, g.nu)
    outer = hertz.line_contact(load_N, g.roller_length_m, g.roller_radius_m, -g.bore_radius_m, g.E_Pa, g.nu,
                               g.E_Pa, g.nu)
    return inner, outer


def wedge_angle_rad(geometry: ClutchGeometry, load_N: float, *, compliant: bool = True) -> float:
    """eps at the roller load ``load_N``: cos(eps) = (h + r - delta_i)/(R + u - r + delta_o) (module docstring)."""
    g = geometry
    if not compliant or load_N == 0.0:
        return g.free_wedge_angle_rad
    delta = palmgren_approach_m(load_N, g.roller_length_m)
    u = _ring(g, load_N).bore_displacement_m
    c = (g.cam_offset_m + g.roller_radius_m - delta) / (g.bore_radius_m + u - g.roller_radius_m + delta)
    return math.acos(max(-1.0, min(1.0, c)))


def _ring(g: ClutchGeometry, load_N: float):
    p = g.rollers * load_N / (2.0 * math.pi * g.bore_radius_m * g.ring_width_m)
    return lame_ring(g.bore_radius_m, g.outer_diameter_m / 2.0, p, g.E_Pa, g.nu)


def torque_Nm(geometry: ClutchGeometry, load_N: float, *, compliant: bool = True) -> float:
    """T = n N tan(eps(N)/2) R, eq. (1)."""
    eps = wedge_angle_rad(geometry, load_N, compliant=compliant)
    return geometry.rollers * load_N * math.tan(eps / 2.0) * geometry.bore_radius_m


def engage(geometry: ClutchGeometry, torque: float, *, compliant: bool = True) -> Engagement:
    """Solve eq. (1) for the roller load at the transmitted torque ``torque`` (N m, > 0).

    T(N) grows monotonically (eps grows with N), so the root is bracketed and unique.
    """
    require(math.isfinite(torque) and torque > 0.0, "torque_Nm", torque, "must be a positive finite torque")
    g = geometry
    rigid = torque / (g.rollers * math.tan(g.free_wedge_angle_rad / 2.0) * g.bore_radius_m)
    if compliant:
        # the take-up only opens the wedge, so T(N) >= the rigid T(N) and the root lies below the rigid load
        if torque_Nm(g, rigid) < torque:
            raise SolverError(f"roller load not bracketed at torque {torque} N m (the wedge closed under load)")
        N = brentq(lambda q: torque_Nm(g, q) - torque, 0.0, rigid, xtol=1e-9, rtol=1e-13)
    else:
        N = rigid
    eps = wedge_angle_rad(g, N, compliant=compliant)
    inner, outer = roller_contacts(g, N)
    ring = _ring(g, N)
    delta = palmgren_approach_m(N, g.roller_length_m) if compliant else 0.0
    return Engagement(torque_Nm=torque, roller_load_N=N, wedge_angle_rad=eps, traction_ratio=math.tan(eps / 2.0),
                      load_per_torque_N_per_Nm=N / torque, approach_flat_m=delta, approach_bore_m=delta,
                      bore_expansion_m=ring.bore_displacement_m if compliant else 0.0,
                      bore_pressure_Pa=ring.pressure_Pa, ring_bore_hoop_Pa=ring.bore_hoop_Pa, inner=inner, outer=outer)


def free_wedge_angle_for(geometry: ClutchGeometry, torque: float, roller_load_N: float) -> float:
    """The free wedge angle eps0 at which ``torque`` gives ``roller_load_N`` (compliant model): the inverse
    of :func:`engage` used to set eps0 from one measured (torque, load) pair."""
    require(math.isfinite(roller_load_N) and roller_load_N > 0.0, "roller_load_N", roller_load_N, "must be positive")
    require(math.isfinite(torque) and torque > 0.0, "torque_Nm", torque, "must be a positive finite torque")
    target = torque / (geometry.rollers * roller_load_N * geometry.bore_radius_m)  # tan(eps/2) needed

    def excess(eps0: float) -> float:
        return math.tan(wedge_angle_rad(replace(geometry, free_wedge_angle_rad=eps0), roller_load_N) / 2.0) - target

    hi = 2.0 * math.atan(target)  # the rigid answer; the compliant eps0 is smaller
    if excess(1e-6) > 0.0:
        raise InputError("roller_load_N", roller_load_N,
                         f"the elastic take-up alone opens the wedge beyond tan(eps/2) = {target:.4g} at this load")
    return brentq(excess, 1e-6, hi, xtol=1e-14)


@dataclass(frozen=True)
class WedgeHold:
    """Self-locking check at one torque: the friction the wedge needs there (tan(eps/2)), the margin
    ``friction / required_friction`` (>= 1: the rollers stay wedged) and the torque at which the growing wedge
    angle reaches tan(eps/2) = friction (0: the free wedge already needs more; inf: not within
    ``HOLD_SEARCH_LOAD_N`` of roller load)."""

    friction: float
    required_friction: float
    margin: float
    holds: bool
    slip_torque_Nm: float
    slip_roller_load_N: float


HOLD_SEARCH_LOAD_N = 1.0e8
"""Largest roller load searched for the slip torque (far beyond any steel contact's static capacity)."""


def wedge_hold(geometry: ClutchGeometry, torque: float, friction: float, *, compliant: bool = True) -> WedgeHold:
    """The self-locking check tan(eps/2) <= friction at ``torque`` and the slip torque (module docstring)."""
    require(math.isfinite(friction) and friction > 0.0, "friction", friction, "must be a positive friction coefficient")
    e = engage(geometry, torque, compliant=compliant)
    needed = e.traction_ratio

    def excess(load: float) -> float:
        return math.tan(wedge_angle_rad(geometry, load, compliant=compliant) / 2.0) - friction

    if excess(0.0) >= 0.0:
        slip_load, slip_torque = 0.0, 0.0
    else:
        load = max(e.roller_load_N, 1.0)
        while excess(load) < 0.0 and load < HOLD_SEARCH_LOAD_N:
            load *= 2.0
        if excess(load) < 0.0:
            slip_load, slip_torque = math.inf, math.inf
        else:
            slip_load = brentq(excess, 0.0, load, xtol=1e-6, rtol=1e-12)
            slip_torque = torque_Nm(geometry, slip_load, compliant=compliant)
    return WedgeHold(friction, needed, friction / needed, needed <= friction, slip_torque, slip_load)


def roller_from_line_contact(load_N: float, p_max_Pa: float, depth_max_shear_m: float,
                             E_Pa: float, nu: float) -> tuple[float, float]:
    """Inverse Hertz line contact of a roller on a flat: the roller radius and contact length that give the
    peak pressure ``p_max_Pa`` and the depth of the maximum shear ``depth_max_shear_m`` under ``load_N``.

    b = z / 0.7862, w = pi b p_max / 2, L = Q / w, r = pi E' b^2 / (8 w) (Johnson 1985 eqs. 4.43-4.49).

    >>> r, L = roller_from_line_contact(29812.0, 3144e6, 0.227e-3, 2.08e11, 0.3)
    >>> round(r * 1e3, 2), round(L * 1e3, 1)
    (5.25, 20.9)
    """
    for name, v in (("load_N", load_N), ("p_max_Pa", p_max_Pa), ("depth_max_shear_m", depth_max_shear_m)):
        require(math.isfinite(v) and v > 0.0, name, v, "must be positive and finite")
    b = depth_max_shear_m / hertz.LINE_SHEAR_DEPTH_RATIO
    w = math.pi * b * p_max_Pa / 2.0
    E_eff = hertz.effective_modulus_Pa(E_Pa, nu, E_Pa, nu)
    return math.pi * E_eff * b * b / (8.0 * w), load_N / w
