"""Crank-slider kinematics, two-stroke gas force and the loads on the big end.

Inertial frame: X along the cylinder axis towards top dead centre, crank centre at the origin,
crank angle theta = omega t from TDC. Crank pin P = r (cos theta, sin theta). Con-rod angle beta
(direction from big end to small end): sin beta = -lambda sin theta, lambda = r / l.
    x_p = r cos theta + l cos beta                      (piston pin)
    beta_dot = -lambda omega cos theta / cos beta
    beta_ddot = (lambda omega^2 sin theta + beta_dot^2 sin beta) / cos beta   (constant omega)
    x_p_ddot = -r omega^2 cos theta - l (beta_ddot sin beta + beta_dot^2 cos beta)
Piston: m_rec x_p_ddot = -F_gas - T cos beta  ->  rod force T = -(F_gas + m_rec x_p_ddot) / cos beta
(tension positive); the rod pushes on the big end with T (cos beta, sin beta).

Gas pressure (shape only): single-zone closed-cycle model between exhaust-port closing and opening
(two-stroke, one firing per revolution), polytropic compression/expansion and Wiebe heat release
    dp/dtheta = -gamma p / V dV/dtheta + (gamma - 1) / V dQ/dtheta,
    x_b = 1 - exp(-a ((theta - theta_s)/dtheta_b)^(m+1))
(Heywood, Internal Combustion Engine Fundamentals, 1988, sec. 9.2; Blair, Design and Simulation of
Two-Stroke Engines, 1996, ch. 4); after exhaust-port opening the pressure falls linearly to p0 over
the blowdown angle, and p = p0 while the ports are open. The force is the pressure
normalised to [0, 1] times the given full amplitude: F_gas = F_amp (p - p_min) / (p_max - p_min).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp


@dataclass(frozen=True)
class GasCycle:
    """Closed-cycle data of the two-stroke pressure shape (angles in degrees after TDC)."""

    compression_ratio: float
    port_closing_deg: float
    port_opening_deg: float
    combustion_start_deg: float
    combustion_duration_deg: float
    wiebe_a: float
    wiebe_m: float
    polytropic_exponent: float
    heat_release_over_p0_vd: float
    blowdown_deg: float


@dataclass(frozen=True)
class CrankSlider:
    """Crank radius [m], con-rod length [m], speed [rad/s]."""

    crank_radius: float
    rod_length: float
    omega: float

    def rod_angle(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """beta, beta_dot, beta_ddot of the con-rod (rad, rad/s, rad/s^2)."""
        lam = self.crank_radius / self.rod_length
        beta = np.arcsin(-lam * np.sin(theta))
        beta_dot = -lam * self.omega * np.cos(theta) / np.cos(beta)
        beta_ddot = (lam * self.omega**2 * np.sin(theta) + beta_dot**2 * np.sin(beta)) / np.cos(beta)
        return beta, beta_dot, beta_ddot

    def piston(self, theta: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Piston-pin position x_p [m] and acceleration [m/s^2] along the cylinder axis."""
        beta, beta_dot, beta_ddot = self.rod_angle(theta)
        r, l, w = self.crank_radius, self.rod_length, self.omega
        x = r * np.cos(theta) + l * np.cos(beta)
        acc = -r * w**2 * np.cos(theta) - l * (beta_ddot * np.sin(beta) + beta_dot**2 * np.cos(beta))
        return x, acc


def cylinder_volume_ratio(theta: np.ndarray, crank: CrankSlider, compression_ratio: float) -> np.ndarray:
    """V / V_swept = 1/(CR - 1) + (r + l - x_p) / (2 r)."""
    x, _ = crank.piston(theta)
    r, l = crank.crank_radius, crank.rod_length
    return 1.0 / (compression_ratio - 1.0) + (r + l - x) / (2.0 * r)


def gas_pressure_shape(theta: np.ndarray, crank: CrankSlider, cycle: GasCycle) -> np.ndarray:
    """Cylinder pressure over p0 at crank angles ``theta`` [rad] (periodic, one firing per revolution)."""
    th0, th1 = np.radians(cycle.port_closing_deg), np.radians(cycle.port_opening_deg)
    ths, dth = np.radians(cycle.combustion_start_deg), np.radians(cycle.combustion_duration_deg)
    g = cycle.polytropic_exponent
    a, m = cycle.wiebe_a, cycle.wiebe_m

    def dp(th: float, p: np.ndarray) -> np.ndarray:
        v = cylinder_volume_ratio(np.array([th]), crank, cycle.compression_ratio)[0]
        h = 1e-6
        dv = (cylinder_volume_ratio(np.array([th + h]), crank, cycle.compression_ratio)[0]
              - cylinder_volume_ratio(np.array([th - h]), crank, cycle.compression_ratio)[0]) / (2 * h)
        z = (th - ths) / dth
        dxb = 0.0 if z <= 0.0 else a * (m + 1) / dth * z**m * np.exp(-a * z ** (m + 1))
        return np.array([-g * p[0] / v * dv + (g - 1.0) / v * cycle.heat_release_over_p0_vd * dxb])

    ang = np.mod(np.asarray(theta, dtype=float) - th0, 2 * np.pi) + th0  # wrap into [th0, th0 + 2 pi)
    grid = np.linspace(th0, th1, 721)
    sol = solve_ivp(dp, (th0, th1), [1.0], t_eval=grid, rtol=1e-8, atol=1e-10, max_step=np.radians(0.5))
    blow = np.radians(cycle.blowdown_deg)
    grid = np.append(grid, th1 + blow)
    p = np.append(sol.y[0], 1.0)
    return np.interp(ang, grid, p, right=1.0)


def gas_force(theta: np.ndarray, crank: CrankSlider, cycle: GasCycle, amplitude_n: float) -> np.ndarray:
    """Gas force on the piston towards the crank [N]: pressure shape scaled to the full amplitude."""
    grid = np.linspace(0.0, 2 * np.pi, 1441)
    p = gas_pressure_shape(grid, crank, cycle)
    shape = (p - p.min()) / (p.max() - p.min())
    return amplitude_n * np.interp(np.mod(theta, 2 * np.pi), grid, shape)


def big_end_load(theta: np.ndarray, crank: CrankSlider, cycle: GasCycle, amplitude_n: float,
                 reciprocating_mass_kg: float) -> tuple[np.ndarray, np.ndarray]:
    """Force of the con-rod on the outer ring, in the frame rotating with the crank pin [N].

    Inertial force T (cos beta, sin beta) rotated by -theta; components along / across the crank arm.
    """
    beta, _, _ = crank.rod_angle(theta)
    _, acc = crank.piston(theta)
    tension = -(gas_force(theta, crank, cycle, amplitude_n) + reciprocating_mass_kg * acc) / np.cos(beta)
    return tension * np.cos(beta - theta), tension * np.sin(beta - theta)
