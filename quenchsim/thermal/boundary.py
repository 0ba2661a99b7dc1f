"""Tabulated heat-transfer coefficients: h(T_surface) or h(t), one table or one per boundary segment.

Case-file form (``[quench.htc_table]``)::

    T_C = [0, 200, 400, ...]          # surface temperature, strictly increasing
    h_W_m2K = [4350, 8207, ...]       # >= 0
    ambient_C = 20
    [quench.htc_table.segments.bore]  # optional per-segment tables (same keys)
    # or, for an HTC history:  time_s = [...], h_W_m2K = [...]

Linear interpolation, constant beyond the ends.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any, cast

import numpy as np

from quenchsim.errors import InputError, require
from quenchsim.inputs.htc import HtcTable
from quenchsim.inputs.declare import from_table


def _table(table: HtcTable, ambient_C: float | None, field: str) -> tuple[str, np.ndarray, np.ndarray, float]:
    """One table's kind, axis, values and ambient (its own, else the enclosing table's ``ambient_C``)."""
    ambient = table.ambient_C if table.ambient_C is not None else ambient_C
    require(ambient is not None, f"{field}.ambient_C", None, "must be a number (degrees C)")
    kind = "temperature" if table.T_C is not None else "time"
    return kind, np.asarray(table.axis, dtype=float), np.asarray(table.h_W_m2K, dtype=float), float(cast(float, ambient))


class TableHTC:
    """h at boundary points from tables: ``htc(T_surface_C, time_s) -> h_W_m2K`` (vectorised)."""

    def __init__(self, kinds: list[str], axes: list[np.ndarray], values: list[np.ndarray],
                 ambients: list[float], table_of_point: np.ndarray) -> None:
        self.kinds, self.axes, self.values = kinds, axes, values
        self.table_of_point = table_of_point
        self.ambient_C = np.asarray(ambients)[table_of_point]
        self._groups = [np.flatnonzero(table_of_point == i) for i in range(len(kinds))]

    def __call__(self, T_surface_C: np.ndarray, time_s: float) -> np.ndarray:
        h = np.empty_like(T_surface_C, dtype=float)
        flat_T, flat_h = T_surface_C.reshape(-1), h.reshape(-1)
        for i, idx in enumerate(self._groups):
            if self.kinds[i] == "temperature":
                flat_h[idx] = np.interp(flat_T[idx], self.axes[i], self.values[i])
            else:
                flat_h[idx] = np.interp(time_s, self.axes[i], self.values[i])
        return h


def parse_htc_table(spec: Mapping[str, Any] | HtcTable, segment_of_point: np.ndarray,
                    field: str = "quench.htc_table") -> TableHTC:
    """Build a :class:`TableHTC` for points labelled by segment name from an HTC table (its declaration,
    :class:`quenchsim.inputs.case.HtcTable`, or a table as read); per-segment tables override the default."""
    table = spec if isinstance(spec, HtcTable) else from_table(HtcTable, spec, field)
    tables = []
    has_default = bool(table.axis)
    if has_default:
        tables.append(("", _table(table, None, field)))
    for name, sub in table.segments.items():
        require(bool(sub.axis), f"{field}.segments.{name}", sorted(sub._given), "needs T_C or time_s with h_W_m2K")
        tables.append((name, _table(sub, table.ambient_C, f"{field}.segments.{name}")))
    which = np.full(segment_of_point.shape, -1, dtype=int)
    if has_default:
        which[:] = 0
    for i, (name, _) in enumerate(tables):
        if name:
            which[segment_of_point == name] = i
    missing = sorted(set(segment_of_point[which < 0]))
    if missing:
        raise InputError(f"{field}.segments", sorted(table.segments), f"no table for segments {missing} (and no default "
                         "T_C/time_s)")
    known = set(segment_of_point)
    for name in table.segments:
        require(name in known, f"{field}.segments.{name}", name, f"unknown segment; the section has {sorted(known)}")
    return TableHTC([t[1][0] for t in tables], [t[1][1] for t in tables], [t[1][2] for t in tables],
                    [t[1][3] for t in tables], which)


class SurfaceTemperatureHTC:
    """A boundary HTC that depends on the surface temperature only (e.g. the bath model's curves per point),
    in the ``htc(T_surface_C, time_s)`` form the solver calls; ``curves(T_surface_C)`` gives h per point."""

    def __init__(self, curves: Any) -> None:
        self.curves = curves
        self.ambient_C = np.asarray(curves.ambient_C)

    def __call__(self, T_surface_C: np.ndarray, time_s: float) -> np.ndarray:
        return self.curves(T_surface_C)


class ImmersionHTC:
    """A part lowered into the bath bottom face first at ``speed_m_s`` from ``start_s``: the boundary points below
    the oil level z_level(t) = z_bottom + speed (t - start) get the bath's h (``immersed``), those above it still
    the air's (``in_air``), in the ``htc(T_surface_C, time_s)`` form the solver calls.

    The solver takes one ambient temperature per point (the bath's, ``ambient_C``); a point still in air is given
    the coefficient that carries its air flux to that ambient, h_air (T_s - T_air)/(T_s - T_bath) (the same heat
    flux; the part is far hotter than either medium while it is lowered, and the difference is kept >= 1 K)."""

    def __init__(self, immersed: Any, in_air: Any, point_z_m: np.ndarray, bottom_z_m: float, speed_m_s: float,
                 start_s: float) -> None:
        self.immersed, self.in_air = immersed, in_air
        self.point_z_m = np.asarray(point_z_m, dtype=float)
        self.bottom_z_m, self.speed_m_s, self.start_s = float(bottom_z_m), float(speed_m_s), float(start_s)
        self.ambient_C = np.asarray(immersed.ambient_C, dtype=float)

    def wetted(self, time_s: float) -> np.ndarray:
        """Which boundary points are below the oil level at ``time_s``."""
        return self.point_z_m <= self.bottom_z_m + self.speed_m_s * max(time_s - self.start_s, 0.0)

    def __call__(self, T_surface_C: np.ndarray, time_s: float) -> np.ndarray:
        shape = np.shape(T_surface_C)
        T = np.asarray(T_surface_C, dtype=float).reshape(-1)
        wet = self.wetted(time_s)
        if np.all(wet):
            return self.immersed(T, time_s).reshape(shape)
        h_air = self.in_air(T, time_s) * (T - self.in_air.ambient_C) / np.maximum(T - self.ambient_C, 1.0)
        return np.where(wet, self.immersed(T, time_s), h_air).reshape(shape)


class HeatingHTC:
    """A still-air HTC(T_surface) (natural convection + radiation to ``ambient_C``) for a part colder than its
    surroundings, as in a furnace: evaluated at the ambient plus |T_s - T_ambient|. Natural convection depends on the
    temperature difference alone (its Grashof number; the film properties are taken on the hot side), and the
    linearised radiation eps sigma (T_s^2 + T_a^2)(T_s + T_a) to first order in the difference."""

    def __init__(self, inner: Any) -> None:
        self.inner = inner
        self.ambient_C = np.asarray(inner.ambient_C)

    def __call__(self, T_surface_C: np.ndarray, time_s: float) -> np.ndarray:
        T = np.asarray(T_surface_C, dtype=float)
        return self.inner(self.ambient_C + np.abs(T - self.ambient_C), time_s)
