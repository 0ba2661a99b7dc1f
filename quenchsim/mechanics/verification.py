"""Verification problems of the mechanics solver with closed-form answers (used by the tests and by the
verification report).  Each ``run_*`` function builds a scikit-fem mesh, runs :class:`MechanicsSolver`
and returns the computed and exact quantities.

Closed forms:
* Lame open-ended thick tube under internal pressure p (Timoshenko & Goodier, Theory of Elasticity,
  1970, section 28): sigma_rr = A - B/r^2, sigma_tt = A + B/r^2, sigma_zz = 0,
  A = p a^2/(b^2 - a^2), B = p a^2 b^2/(b^2 - a^2), u_r = [(1 - nu) A r + (1 + nu) B / r] / E.
* Hollow cylinder in plane strain with a temperature change tau(r) (Timoshenko & Goodier, section 151):
  sigma_rr = alpha E/((1 - nu) r^2) [(r^2 - a^2)/(b^2 - a^2) I(b) - I(r)],
  sigma_tt = alpha E/((1 - nu) r^2) [(r^2 + a^2)/(b^2 - a^2) I(b) + I(r) - tau r^2],
  sigma_zz = nu (sigma_rr + sigma_tt) - alpha E tau, I(r) = int_a^r tau s ds; here the steady
  logarithmic field tau = tau_a ln(b/r)/ln(b/a), for which int s ln(b/s) ds = s^2/2 ln(b/s) + s^2/4.
* Axially restrained bar heated by dT_max and cooled back (uniaxial stress, linear isotropic hardening):
  heating yields at |sigma| = sigma_y, p1 = (E alpha dT_max - sigma_y)/(E + H), sigma = -(sigma_y + H p1);
  cooling back gives sigma = E p1 if elastic, else p2 = (E p1 - sigma_y - H p1)/(E + H),
  sigma = sigma_y + H (p1 + p2).
* Plane-strain thick tube, perfectly plastic von Mises: limit pressure p_L = (2/sqrt 3) sigma_y ln(b/a)
  (Hill, The Mathematical Theory of Plasticity, 1950, ch. V).
* TRIP under constant uniaxial stress sigma (Desalos form): eps_zz = sigma/E + gamma + K sigma f (2 - f),
  eps_rr = -nu sigma/E + gamma - K sigma f (2 - f)/2.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from skfem import Basis, ElementTriP2, ElementVector, MeshTri

from quenchsim.materials import PHASES
from quenchsim.mechanics.loads import surface_load
from quenchsim.mechanics.model import MechanicsModel, free_strain, load_mechanics
from quenchsim.mechanics.solver import MechanicsSolver

T_REF_C = 850.0
"""Stress-free (austenitising) temperature of the verification materials."""


def uniform_material(E_Pa: float, nu: float, alpha_1_K: float = 0.0, *, yield_Pa: float | None = None,
                     hardening_Pa: float = 0.0, gamma: float = 0.0, trip_K_1_Pa: float = 0.0,
                     hardening_memory: float = 0.0) -> dict[str, Any]:
    """A material table whose phases share E, nu, alpha, yield and hardening; austenite -> product phases
    has the linear transformation strain ``gamma`` and TRIP constant ``trip_K_1_Pa`` (expansion form)."""
    mech: dict[str, Any] = {
        "reference": {"austenitizing_T_C": T_REF_C},
        "elastic": {"E_Pa": E_Pa, "nu": nu},
        "free_strain": {"form": "expansion", "alpha_1_K": alpha_1_K,
                        "transformation_strain": {"per_phase": {"austenite": 0.0, "default": gamma}}},
        "annealed": {"free_strain": 0.0},
        "trip": {"law": "desalos", "K_1_Pa": {"per_phase": {"austenite": 0.0, "default": trip_K_1_Pa}}},
    }
    if yield_Pa is not None:
        mech["plastic"] = {"yield_Pa": yield_Pa, "hardening_Pa": hardening_Pa, "hardening_memory": hardening_memory}
    return {"name": "verification", "mechanics": mech}


def uniform_fields(solver: MechanicsSolver, T_C: float | np.ndarray, martensite: float = 0.0) -> tuple[np.ndarray, dict]:
    """Temperature and an austenite/martensite split at the quadrature points."""
    shape = solver.asm.radius.shape
    T = np.broadcast_to(np.asarray(T_C, dtype=float), shape).copy()
    X = {p: np.zeros(shape) for p in PHASES}
    X["martensite"][:] = martensite
    X["austenite"][:] = 1.0 - martensite
    return T, X


def tube_mesh(a: float, b: float, h: float, n_r: int) -> MeshTri:
    """Structured triangulation of the section [a, b] x [0, h] with n_r elements across the wall."""
    n_z = max(1, int(round(n_r * h / (b - a))))
    return MeshTri.init_tensor(np.linspace(a, b, n_r + 1), np.linspace(0.0, h, n_z + 1))


def facets_on_line(mesh: MeshTri, axis: int, value: float) -> np.ndarray:
    """Boundary or interior facets lying on the coordinate line x[axis] = value."""
    return mesh.facets_satisfying(lambda x: np.isclose(x[axis], value, rtol=0.0, atol=1e-12))


@dataclass(frozen=True)
class FieldComparison:
    """Computed vs exact fields at the quadrature points and their relative L2 errors."""

    r: np.ndarray
    computed: dict[str, np.ndarray]
    exact: dict[str, np.ndarray]
    errors: dict[str, float]


def _compare(solver: MechanicsSolver, exact: dict[str, np.ndarray], scale: float) -> FieldComparison:
    computed = {k: solver.stress_Pa[k] for k in exact}
    w = solver.asm.weights
    errors = {k: float(np.sqrt(np.sum(w * (computed[k] - exact[k]) ** 2) / np.sum(w)) / scale) for k in exact}
    return FieldComparison(solver.asm.radius, computed, exact, errors)


def lame_exact(r: np.ndarray, a: float, b: float, p: float, E: float, nu: float) -> dict[str, np.ndarray]:
    """Lame stresses and radial displacement of the open-ended tube (module docstring)."""
    A = p * a**2 / (b**2 - a**2)
    B = p * a**2 * b**2 / (b**2 - a**2)
    return {"rr": A - B / r**2, "tt": A + B / r**2, "zz": 0.0 * r,
            "u_r": ((1.0 - nu) * A * r + (1.0 + nu) * B / r) / E}


def run_lame(n_r: int, a: float = 0.1, b: float = 0.2, h: float = 0.1, p: float = 100e6,
             E: float = 2.0e11, nu: float = 0.3) -> tuple[FieldComparison, float]:
    """Open-ended tube under internal pressure; returns the stress comparison and the max relative
    error of u_r at the vertices."""
    mesh = tube_mesh(a, b, h, n_r)
    model = load_mechanics(uniform_material(E, nu), {"plasticity": False, "trip": False})
    solver = MechanicsSolver(mesh, model, fixed_point=(a, 0.0))
    T, X = uniform_fields(solver, T_REF_C)
    info = solver.step(T, X, T, X, external_force_N=surface_load(mesh, facets_on_line(mesh, 0, a), pressure_Pa=p))
    assert info.converged
    exact = lame_exact(solver.asm.radius, a, b, p, E, nu)
    comparison = _compare(solver, {k: exact[k] for k in ("rr", "tt", "zz")}, p)
    u = solver.vertex_displacement()[:, 0]
    u_exact = lame_exact(mesh.p[0], a, b, p, E, nu)["u_r"]
    return comparison, float(np.max(np.abs(u - u_exact)) / np.max(np.abs(u_exact)))


def log_thermal_exact(r: np.ndarray, a: float, b: float, tau_a: float, E: float, nu: float,
                      alpha: float) -> dict[str, np.ndarray]:
    """Plane-strain thermal stresses of the steady logarithmic temperature change (module docstring)."""
    L = np.log(b / a)

    def integral(x):
        return tau_a / L * ((x**2 / 2 * np.log(b / x) + x**2 / 4) - (a**2 / 2 * np.log(b / a) + a**2 / 4))

    tau = tau_a * np.log(b / r) / L
    c = alpha * E / ((1.0 - nu) * r**2)
    rr = c * ((r**2 - a**2) / (b**2 - a**2) * integral(b) - integral(r))
    tt = c * ((r**2 + a**2) / (b**2 - a**2) * integral(b) + integral(r) - tau * r**2)
    return {"rr": rr, "tt": tt, "zz": nu * (rr + tt) - alpha * E * tau}


def run_log_thermal(n_r: int, a: float = 0.1, b: float = 0.2, h: float = 0.05, tau_a: float = -200.0,
                    E: float = 2.0e11, nu: float = 0.3, alpha: float = 1.2e-5) -> FieldComparison:
    """Hollow cylinder, plane strain (u_z = 0 on both ends), temperature change tau_a ln(b/r)/ln(b/a)
    from the stress-free state; stresses relative to alpha E |tau_a|."""
    mesh = tube_mesh(a, b, h, n_r)
    model = load_mechanics(uniform_material(E, nu, alpha), {"plasticity": False, "trip": False})
    ends = {"z": np.concatenate([nodes_on_line(mesh, 1, 0.0), nodes_on_line(mesh, 1, h)])}
    solver = MechanicsSolver(mesh, model, fixed_point=(a, 0.0), dirichlet=ends)
    r = solver.asm.radius
    T0, X = uniform_fields(solver, T_REF_C)
    T1 = T_REF_C + tau_a * np.log(b / r) / np.log(b / a)
    assert solver.step(T1, X, T0, X).converged
    return _compare(solver, log_thermal_exact(r, a, b, tau_a, E, nu, alpha), alpha * E * abs(tau_a))


def nodes_on_line(mesh: MeshTri, axis: int, value: float) -> np.ndarray:
    """P2 node indices (columns of the vector basis doflocs // 2) on a coordinate line."""
    locs = Basis(mesh, ElementVector(ElementTriP2()), intorder=1).doflocs
    return np.flatnonzero(np.isclose(locs[axis, 0::2], value, rtol=0.0, atol=1e-12))


def restrained_bar_exact(E: float, alpha: float, sigma_y: float, H: float, dT_max: float) -> dict[str, float]:
    """Axial stress after heating by dT_max and after cooling back (module docstring)."""
    p1 = max(E * alpha * dT_max - sigma_y, 0.0) / (E + H)
    hot = -(sigma_y + H * p1) if p1 > 0 else -E * alpha * dT_max
    trial = E * p1
    p2 = max(trial - sigma_y - H * p1, 0.0) / (E + H)
    cold = sigma_y + H * (p1 + p2) if p2 > 0 else trial
    return {"hot": hot, "cold": cold, "p_hot": p1, "p_cold": p1 + p2}


def run_restrained_bar(n_steps: int, dT_max: float = 300.0, E: float = 2.0e11, nu: float = 0.3,
                       alpha: float = 1.2e-5, sigma_y: float = 200e6, H: float = 5e9,
                       R: float = 0.01, L: float = 0.02) -> dict[str, Any]:
    """Solid cylinder (axis included) with u_z = 0 on both ends, heated uniformly by dT_max in n_steps
    and cooled back in n_steps; returns computed and exact axial stress, eq. plastic strain and the
    largest radial/hoop stress (zero exactly) and the Newton iteration counts."""
    mesh = tube_mesh(0.0, R, L, 2)
    model = load_mechanics(uniform_material(E, nu, alpha, yield_Pa=sigma_y, hardening_Pa=H), {"trip": False})
    ends = {"z": np.concatenate([nodes_on_line(mesh, 1, 0.0), nodes_on_line(mesh, 1, L)])}
    solver = MechanicsSolver(mesh, model, fixed_point=(0.0, 0.0), dirichlet=ends)
    path = np.concatenate([np.linspace(0.0, dT_max, n_steps + 1), np.linspace(dT_max, 0.0, n_steps + 1)[1:]])
    iterations, history = [], []
    for dT0, dT1 in zip(path[:-1], path[1:]):
        T0, X = uniform_fields(solver, T_REF_C + dT0)
        T1, _ = uniform_fields(solver, T_REF_C + dT1)
        info = solver.step(T1, X, T0, X)
        assert info.converged
        iterations.append(info.newton_iterations)
        history.append(float(np.mean(solver.stress_Pa["zz"])))
        if dT1 == dT_max and dT0 < dT1:
            hot = {"sigma_zz": history[-1], "p": float(np.mean(solver.quadrature_state["equivalent_plastic_strain"]))}
    s = solver.stress_Pa
    return {"exact": restrained_bar_exact(E, alpha, sigma_y, H, dT_max), "hot": hot,
            "cold": {"sigma_zz": float(np.mean(s["zz"])),
                     "p": float(np.mean(solver.quadrature_state["equivalent_plastic_strain"]))},
            "spread_Pa": float(np.ptp(s["zz"])), "max_lateral_Pa": float(max(np.abs(s["rr"]).max(), np.abs(s["tt"]).max())),
            "newton_iterations": iterations, "path_dT": path[1:], "sigma_zz_history": np.array(history), "solver": solver}


def run_limit_pressure(factor: float, n_r: int = 6, a: float = 0.1, b: float = 0.2, sigma_y: float = 200e6,
                       E: float = 2.0e11, nu: float = 0.3, n_steps: int = 10) -> bool:
    """Load a perfectly plastic plane-strain tube to ``factor`` times Hill's limit pressure in n_steps;
    True if every load step found equilibrium."""
    mesh = tube_mesh(a, b, 0.25 * (b - a), n_r)
    model = load_mechanics(uniform_material(E, nu, yield_Pa=sigma_y, hardening_Pa=0.0),
                           {"trip": False, "max_newton_iterations": 40})
    h = 0.25 * (b - a)
    ends = {"z": np.concatenate([nodes_on_line(mesh, 1, 0.0), nodes_on_line(mesh, 1, h)])}
    solver = MechanicsSolver(mesh, model, fixed_point=(a, 0.0), dirichlet=ends)
    unit = surface_load(mesh, facets_on_line(mesh, 0, a), pressure_Pa=1.0)
    p_limit = 2.0 / np.sqrt(3.0) * sigma_y * np.log(b / a)
    T, X = uniform_fields(solver, T_REF_C)
    for p in np.linspace(0.0, factor * p_limit, n_steps + 1)[1:]:
        if not solver.step(T, X, T, X, external_force_N=p * unit).converged:
            return False
    return True


def run_trip_bar(fractions_path: np.ndarray, sigma: float = 50e6, E: float = 2.0e11, nu: float = 0.3,
                 gamma: float = 5e-3, K: float = 7e-11, R: float = 0.01, L: float = 0.02,
                 plasticity: bool = False) -> dict[str, np.ndarray]:
    """Solid cylinder under constant axial stress sigma (traction on the top, u_z = 0 at the bottom)
    transforming isothermally A -> M along ``fractions_path`` (starting at 0); returns the axial and
    radial strains (from the displacement of the top outer corner) and their closed forms."""
    mesh = tube_mesh(0.0, R, L, 2)
    material = uniform_material(E, nu, gamma=gamma, trip_K_1_Pa=K, yield_Pa=1e9 if plasticity else None)
    model = load_mechanics(material, {"plasticity": plasticity, "trip": True})
    solver = MechanicsSolver(mesh, model, fixed_point=(0.0, 0.0), dirichlet={"z": nodes_on_line(mesh, 1, 0.0)})
    load = surface_load(mesh, facets_on_line(mesh, 1, L), traction_Pa=(0.0, sigma))
    corner = np.flatnonzero(np.isclose(mesh.p[0], R) & np.isclose(mesh.p[1], L))[0]
    eps_zz, eps_rr = [], []
    T, X0 = uniform_fields(solver, T_REF_C, 0.0)
    assert solver.step(T, X0, T, X0, external_force_N=load).converged
    for f0, f1 in zip(fractions_path[:-1], fractions_path[1:]):
        _, Xa = uniform_fields(solver, T_REF_C, f0)
        _, Xb = uniform_fields(solver, T_REF_C, f1)
        assert solver.step(T, Xb, T, Xa, external_force_N=load).converged
        u = solver.vertex_displacement()[corner]
        eps_zz.append(u[1] / L)
        eps_rr.append(u[0] / R)
    f = np.asarray(fractions_path[1:])
    phi = f * (2.0 - f)
    return {"f": f, "eps_zz": np.array(eps_zz), "eps_rr": np.array(eps_rr),
            "eps_zz_exact": sigma / E + gamma * f + K * sigma * phi,
            "eps_rr_exact": -nu * sigma / E + gamma * f - 0.5 * K * sigma * phi,
            "trip_zz_exact": K * sigma * phi}


def run_uniform_free_strain(model: MechanicsModel, T_C: float, martensite: float, n: int = 3) -> dict[str, float]:
    """A ring section cooled uniformly from T_aust (austenite) to T_C with a uniform martensite fraction:
    returns the largest von Mises stress and the largest deviation of the displacement from the free
    expansion u = eps_free (x - x_fixed), both in absolute units, and the free strain."""
    a, b, h = 0.10, 0.14, 0.06
    mesh = tube_mesh(a, b, h, n)
    solver = MechanicsSolver(mesh, model, fixed_point=(a, 0.0))
    T0, X0 = uniform_fields(solver, model.austenitizing_T_C, 0.0)
    T1, X1 = uniform_fields(solver, T_C, martensite)
    info = solver.step(T1, X1, T0, X0)
    assert info.converged
    eps = float(free_strain(model, T_C, {"austenite": 1.0 - martensite, "martensite": martensite})) \
        if model.free_strain_form == "specific_volume" else float(solver.quadrature_state["free_strain"].mean())
    u = solver.vertex_displacement()
    expected = np.column_stack([eps * mesh.p[0], eps * mesh.p[1]])
    return {"max_von_mises_Pa": float(solver.quadrature_state["von_mises_Pa"].max()),
            "max_displacement_error_m": float(np.abs(u - expected).max()), "free_strain": eps}
