"""One engaged state of a two-way roller clutch: roller load, wedge angle, the two Hertz line contacts with
their max-shear depths, and the outer ring by the Lame closed form (uniform pressure), the exact discrete-load
series (n Hertz strips) and, on request, the plane-stress FE check of both.

The case-depth rule of the clutch paper (Okada et al., NTN Technical Review 69 (2001) 39, sec. 5.2: the
outer race is carburised to at least twice the depth of the maximum shear stress) is reported as
``min_case_depth_m`` = 2 x the larger max-shear depth of the two contacts. The static capacity of each contact
against ISO 76's 4000 MPa for roller bearings (brinelling) is its static safety factor s0 = (4000 MPa / p_max)^2
(:func:`quenchsim.bearings.hertz.static_safety_factor`; s0 < 1: a brinell dent beyond the standard's 1e-4 D).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from quenchsim.bearings import hertz
from quenchsim.bearings.roller_clutch import fe, ring, wedge


@dataclass(frozen=True)
class ClutchState:
    """An engaged clutch (SI units): the engagement, the Lame ring and the discrete-load ring."""

    engagement: wedge.Engagement
    lame: ring.LameRing
    discrete: ring.RingResponse
    min_case_depth_m: float

    def summary(self) -> dict:
        """Plain numbers in engineering units (N, deg, MPa, mm) for the CLI and the reports."""
        e = self.engagement
        out: dict[str, Any] = {"torque_Nm": e.torque_Nm, "roller_load_N": e.roller_load_N,
               "load_per_torque_N_per_Nm": e.load_per_torque_N_per_Nm,
               "wedge_angle_deg": math.degrees(e.wedge_angle_rad), "traction_ratio": e.traction_ratio,
               "approach_per_contact_mm": e.approach_flat_m * 1e3, "bore_expansion_lame_mm": e.bore_expansion_m * 1e3}
        for name, c in (("inner_flat", e.inner), ("outer_bore", e.outer)):
            out[name] = {"p_max_MPa": c.p_max_Pa / 1e6, "half_width_mm": c.half_width_m * 1e3,
                         "depth_max_shear_mm": c.depth_max_shear_m * 1e3, "max_shear_MPa": c.max_shear_Pa / 1e6}
        out["min_case_depth_mm"] = self.min_case_depth_m * 1e3
        s0 = {name: hertz.static_safety_factor(c.p_max_Pa, "roller") for name, c in (("inner_flat", e.inner),
                                                                                     ("outer_bore", e.outer))}
        out["static_capacity"] = {"iso76_limit_MPa": hertz.iso76_limits()["roller_MPa"], "safety_factor": s0,
                                  "brinelling": bool(min(s0.values()) < 1.0)}
        out["ring_lame"] = {"bore_pressure_MPa": self.lame.pressure_Pa / 1e6,
                            "bore_expansion_mm": self.lame.bore_displacement_m * 1e3,
                            "bore_hoop_MPa": self.lame.bore_hoop_Pa / 1e6, "outer_hoop_MPa": self.lame.outer_hoop_Pa / 1e6}
        d = self.discrete
        out["ring_discrete"] = {"bore_expansion_at_roller_mm": d.bore_u_at_roller_m * 1e3,
                                "bore_expansion_between_mm": d.bore_u_between_m * 1e3,
                                "bore_hoop_between_MPa": d.bore_hoop_between_Pa / 1e6,
                                "outer_hoop_at_roller_MPa": d.outer_hoop_at_roller_Pa / 1e6,
                                "outer_hoop_between_MPa": d.outer_hoop_between_Pa / 1e6,
                                "max_hoop_MPa": d.max_hoop_Pa / 1e6}
        return out


def discrete_ring(geometry: wedge.ClutchGeometry, e: wedge.Engagement) -> ring.DiscreteLoadRing:
    """The outer ring under the n roller loads of the engagement ``e`` (Hertz strips of the bore contact's
    half-width, tangential traction tan(eps/2) x pressure, per unit width N / B)."""
    g = geometry
    return ring.DiscreteLoadRing(g.bore_radius_m, g.outer_diameter_m / 2.0, g.rollers, e.roller_load_N / g.ring_width_m,
                                 e.outer.half_width_m, g.E_Pa, g.nu, e.traction_ratio)


def analyse(geometry: wedge.ClutchGeometry, torque_Nm: float, *, compliant: bool = True) -> ClutchState:
    """Engage the clutch at ``torque_Nm`` and evaluate contacts and ring (module docstring)."""
    e = wedge.engage(geometry, torque_Nm, compliant=compliant)
    g = geometry
    lame = ring.lame_ring(g.bore_radius_m, g.outer_diameter_m / 2.0, e.bore_pressure_Pa, g.E_Pa, g.nu)
    resp = ring.ring_response(discrete_ring(g, e))
    return ClutchState(engagement=e, lame=lame, discrete=resp,
                       min_case_depth_m=2.0 * max(e.inner.depth_max_shear_m, e.outer.depth_max_shear_m))


@dataclass(frozen=True)
class FECheck:
    """FE against the closed forms at the same points: uniform pressure vs Lame (bore expansion, bore hoop)
    and discrete loads vs the series (bore expansion at and between rollers, bore hoop between, outer hoop at
    and between); values in SI, relative differences in %."""

    lame_closed: dict[str, float]
    lame_fe: dict[str, float]
    discrete_closed: dict[str, float]
    discrete_fe: dict[str, float]
    nodes: int
    triangles: int

    def differences_pct(self) -> dict[str, float]:
        out = {f"lame.{k}": 100.0 * (self.lame_fe[k] / v - 1.0) for k, v in self.lame_closed.items()}
        out.update({f"discrete.{k}": 100.0 * (self.discrete_fe[k] / v - 1.0) for k, v in self.discrete_closed.items()})
        return out


DISCRETE_KEYS = ("bore_u_at_roller_m", "bore_u_between_m", "bore_hoop_between_Pa", "outer_hoop_at_roller_Pa",
                 "outer_hoop_between_Pa")


def fe_check(geometry: wedge.ClutchGeometry, state: ClutchState, *, per_pitch: int = 64,
             first_layer_m: float = 5e-5, max_layer_m: float = 5e-4, focus: float = 4.5) -> FECheck:
    """Solve the ring by FE (:mod:`quenchsim.bearings.roller_clutch.fe`) under the Lame pressure and under the
    discrete loads of ``state``; the default mesh puts 4-6 elements across the Hertz strip."""
    g, e = geometry, state.engagement
    a, b, n = g.bore_radius_m, g.outer_diameter_m / 2.0, g.rollers
    mesh = fe.polar_mesh(a, b, n, per_pitch=per_pitch, first_layer_m=first_layer_m, max_layer_m=max_layer_m,
                         focus=focus)
    mid = math.pi / n
    rr = np.array([a, a, a, b, b])
    th = np.array([0.0, mid, mid, 0.0, mid])
    p = state.lame.pressure_Pa
    uni = fe.solve_ring(mesh, a, b, g.E_Pa, g.nu, lambda t: p + 0.0 * t, lambda t: 0.0 * t, 0.0, rr[:2], th[:2])
    lame_closed = {"bore_u_m": state.lame.bore_displacement_m, "bore_hoop_Pa": state.lame.bore_hoop_Pa}
    lame_fe = {"bore_u_m": float(np.mean(uni.u_r)), "bore_hoop_Pa": float(np.mean(uni.s_tt))}
    c = e.outer.half_width_m
    beta, p0 = c / a, e.outer.p_max_Pa * g.roller_length_m / g.ring_width_m
    pitch = 2.0 * math.pi / n

    def pressure(t: np.ndarray) -> np.ndarray:
        d = np.mod(t + pitch / 2.0, pitch) - pitch / 2.0
        return p0 * np.sqrt(np.clip(1.0 - (d / beta) ** 2, 0.0, None))

    mu = e.traction_ratio
    outer_shear = -mu * n * (e.roller_load_N / g.ring_width_m) / (2.0 * math.pi * a) * a * a / (b * b)
    dis = fe.solve_ring(mesh, a, b, g.E_Pa, g.nu, pressure, lambda t: mu * pressure(t), outer_shear, rr, th)
    d = state.discrete
    discrete_closed = {k: getattr(d, k) for k in DISCRETE_KEYS}
    discrete_fe = dict(zip(DISCRETE_KEYS, (float(dis.u_r[0]), float(dis.u_r[1]), float(dis.s_tt[2]),
                                           float(dis.s_tt[3]), float(dis.s_tt[4]))))
    return FECheck(lame_closed, lame_fe, discrete_closed, discrete_fe, nodes=dis.nodes, triangles=dis.triangles)
