"""Local oil flow at the boundary points of a section: nozzle jets, wall jets, part rotation.

The section is axisymmetric, so every quantity is the circumferential average seen by a point of
the rotating ring. Each flow source (one nozzle row, or the rotation) gives every boundary point a
local speed U_i and a run length x_i (distance the boundary layer has developed over); the HTC
model turns each pair into a forced-convection coefficient.

Jet rows (see quenchsim.bath.correlations for the constants and sources):
1. Free jet from the exit to the surface, penetration y = standoff / cos(inclination). A vertical cross-flow
   U_x on the row's side (``id_crossflow_up_m_s``: the oil rising in the bore as the ring heats it; the
   report saw weak ID jets bend before the bore, strong ones hit it and rise) makes the jet drift
   x = R d (y/(A R d))^(1/m), R = U_0/|U_x| (Pratte & Baines 1967): the jet travels H = sqrt(y^2 + x^2)
   and arrives weaker (the shift of its impact point is not modelled: it would let a faster jet lower the
   HTC of points near the slow jet's impact). Arrival centre-line speed U_a = U_0 min(1, B d/H) (potential
   core, then 1/x decay); arrival half-width b = max(d/2, S H). The cross-flow itself is the buoyant
   flow along the hot part, already in the natural-convection coefficient.
2. Impingement at height z_imp = height - standoff tan(inclination) on the face the row aims at
   (the bore for "id" rows, the OD for "od" rows). The momentum flux of the row, N rho U_0^2 pi d^2/4
   (conserved along a free jet), spread over the circumference 2 pi r_imp, leaves the impact line as
   two plane wall jets, up and down, carrying the shares (1 -+ sin(inclination))/2 -- a jet aimed
   downward sends more of its oil toward the turntable, as the report's lower OD row does.
3. Wall-jet run: at distance s from the impact point (straight distance in the section plane, which
   follows the surface on convex faces) U = min(U_a, 3.5 sqrt(J'_share/(rho (s + b)))) and x = s + b
   (the stagnation zone of width b is the boundary layer's origin).
4. Faces: a point whose outward normal faces the jet (n . -e_jet > 0) gets the full wall jet scaled by
   that cosine; faces turned about 90 deg away (the top and bottom faces) get the fraction
   ``corner_carryover`` of it (a wall jet partly stays attached round a convex edge, Coanda effect);
   faces turned away from the row (the opposite side of the wall) get nothing.

Rotation: relative speed U_rot = omega r (1 - oil_swirl_fraction) along the surface, run length the
circumferential pitch of the facing nozzle row (each jet crossing restarts the boundary layer), or
the full circumference where no row faces the point.

Bulk agitation (``agitation_m_s``, a tank agitator's oil speed past the work): one more source, the same speed at
every point, run length the section height on vertical faces and half the radial width on horizontal ones (the
flow sweeps the whole face; the lengths of the natural-convection correlations).

The part's support (``support``): on a turntable or fixture the bottom face's points (outward normal down, at z_min)
exchange heat only on the open fraction ``turntable_open_fraction`` of their area (the rest is covered and treated
as adiabatic); a hanging part is open on every face (fraction 1).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from quenchsim.bath.config import BathConfig, NozzleRow
from quenchsim.bath.correlations import (crossflow_drift, jet_centreline_velocity, jet_half_width,
                                         plane_wall_jet_velocity)
from quenchsim.geometry.boundary import BoundaryPoints

VERTICAL_NZ = 0.7
"""|n_z| below this: the face is treated as vertical (natural convection along the section height)."""
FACING_COSINE = 0.5
"""n . -e_jet above this: the point lies on the face a row aims at (used to locate the impact point)."""
AWAY_COSINE = -0.5
"""n . -e_jet below this: the face is turned away from the row and gets none of its wall jet."""


@dataclass(frozen=True)
class LocalFlow:
    """Local flow per boundary point; per-source arrays are shaped (n_sources, n_points)."""

    source_names: tuple[str, ...]
    speed_m_s: np.ndarray
    run_length_m: np.ndarray
    natural_length_m: np.ndarray
    orientation: np.ndarray
    exposed_fraction: np.ndarray

    @property
    def velocity_m_s(self) -> np.ndarray:
        """Resultant local speed sqrt(sum_i U_i^2) (the jets' wall flow and the rotation are roughly orthogonal)."""
        return np.sqrt(np.sum(self.speed_m_s**2, axis=0))

    @property
    def length_m(self) -> np.ndarray:
        """Run length of the fastest source at each point (for display)."""
        idx = np.argmax(self.speed_m_s, axis=0)
        return self.run_length_m[idx, np.arange(idx.size)]


def _jet_direction(row: NozzleRow) -> tuple[float, float]:
    """Unit vector (r, z) of a row's jet axis (downward for a positive inclination)."""
    radial = 1.0 if row.side == "id" else -1.0
    return radial * np.cos(row.inclination_rad), -np.sin(row.inclination_rad)


def _row_flow(cfg: BathConfig, row: NozzleRow, pts: BoundaryPoints) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Wall-jet speed, run length and face factor of one row at every point."""
    er, _ = _jet_direction(row)
    facing = -(pts.normal_r * er)  # cosine between the outward normal and the direction back to the nozzle (horizontal)
    n = len(pts)
    on_face = facing > FACING_COSINE
    if not np.any(on_face) or row.jet_speed_m_s == 0.0:
        return np.zeros(n), np.ones(n), np.zeros(n)
    U_cross = cfg.crossflow_up_m_s[row.side]
    drift = crossflow_drift(row.jet_speed_m_s, row.diameter_m, row.standoff_m / np.cos(row.inclination_rad), U_cross)
    travel = np.hypot(row.standoff_m / np.cos(row.inclination_rad), drift)
    z_imp = pts.extent.z_min_m + row.height_m - row.standoff_m * np.tan(row.inclination_rad)
    face_idx = np.flatnonzero(on_face)
    r_imp = pts.r_m[face_idx[np.argmin(np.abs(pts.z_m[face_idx] - z_imp))]]
    U_a = float(jet_centreline_velocity(row.jet_speed_m_s, row.diameter_m, travel))
    b = float(jet_half_width(row.diameter_m, travel))
    momentum = row.count * cfg.liquid.density_kg_m3 * row.jet_speed_m_s**2 * np.pi * row.diameter_m**2 / 4.0
    J_per_width = momentum / (2.0 * np.pi * r_imp)
    sin_inc = np.sin(row.inclination_rad)
    share = np.where(pts.z_m < z_imp, 0.5 * (1.0 + sin_inc), 0.5 * (1.0 - sin_inc))
    s = np.hypot(pts.r_m - r_imp, pts.z_m - z_imp)
    x = s + b
    U = np.minimum(U_a, plane_wall_jet_velocity(share * J_per_width, cfg.liquid.density_kg_m3, x))
    factor = np.where(facing > AWAY_COSINE, np.maximum(facing, cfg.corner_carryover), 0.0)
    return U * factor, x, factor


def local_flow(cfg: BathConfig, pts: BoundaryPoints) -> LocalFlow:
    """Local speeds and lengths of every flow source at every boundary point (built once per stage)."""
    ext = pts.extent
    speeds, lengths, names = [], [], []
    pitch_count = np.zeros(len(pts))
    for row in cfg.rows:
        U, x, factor = _row_flow(cfg, row, pts)
        speeds.append(U)
        lengths.append(x)
        names.append(row.name)
        pitch_count = np.where(factor > 0.0, np.maximum(pitch_count, row.count), pitch_count)
    circumference = 2.0 * np.pi * np.maximum(pts.r_m, 1e-6)
    speeds.append(cfg.omega_rad_s * pts.r_m * (1.0 - cfg.oil_swirl_fraction))
    lengths.append(circumference / np.maximum(pitch_count, 1.0))
    names.append("rotation")
    vertical = np.abs(pts.normal_z) < VERTICAL_NZ
    height = ext.z_max_m - ext.z_min_m
    half_width = 0.5 * (ext.r_max_m - ext.r_min_m)
    if cfg.agitation_m_s > 0.0:
        speeds.append(np.full(len(pts), cfg.agitation_m_s))
        lengths.append(np.where(vertical, height, half_width))
        names.append("agitation")
    orientation = np.where(vertical, 0, np.sign(pts.normal_z)).astype(int)
    tol = 1e-6 + 1e-3 * height
    on_table = (pts.normal_z < -VERTICAL_NZ) & (pts.z_m - ext.z_min_m < tol)
    return LocalFlow(source_names=tuple(names), speed_m_s=np.array(speeds), run_length_m=np.array(lengths),
                     natural_length_m=np.where(vertical, height, half_width), orientation=orientation,
                     exposed_fraction=np.where(on_table, cfg.turntable_open_fraction, 1.0))
