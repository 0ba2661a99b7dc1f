"""Quasi-static equilibrium of the free ring on Z ball contacts, all time steps at once.

Each ball carries a load Q_j = k s_j^p along its contact line (p = 1: linear springs, p = 3/2:
Hertz), s_j being the elastic approach of the ball's inner and outer contacts in series,

    s_j = e_j + sigma cos(alpha) (x cos th_j + y sin th_j) + z sin(alpha),    Q_j = 0 if s_j <= 0,

with e_j the geometric interference from form errors (per model, see linear2d / hertz3d), (x, y)
the free ring's centre in the fixed frame (sigma = +1 if the free ring is the inner ring, -1 if it
is the outer ring: moving the outer ring towards a ball opens that ball's contact) and z its axial
approach. Equilibrium under the constant-pressure axial preload F_a (reference sec. 3):

    sum_j Q_j cos(alpha) cos(th_j) = 0,  sum_j Q_j cos(alpha) sin(th_j) = 0,  sum_j Q_j sin(alpha) = F_a.

These are the stationarity conditions of the convex potential
V(x, y, z) = sum_j k s_j^(p+1)/(p+1) - F_a z, so Newton's method with a backtracking (Armijo) line
search on V converges from the unloaded-geometry start. All N time steps are independent and are
solved together: one batched 3x3 Newton system per step, vectorised over steps and balls; every
step is warm-started from the rigid preload solution shifted by its mean interference.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from quenchsim.errors import SolverError

# Newton stops when no time step moves by more than this (m); 1e-15 m is ~1e-9 of a typical
# preload approach and far below the smallest line of interest (0.01 nm).
STEP_TOLERANCE_M = 1.0e-15
MAX_NEWTON_ITERATIONS = 60
_ARMIJO = 1.0e-4
# relative rounding allowance of the potential (near the solution its change is below machine precision)
_ROUNDING = 1.0e-13


@dataclass(frozen=True)
class Equilibrium:
    """Free-ring centre (N,) per time step, ball approaches and loads (N, Z), Newton iterations."""

    x_m: np.ndarray
    y_m: np.ndarray
    z_m: np.ndarray
    approach_m: np.ndarray
    load_N: np.ndarray
    iterations: int


def solve_equilibrium(interference_m: np.ndarray, ball_angle_rad: np.ndarray, contact_angle_rad: float,
                      free_ring: str, stiffness: float, exponent: float, axial_load_N: float) -> Equilibrium:
    """Solve the equilibrium of the module docstring at every time step.

    interference_m, ball_angle_rad: (N, Z); stiffness k in N/m^p; free_ring "inner" or "outer"."""
    e = np.asarray(interference_m, dtype=float)
    th = np.asarray(ball_angle_rad, dtype=float)
    n, z = e.shape
    sigma = 1.0 if free_ring == "inner" else -1.0
    ca, sa = np.cos(contact_angle_rad), np.sin(contact_angle_rad)
    gx, gy = sigma * ca * np.cos(th), sigma * ca * np.sin(th)   # d s_j / d(x, y); d s_j / dz = sin(alpha)
    p = exponent

    def approach(u: np.ndarray) -> np.ndarray:
        return e + gx * u[:, :1] + gy * u[:, 1:2] + sa * u[:, 2:3]

    def potential(s: np.ndarray, uz: np.ndarray) -> np.ndarray:
        sp = np.maximum(s, 0.0)
        return stiffness * (sp ** (p + 1.0)).sum(axis=1) / (p + 1.0) - axial_load_N * uz

    s0 = (axial_load_N / (z * stiffness * sa)) ** (1.0 / p)
    u = np.zeros((n, 3))
    u[:, 2] = (s0 - e.mean(axis=1)) / sa
    for iteration in range(1, MAX_NEWTON_ITERATIONS + 1):
        s = approach(u)
        sp = np.maximum(s, 0.0)
        q = stiffness * sp ** p
        kt = p * stiffness * sp ** (p - 1.0) if p != 1.0 else np.where(s > 0.0, stiffness, 0.0)
        r = np.stack([(q * gx).sum(axis=1), (q * gy).sum(axis=1), sa * q.sum(axis=1) - axial_load_N], axis=1)
        kx, ky = kt * gx, kt * gy
        hxx, hxy, hyy = (kx * gx).sum(axis=1), (kx * gy).sum(axis=1), (ky * gy).sum(axis=1)
        hxz, hyz, hzz = sa * kx.sum(axis=1), sa * ky.sum(axis=1), sa * sa * kt.sum(axis=1)
        h = np.stack([np.stack([hxx, hxy, hxz], -1), np.stack([hxy, hyy, hyz], -1),
                      np.stack([hxz, hyz, hzz], -1)], axis=1)
        h += (1e-12 * (hxx + hyy + hzz) + 1e-300)[:, None, None] * np.eye(3)
        du = -np.linalg.solve(h, r[..., None])[..., 0]
        # backtracking line search on the convex potential, only where the full step does not descend
        v0 = potential(s, u[:, 2])
        slope = (r * du).sum(axis=1)
        step = np.ones(n)
        for _ in range(40):
            trial = u + step[:, None] * du
            bad = potential(approach(trial), trial[:, 2]) > v0 + _ARMIJO * step * slope + _ROUNDING * np.abs(v0)
            if not bad.any():
                break
            step = np.where(bad, 0.5 * step, step)
        u = u + step[:, None] * du
        if np.max(np.abs(step[:, None] * du)) < STEP_TOLERANCE_M:
            s = approach(u)
            return Equilibrium(x_m=u[:, 0], y_m=u[:, 1], z_m=u[:, 2], approach_m=s,
                               load_N=stiffness * np.maximum(s, 0.0) ** p, iterations=iteration)
    raise SolverError(f"ball-bearing equilibrium did not converge in {MAX_NEWTON_ITERATIONS} Newton iterations "
                      f"(largest step {np.max(np.abs(du)):.3g} m)")


@dataclass(frozen=True)
class Trajectory:
    """Free-ring centre history of one run: time (N,), x, y (fixed frame) and axial approach z (m),
    ball loads (N, Z), the model's contact stiffness k (N/m^p, Q = k s^p) and the preload approach s0."""

    model: str
    time_s: np.ndarray
    x_m: np.ndarray
    y_m: np.ndarray
    z_m: np.ndarray
    load_N: np.ndarray
    stiffness: float
    exponent: float
    preload_approach_m: float
    iterations: int
