"""Local oil flow at the boundary points of a section: nozzle jets, wall jets, part rotation.

The section is axisymmetric, so every quantity is the circumferential average seen by a point of
the rotating ring: the ring turns past the fixed nozzles, so a point at a given height sees every jet of a row in
turn. Each flow source (one nozzle row, the rotation, bulk agitation) gives every boundary point a local speed U_i
and a run length x_i (what the boiling model uses: critical flux, film flux); the nozzle rows also give the
circumferential mean of their impinging-jet heat transfer (what the convection model uses).

Jet rows (see quenchsim.bath.correlations for the constants and sources):
1. Free jet from the exit to the surface, penetration y = standoff / cos(inclination). A vertical cross-flow
   U_x on the row's side (``id_crossflow_up_m_s``: the oil rising in the bore as the ring heats it; the
   report saw weak ID jets bend before the bore, strong ones hit it and rise) makes the jet drift
   x = R d (y/(A R d))^(1/m), R = U_0/|U_x| (Pratte & Baines 1967): the jet travels H = sqrt(y^2 + x^2)
   and arrives weaker (the shift of its impact point is not modelled). Arrival centre-line speed
   U_a = U_0 min(1, B d/H) (potential core, then 1/x decay); arrival half-width b = max(d/2, S H).
2. Impingement at height z_imp = height - standoff tan(inclination) on the face the row aims at
   (the bore for "id" rows, the OD for "od" rows).
3. Impinging-jet convection (the circumferential mean of Martin's local distribution): a point at in-plane distance s
   from the impact line lies at rho = sqrt(c^2 + s^2) from a stagnation point, c the circumferential offset; the
   ring's turning averages c over one nozzle pitch P = 2 pi r_imp / N, so the row's coefficient is
   h = (k/D) Pr^0.42 F_1(Re) <l(rho/D, H/D)>_c with Martin's F_1 and the local shape l of
   :func:`quenchsim.bath.correlations.martin_srn_local_shape` (Martin 1977 area-mean for r/D >= 2.5, Goldstein et al.
   1986 shape inside). Re = U_0 D / nu. Where the rows aimed at a face form an array in Martin's range (A_r = nozzle
   area / (pitch x face length per row) >= 0.004: the reference OD rows), the cell mean is Martin's array
   correlation instead, h = (k/D) Pr^0.42 K G F_2(Re) <l>_c / mean_cell <l>_c (interacting jets: single-jet
   superposition over the reference OD cell would be 1.36-1.57 times Martin's array value). Beyond Martin's H/D = 12
   (a long or bent path) the jet is taken at H/D = 12 with the exit speed reduced by the free jet's 1/x decay,
   U_0 12 D/H. The shape per row and point is :attr:`LocalFlow.jet_shape`; the HTC model multiplies it by the
   temperature-dependent Pr^0.42 F(Re).
4. Wall jets for the boiling model's local speed: the momentum flux of the row, N rho U_0^2 pi d^2/4 (conserved along
   a free jet), spread over the circumference 2 pi r_imp, leaves the impact line as two plane wall jets, up and down,
   carrying the shares (1 -+ sin(inclination))/2; at distance s from the impact U = min(U_a, 3.5 sqrt(J'_share/(rho
   (s + b)))), run x = s + b. In the bore this is the bore flow the ID jets feed: their momentum drives the oil along
   the bore (their volume flow, N pi d^2/4 U_0 ~ 0.4 L/s at 1 m/s, leaves the bore's ~0.04 m^2 cross-section at
   ~5 mm/s: negligible beside the wall jets).
5. Faces: a point whose outward normal faces the jet (n . -e_jet > 0) gets the full wall jet and impingement
   coefficient scaled by that cosine; faces turned about 90 deg away (the top and bottom faces) get the fraction
   ``corner_carryover`` of it (a wall jet partly stays attached round a convex edge, Coanda effect);
   faces turned away from the row (the opposite side of the wall) get nothing.

Rotation: the part slides past the oil next to it at U_rot = omega r (1 - f), f the share of the rotation that oil
follows: ``bore_swirl_fraction`` for the bore (the enclosed oil column is spun up by the turning bore),
``oil_swirl_fraction`` for the outer faces (the open tank); run length the circumferential pitch of the facing nozzle
row (each jet crossing restarts the boundary layer), or the full circumference where no row faces the point.

Bulk agitation (``agitation_m_s``, a tank agitator's oil speed past the work): one more source, the same speed at
every point, run length the section height on vertical faces and half the radial width on horizontal ones (the
flow sweeps the whole face; the lengths of the natural-convection correlations).

The part's support (``support``): on a turntable or fixture the bottom face's points (outward normal down, at z_min)
exchange heat only on the open fraction ``turntable_open_fraction`` of their area (the rest is covered and treated
as adiabatic); a hanging part is open on every face (fraction 1).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from quenchsim.bath.config import BathConfig, NozzleRow
from quenchsim.bath.correlations import (MARTIN_ARN_AREA_RANGE, MARTIN_H_D_RANGE, crossflow_drift,
                                         jet_centreline_velocity, jet_half_width, martin_srn_local_shape,
                                         plane_wall_jet_velocity)
from quenchsim.geometry.boundary import BoundaryPoints

VERTICAL_NZ = 0.7
"""|n_z| below this: the face is treated as vertical (natural convection along the section height)."""
FACING_COSINE = 0.5
"""n . -e_jet above this: the point lies on the face a row aims at (used to locate the impact point)."""
AWAY_COSINE = -0.5
"""n . -e_jet below this: the face is turned away from the row and gets none of its wall jet."""
PITCH_NODES = 48
"""Midpoint nodes of the circumferential mean over one nozzle pitch (the mean of the local shape converges to < 0.5 %
at 48 nodes for the reference layouts, r/D >= 0 on the impact line)."""
BORE_NORMAL_R = -0.5
"""normal_r below this: the point faces the axis (a bore): its oil is the enclosed column in the bore."""


@dataclass(frozen=True)
class LocalFlow:
    """Local flow per boundary point; per-source arrays are shaped (n_sources, n_points)."""

    source_names: tuple[str, ...]
    speed_m_s: np.ndarray
    run_length_m: np.ndarray
    natural_length_m: np.ndarray
    orientation: np.ndarray
    exposed_fraction: np.ndarray
    jet_shape: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    """(n_rows, n_points): face factor x circumferential mean of Martin's local shape <l(rho/D, H/D)>_c per row."""
    jet_speed_m_s: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """(n_rows,): the speed Re is formed with (exit speed, decayed beyond H/D = 12)."""
    jet_diameter_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """(n_rows,): nozzle exit diameters."""
    jet_area_ratio: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """(n_rows,): A_r = nozzle area / the cell one nozzle serves on its face, where the row is part of an array in
    Martin's range (its jet_shape is then normalised to a cell mean of 1 and scaled by Martin's array correlation);
    0 for a single-jet row (jet_shape is Martin's single-nozzle local shape)."""
    jet_H_D: np.ndarray = field(default_factory=lambda: np.zeros(0))
    """(n_rows,): nozzle-to-surface distance over D (clamped to Martin's 2-12)."""

    def without_flow(self) -> "LocalFlow":
        """The same points in still oil (no speeds, no jets)."""
        return LocalFlow(self.source_names, np.zeros_like(self.speed_m_s), self.run_length_m, self.natural_length_m,
                         self.orientation, self.exposed_fraction, np.zeros_like(self.jet_shape),
                         self.jet_speed_m_s, self.jet_diameter_m, self.jet_area_ratio, self.jet_H_D)

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


@dataclass(frozen=True)
class RowFlow:
    """What one nozzle row gives every point: wall-jet speed, run length, face factor, and the impinging-jet shape."""

    speed_m_s: np.ndarray
    run_length_m: np.ndarray
    factor: np.ndarray
    jet_shape: np.ndarray
    re_speed_m_s: float
    area_ratio: float = 0.0
    H_D: float = 0.0


def circumferential_jet_shape(s_m: np.ndarray, diameter_m: float, pitch_m: float, H_D: float) -> np.ndarray:
    """Mean of Martin's local shape l(rho/D, H/D) over one nozzle pitch, rho = sqrt(c^2 + s^2), c in [-P/2, P/2]
    (midpoint rule, :data:`PITCH_NODES` nodes)."""
    c = pitch_m * ((np.arange(PITCH_NODES) + 0.5) / PITCH_NODES - 0.5)
    rho = np.hypot(np.asarray(s_m, dtype=float)[:, None], c[None, :])
    return martin_srn_local_shape(rho / diameter_m, H_D).mean(axis=1)


def array_cell(row: NozzleRow, rows_on_face: int, r_imp_m: float, face_length_m: float) -> tuple[float, float]:
    """(circumferential pitch, axial cell length) of the face area one nozzle of ``row`` serves: the pitch 2 pi r / N
    round the part and the face length shared by the rows aimed at that face."""
    return 2.0 * np.pi * r_imp_m / row.count, face_length_m / max(rows_on_face, 1)


def _row_flow(cfg: BathConfig, row: NozzleRow, pts: BoundaryPoints) -> RowFlow:
    """Wall-jet speed, run length, face factor and impinging-jet shape of one row at every point."""
    er, _ = _jet_direction(row)
    facing = -(pts.normal_r * er)  # cosine between the outward normal and the direction back to the nozzle (horizontal)
    n = len(pts)
    on_face = facing > FACING_COSINE
    if not np.any(on_face) or row.jet_speed_m_s == 0.0:
        return RowFlow(np.zeros(n), np.ones(n), np.zeros(n), np.zeros(n), 0.0)
    U_cross = cfg.crossflow_up_m_s[row.side]
    penetration = row.standoff_m / np.cos(row.inclination_rad)
    drift = crossflow_drift(row.jet_speed_m_s, row.diameter_m, penetration, U_cross)
    travel = float(np.hypot(penetration, drift))
    ext = pts.extent
    z_imp = ext.z_min_m + row.height_above_bottom_m(ext.z_max_m - ext.z_min_m) - row.standoff_m * np.tan(row.inclination_rad)
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
    H_D = travel / row.diameter_m
    H_max = MARTIN_H_D_RANGE[1]
    re_speed = row.jet_speed_m_s * min(1.0, H_max / H_D)
    H_D = float(np.clip(H_D, *MARTIN_H_D_RANGE))
    rows_on_face = sum(1 for other in cfg.rows if other.side == row.side)
    pitch, cell_length = array_cell(row, rows_on_face, r_imp, pts.extent.z_max_m - pts.extent.z_min_m)
    shape = circumferential_jet_shape(s, row.diameter_m, pitch, H_D)
    area_ratio = np.pi * row.diameter_m**2 / 4.0 / (pitch * cell_length)
    if area_ratio >= MARTIN_ARN_AREA_RANGE[0]:
        # an array in Martin's range: his array correlation gives the cell mean, the local shape its distribution
        cell = circumferential_jet_shape(np.abs((np.arange(PITCH_NODES) + 0.5) / PITCH_NODES - 0.5) * cell_length,
                                         row.diameter_m, pitch, H_D).mean()
        shape = shape / cell
        area_ratio = min(area_ratio, MARTIN_ARN_AREA_RANGE[1])
    else:
        area_ratio = 0.0
    return RowFlow(U * factor, x, factor, shape * factor, re_speed, area_ratio, H_D)


def local_flow(cfg: BathConfig, pts: BoundaryPoints) -> LocalFlow:
    """Local speeds and lengths of every flow source at every boundary point (built once per stage)."""
    ext = pts.extent
    speeds, lengths, names, shapes, re_speeds, areas, H_Ds = [], [], [], [], [], [], []
    pitch_count = np.zeros(len(pts))
    for row in cfg.rows:
        rf = _row_flow(cfg, row, pts)
        speeds.append(rf.speed_m_s)
        lengths.append(rf.run_length_m)
        names.append(row.name)
        shapes.append(rf.jet_shape)
        re_speeds.append(rf.re_speed_m_s)
        areas.append(rf.area_ratio)
        H_Ds.append(rf.H_D)
        pitch_count = np.where(rf.factor > 0.0, np.maximum(pitch_count, row.count), pitch_count)
    circumference = 2.0 * np.pi * np.maximum(pts.r_m, 1e-6)
    swirl = np.where(pts.normal_r < BORE_NORMAL_R, cfg.bore_swirl_fraction, cfg.oil_swirl_fraction)
    speeds.append(cfg.omega_rad_s * pts.r_m * (1.0 - swirl))
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
                     exposed_fraction=np.where(on_table, cfg.turntable_open_fraction, 1.0),
                     jet_shape=np.array(shapes).reshape(len(cfg.rows), len(pts)),
                     jet_speed_m_s=np.array(re_speeds, dtype=float),
                     jet_diameter_m=np.array([row.diameter_m for row in cfg.rows], dtype=float),
                     jet_area_ratio=np.array(areas, dtype=float), jet_H_D=np.array(H_Ds, dtype=float))
