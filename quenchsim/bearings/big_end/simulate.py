"""Set up and integrate one big-end run (engine, static or rig mode) and derive the slip histories.

Slip ratios (reference section 7: C_s = (1 - N_c / N_tc) x 100 %, N_c the measured, absolute cage
speed). With Omega the speeds relative to the inner ring (the rotating frame, itself turning at omega)
and Omega_o that of the outer ring, pure rolling gives
    cage / roller orbit  Omega_th = Omega_o R_o / (R_i + R_o)   (relative to the inner ring)
    roller spin about its own axis relative to its orbit
        s_th = Omega_o R_o (R_i + R_o - 2 r) / (2 r (R_i + R_o))
        (= Omega_o R_o R_i / (r (R_i + R_o)) at zero clearance)
and the slips are formed with absolute speeds where the reference does:
    cage slip = 1 - (omega + Omega_c) / (omega + Omega_th),
    roller orbital slip = 1 - (omega + Omega_orb) / (omega + Omega_th),
    roller spin slip = 1 - (Omega_r - Omega_orb) / s_th   (a speed difference: frame independent).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from quenchsim.bearings.big_end.contact import palmgren_compliance
from quenchsim.bearings.big_end.case import MODES, BigEndCase, ClearanceSet, Operation
from quenchsim.bearings.big_end.dynamics import Params, evaluate, jacobian_packed, pack, rhs_packed
from quenchsim.bearings.big_end.state import StateView, cage_index, n_positions, n_states
from quenchsim.bearings.big_end.engine import CrankSlider, big_end_load
from quenchsim.bearings.big_end.lubricant import load_oil
from quenchsim.errors import InputError, SolverError, require

TABLE_POINTS = 1441  # load / outer-ring speed table over one revolution (0.25 deg)
INTEGRATORS = ("RK45", "DOP853", "Radau", "BDF", "LSODA")
# Chosen by the measurement in reports/bearing_big_end.md: the engine load changes size and direction
# all the time (explicit RK45 is cheapest); under a steady load the traction slope makes the problem
# stiff and LSODA with the compiled Jacobian is 1.4x (static) to 30x (rig, 1000 rpm) cheaper.
DEFAULT_INTEGRATOR = {"engine": "RK45", "static": "LSODA", "rig": "LSODA"}
RTOL = 1e-5


@dataclass(frozen=True)
class RunResult:
    """Sampled history of one run (SI; slips in %)."""

    mode: str
    clearance: ClearanceSet
    params: Params
    t: np.ndarray  # (T,)
    crank_angle: np.ndarray  # (T,) rad, unwrapped
    y: np.ndarray  # (6N + 10, T)
    cage_slip_pct: np.ndarray  # (T,)
    roller_orbital_slip_pct: np.ndarray  # (N, T)
    roller_spin_slip_pct: np.ndarray  # (N, T)
    pocket_force_n: np.ndarray  # (N, T)
    inner_load_n: np.ndarray  # (N, T)
    outer_load_n: np.ndarray  # (N, T)
    revolutions: float
    transient_revolutions: float
    wall_time_s: float
    integrator: str
    n_rhs: int


def build_params(case: BigEndCase, set_number: int, mode: str) -> tuple[Params, ClearanceSet, Operation]:
    """Model parameters of clearance set ``set_number`` (1-based) in ``mode``."""
    require(mode in MODES, "mode", mode, f"must be one of {list(MODES)}")
    if mode not in case.operations:
        raise InputError("mode", mode, f"the case file has no [{mode}] section (has {sorted(case.operations)})")
    n_sets = len(case.clearance_sets)
    require(1 <= set_number <= n_sets, "clearance_set", set_number, f"must be 1..{n_sets}")
    cs = case.clearance_sets[set_number - 1]
    op = case.operations[mode]
    b, m, lub, mod = case.bearing, case.masses, case.lubrication, case.model
    oil = load_oil(lub.oil, lub.temperature_C)
    n = b.n_rollers
    r = 0.5 * b.roller_diameter
    r_out = 0.5 * b.outer_race_id
    r_in = r_out - 2 * r - 0.5 * cs.radial
    e_star = b.youngs_modulus / (1.0 - b.poisson**2)  # E' = 2 / (2 (1 - nu^2)/E), same steel
    speed = cs.speed_rpm if (cs.speed_rpm is not None and mode != "engine") else op.speed_rpm
    omega = speed * np.pi / 30.0
    theta = np.linspace(0.0, 2 * np.pi, TABLE_POINTS)
    if mode == "engine":
        crank = CrankSlider(op.crank_radius, op.rod_length, omega)
        assert op.gas_cycle is not None   # the engine operation always carries its gas cycle (case.py)
        fx, fy = big_end_load(theta, crank, op.gas_cycle, op.gas_amplitude_n, m.reciprocating)
        omega_o = crank.rod_angle(theta)[1] - omega
        crank_radius = op.crank_radius
    else:
        load = cs.load_n if cs.load_n is not None else op.load_n
        fx, fy = -load * np.cos(theta), load * np.sin(theta)  # constant load along -X (downwards)
        omega_o = np.full_like(theta, -omega)
        crank_radius = 0.0
    params = Params(
        n=n, r_roller=r, r_in=r_in, r_out=r_out, m_roller=m.roller, i_roller=m.roller_inertia,
        m_cage=m.cage, i_cage=m.cage_inertia, m_ring=m.outer_ring,
        pocket_half_width=0.5 * (b.roller_diameter + cs.pocket),
        pocket_angles=2 * np.pi * np.arange(n) / n,
        l_roller=np.full(n, b.roller_length), l_pocket=np.full(n, b.pocket_contact_length),
        l_land=np.array([b.lands * b.land_width]),
        land_radius=r_out - 0.5 * cs.guide, land_width=b.land_width, lands=float(b.lands),
        guide_clearance=0.5 * cs.guide, e_star=e_star, damping_ratio=mod.damping_ratio,
        mu_pocket=mod.pocket_friction, mu_boundary=mod.boundary_friction, mu_guide=mod.guide_friction,
        v_reg=mod.friction_regularisation, eta0=oil.dynamic_viscosity_Pa_s, alpha=oil.pressure_viscosity_1_Pa,
        beta_t=oil.temperature_viscosity_1_K, k_oil=oil.thermal_conductivity_W_mK,
        mu_lim=oil.limiting_traction_coefficient, slide_roll_scale=oil.traction_slide_roll_scale,
        roughness=lub.roughness, film_lo=lub.film_lo, film_hi=lub.film_hi, u_floor=mod.entrainment_floor,
        eps_max=1.0 - mod.guide_min_film / (0.5 * cs.guide), guide_min_film=mod.guide_min_film,
        r_eff_in=np.full(n, 1.0 / (1.0 / r + 1.0 / r_in)), r_eff_out=np.full(n, 1.0 / (1.0 / r - 1.0 / r_out)),
        omega=omega, omega_dot=0.0, crank_radius=crank_radius, gravity_x=-op.gravity, gravity_y=0.0,
        unbalance=op.cage_unbalance_kg_m, table_theta=theta, table_fx=np.asarray(fx, float),
        table_fy=np.asarray(fy, float), table_omega_o=np.asarray(omega_o, float),
    )
    return params, cs, op


def theoretical_speeds(p: Params, omega_o: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pure-rolling cage/orbit speed and roller spin relative to its orbit (frame-relative, rad/s)."""
    orbit = omega_o * p.r_out / (p.r_in + p.r_out)
    spin = omega_o * p.r_out * (p.r_in + p.r_out - 2.0 * p.r_roller) / (2.0 * p.r_roller * (p.r_in + p.r_out))
    return orbit, spin


def quasi_static_ring_offset(p: Params, force: np.ndarray) -> np.ndarray:
    """Outer-ring offset [m] that carries ``force`` (frame components) on the rollers at their pocket
    centres: each roller squeezed by delta_j = -e . n_j - (r_out - r_in - 2 r), inner and outer contact
    in series with equal force, Q_j = (delta_j / (2 C))^(1/0.9) (Palmgren compliance C); solved for
    |e| along the force by bisection."""
    magnitude = float(np.hypot(force[0], force[1]))
    if magnitude == 0.0:
        return np.zeros(2)
    u = -force / magnitude  # the ring moves with the force; rollers on the side u (opposite) carry it
    cos_a = np.cos(p.pocket_angles) * u[0] + np.sin(p.pocket_angles) * u[1]
    gap = p.r_out - p.r_in - 2.0 * p.r_roller
    c = palmgren_compliance(p.l_roller, p.e_star)

    def carried(e: float) -> float:
        delta = np.maximum(e * cos_a - gap, 0.0)
        return float(np.sum((delta / (2.0 * c)) ** (1.0 / 0.9) * cos_a))

    hi = max(gap, 0.0) + 1e-6
    while carried(hi) < magnitude:
        hi *= 2.0
    e = brentq(lambda x: carried(x) - magnitude, min(gap, 0.0) - 1e-6, hi, xtol=1e-13)
    return -e * u


def initial_state(p: Params) -> np.ndarray:
    """Rollers in their pocket centres, everything in pure rolling, outer ring at the quasi-static
    offset under the load of t = 0 (external force + its frame and gravity forces); rollers moved
    radially so that their inner and outer approaches are equal."""
    n = p.n
    orbit, spin = theoretical_speeds(p, np.array([p.table_omega_o[0]]))
    ang = p.pocket_angles
    force = np.array([p.table_fx[0] + p.m_ring * (p.crank_radius * p.omega**2 + p.gravity_x),
                      p.table_fy[0] + p.m_ring * p.gravity_y])
    ring = quasi_static_ring_offset(p, force)
    # roller centre radius halfway between the pin surface and the displaced bore along its direction
    bore = p.r_out + ring[0] * np.cos(ang) + ring[1] * np.sin(ang)
    rp = 0.5 * (p.r_in + bore)
    y = np.zeros(n_states(n))
    s = StateView(y, n)
    s.roller_x[:] = rp * np.cos(ang)
    s.roller_y[:] = rp * np.sin(ang)
    s.ring_xy[:] = ring
    s.roller_vx[:] = -orbit[0] * rp * np.sin(ang)
    s.roller_vy[:] = orbit[0] * rp * np.cos(ang)
    s.roller_spin[:] = orbit[0] + spin[0]
    y[n_positions(n) + cage_index(n) + 2] = orbit[0]     # the cage turns with the rollers' orbit
    return y


def atol_vector(p: Params) -> np.ndarray:
    """Absolute tolerances: 1 nm on positions, 1e-6 rad on angles, matching rates (x omega)."""
    n = p.n
    pos = np.concatenate([np.full(2 * n, 1e-9), np.full(n, 1e-6), [1e-9, 1e-9, 1e-6, 1e-9, 1e-9]])
    vel = pos * max(p.omega, 1.0)
    return np.concatenate([pos, vel])


def rhs_function(p: Params) -> Callable[[float, np.ndarray], np.ndarray]:
    """f(t, y) for SciPy, calling the compiled right-hand side with packed parameters."""
    packed = pack(p)
    return lambda t, y: rhs_packed(t, y, *packed)


def solver_options(p: Params, method: str) -> dict:
    """Tolerances, plus the compiled finite-difference Jacobian for the implicit methods."""
    atol = atol_vector(p)
    opts: dict = {"atol": atol}
    if method in ("Radau", "BDF", "LSODA"):
        packed = pack(p)
        typical = 1e3 * atol
        opts["jac"] = lambda t, y: jacobian_packed(t, y, *packed, typical)
    return opts


def integrate(p: Params, revolutions: float, samples_per_revolution: int, method: str = "RK45",
              rtol: float = RTOL) -> tuple[np.ndarray, np.ndarray, int, float]:
    """Integrate from the kinematic start state; returns (t, y, n_rhs, wall time)."""
    require(method in INTEGRATORS, "integrator", method, f"must be one of {list(INTEGRATORS)}")
    require(revolutions > 0, "revolutions", revolutions, "must be > 0")
    period = 2 * np.pi / p.omega
    t_end = revolutions * period
    t_eval = np.linspace(0.0, t_end, int(round(revolutions * samples_per_revolution)) + 1)
    y0 = initial_state(p)
    fun = rhs_function(p)
    fun(0.0, y0)  # compile (or load from the cache) outside the timing
    start = time.perf_counter()
    sol = solve_ivp(fun, (0.0, t_end), y0, method=method, t_eval=t_eval, rtol=rtol, **solver_options(p, method))
    wall = time.perf_counter() - start
    if sol.status != 0:
        raise SolverError(f"{method} stopped at t = {sol.t[-1]:.6g} s of {t_end:.6g} s: {sol.message}")
    return sol.t, sol.y, int(sol.nfev), wall


def slip_histories(p: Params, t: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Cage slip (T,), roller orbital slip (N, T) and roller spin slip (N, T) in % at the samples
    (t, y) (definitions in the module docstring)."""
    s = StateView(y, p.n)
    omega_o = np.interp((p.omega * t) % (2 * np.pi), p.table_theta, p.table_omega_o)
    orbit_th, spin_th = theoretical_speeds(p, omega_o)
    xr, yr, vxr, vyr, wr = s.roller_x, s.roller_y, s.roller_vx, s.roller_vy, s.roller_spin
    orbit = (xr * vyr - yr * vxr) / (xr**2 + yr**2)
    cage = s.cage_speed
    return (100.0 * (1.0 - (p.omega + cage) / (p.omega + orbit_th)),
            100.0 * (1.0 - (p.omega + orbit) / (p.omega + orbit_th)),
            100.0 * (1.0 - (wr - orbit) / spin_th))


def simulate(case: BigEndCase, set_number: int, mode: str, revolutions: float | None = None,
             method: str | None = None, overrides: dict[str, Any] | None = None) -> RunResult:
    """Run one case: integrate, then sample pocket forces, loads and slip ratios (``method`` None:
    the measured default of the mode; ``overrides``: model parameters replaced by name, for
    sensitivity studies, e.g. ``{"mu_pocket": 0.0}``)."""
    p, cs, op = build_params(case, set_number, mode)
    if overrides:
        unknown = sorted(set(overrides) - set(Params._fields))
        require(not unknown, "overrides", unknown, f"must be fields of Params {list(Params._fields)}")
        p = p._replace(**overrides)
    method = DEFAULT_INTEGRATOR[mode] if method is None else method
    revs = op.revolutions if cs.revolutions is None else cs.revolutions
    revs = revs if revolutions is None else revolutions
    t, y, nfev, wall = integrate(p, revs, case.samples_per_revolution, method)
    n = p.n
    pocket = np.empty((n, t.size))
    q_in = np.empty((n, t.size))
    q_out = np.empty((n, t.size))
    for k in range(t.size):
        _, pocket[:, k], q_in[:, k], q_out[:, k] = evaluate(t[k], y[:, k], p)
    cage_slip, orbital_slip, spin_slip = slip_histories(p, t, y)
    return RunResult(
        mode=mode, clearance=cs, params=p, t=t, crank_angle=p.omega * t, y=y,
        cage_slip_pct=cage_slip, roller_orbital_slip_pct=orbital_slip, roller_spin_slip_pct=spin_slip,
        pocket_force_n=pocket, inner_load_n=q_in, outer_load_n=q_out, revolutions=revs,
        transient_revolutions=min(case.transient_revolutions, 0.5 * revs), wall_time_s=wall,
        integrator=method, n_rhs=nfev,
    )
