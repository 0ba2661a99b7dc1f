"""Distortion budget: the dimension change of a quenched ring split by the strain that causes it.

The final state of the stress solver satisfies, at every quadrature point,

    eps(u) = eps_el + eps_free I + eps_p + eps_tp,     sigma = C(T, X) : eps_el,

(secant elasticity, :mod:`quenchsim.mechanics.constitutive`) with the moduli C of the final temperature
and phases.  Let L be the linear map "eigenstrain -> displacement" of the final elastic equilibrium,
L(e) = K^-1 int B^T C e r dA, with K = int B^T C B r dA and the solver's own supports.  L is linear and
L(eps(u)) = u for any compatible u, so

    u = L(eps_free - eps_ann) + L(eps_p) + L(eps_tp) + L(eps_el) + L(eps_ann)

exactly.  L(eps_ann) of the uniform annealed free strain is the stress-free expansion eps_ann x that
turns the austenitised section into the "before" (annealed) one, so the displacement from "before" to
"after" is the sum of four parts:

(a) ``free_strain``: the free (thermal + structural) strain of the final phases against the annealed
    state, eps_free - eps_ann, including the elastic accommodation of its non-uniformity;
(b) ``thermal_plasticity``: the classical plastic strain eps_p (driven by thermal and transformation
    stresses alike);
(c) ``transformation_plasticity``: the TRIP strain eps_tp;
(d) ``elastic_residue``: L(eps_el) = K^-1 int B^T sigma r dA, the displacement the out-of-balance force of
    the final stress would cause.  It vanishes when the final state is in equilibrium -- the residual
    stresses are the elastic accommodation of (a)-(c) and change no dimension by themselves -- so a
    non-zero residue flags an unconverged final state.

Each part's dimension change is the linearised change of the caliper measures
(:func:`~quenchsim.mechanics.dimensions.ring_dimensions`, :func:`section_area_mm2`) of the "before" section
along that part's displacement (:data:`LINEARISATION_SCALE`), so the parts are additive; the total is the
run's own after - before.  The two differ by the measures' second-order terms of the total displacement
(a distorted face's slope times the shift of the caliper line, strain^2 x area), which
:func:`distortion_budget` reports as ``sum_minus_total``.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
import scipy.sparse.linalg as spla
from skfem import MeshTri

from quenchsim.materials import PHASES
from quenchsim.mechanics.constitutive import M_VEC, SQRT2, PointUpdate, lame_bulk_shear
from quenchsim.mechanics.dimensions import ring_dimensions, section_area_mm2

PARTS = ("free_strain", "thermal_plasticity", "transformation_plasticity", "elastic_residue")
RELAXATION_PART = "tempering_relaxation"
"""The part of a tempered ring's budget that its relaxation (creep) strain adds (only when there is one)."""
MEASURES = ("id", "od", "width", "area_mm2")
METHOD = ("superposition through the final elastic equilibrium: each strain part (free strain of the final "
          "phases against the annealed state, plastic, TRIP, elastic) is applied alone as an eigenstrain to the "
          "section with the final moduli and the run's supports; the parts' displacements add up to the run's "
          "displacement from the annealed section exactly (linear map); each part's dimension change is the "
          "linearised change of the caliper measure along its displacement, so they add up to the run's after - before "
          "to within the measure's second-order terms (sum_minus_total). The elastic residue is the out-of-balance of the final state (zero in equilibrium).")


def _mandel(state: Mapping[str, np.ndarray], name: str) -> np.ndarray:
    """A (ne, nq, 4) Mandel tensor from the solver's quadrature_state components."""
    return np.stack([state[f"{name}_rr"], state[f"{name}_zz"], state[f"{name}_tt"], SQRT2 * state[f"{name}_rz"]],
                    axis=-1)


def _elastic_operator(solver: Any, T_C: np.ndarray, fractions: Mapping[str, np.ndarray]):
    """The final moduli (bulk, shear) and the factorised elastic stiffness on the free DOFs."""
    shape = solver.asm.radius.shape
    X = {p: np.broadcast_to(np.asarray(fractions.get(p, 0.0), dtype=float), shape) for p in PHASES}
    T = np.broadcast_to(np.asarray(T_C, dtype=float), shape)
    bulk, shear = lame_bulk_shear(solver.model.E_Pa(T, X), solver.model.nu(T, X))
    ones = np.ones(shape)
    elastic = PointUpdate(stress=np.zeros(shape + (4,)), bulk=bulk, shear=shear, beta=ones, c=ones,
                          normal=np.zeros(shape + (4,)), d_plastic_strain=np.zeros(shape + (4,)),
                          d_trip_strain=np.zeros(shape + (4,)), d_eq_plastic=np.zeros(shape))
    free = np.setdiff1d(np.arange(solver.asm.n_dofs), solver.fixed_dofs)
    K = solver.asm.stiffness(elastic).tocsc()[free][:, free]
    return bulk, shear, free, spla.splu(K.tocsc())


def eigenstrain_displacements(solver: Any, T_C: np.ndarray, fractions: Mapping[str, np.ndarray],
                              annealed_free_strain: float) -> dict[str, np.ndarray]:
    """Displacement (vector-P2 DOFs) of each part of the budget, L(part), on the solver's (hot) mesh."""
    state = solver.quadrature_state
    bulk, shear, free, lu = _elastic_operator(solver, T_C, fractions)
    eps_free = (state["free_strain"] - annealed_free_strain)[..., None] * M_VEC
    parts = {"free_strain": eps_free, "thermal_plasticity": _mandel(state, "plastic_strain"),
             "transformation_plasticity": _mandel(state, "trip_strain")}
    if "creep_strain_rr" in state:
        parts[RELAXATION_PART] = _mandel(state, "creep_strain")
    out = {}
    for name, eps in parts.items():
        vol = eps[..., 0] + eps[..., 1] + eps[..., 2]
        stress = (bulk * vol)[..., None] * M_VEC + (2.0 * shear)[..., None] * (eps - (vol / 3.0)[..., None] * M_VEC)
        out[name] = _solve(solver, free, lu, solver.asm.internal_force(stress)[0])
    stress = np.stack([solver.stress_Pa["rr"], solver.stress_Pa["zz"], solver.stress_Pa["tt"],
                       SQRT2 * solver.stress_Pa["rz"]], axis=-1)
    out["elastic_residue"] = _solve(solver, free, lu, solver.asm.internal_force(stress)[0])
    return out


def _solve(solver: Any, free: np.ndarray, lu: Any, force: np.ndarray) -> np.ndarray:
    u = np.zeros(solver.asm.n_dofs)
    u[free] = lu.solve(force[free])
    return u


LINEARISATION_SCALE = 1e-3
"""A part's dimension change is the directional derivative of the measure along its displacement, taken as
(measure(before + s u) - measure(before)) / s with this s: the measure's own curvature (a face's slope
times the shift of the caliper line) then enters the parts 1000x reduced, and the parts add up."""


def _measures(before_mesh: MeshTri, displacement_m: np.ndarray | None) -> dict[str, float]:
    dims = ring_dimensions(before_mesh, displacement_m)
    dims["area_mm2"] = section_area_mm2(before_mesh, displacement_m)
    return dims


def _linear_change(before_mesh: MeshTri, before: Mapping[str, float], displacement_m: np.ndarray) -> dict[str, float]:
    moved = _measures(before_mesh, LINEARISATION_SCALE * displacement_m)
    return {k: (moved[k] - before[k]) / LINEARISATION_SCALE for k in MEASURES}


def distortion_budget(solver: Any, before_mesh: MeshTri, T_C: np.ndarray, fractions: Mapping[str, np.ndarray],
                      annealed_free_strain: float) -> dict[str, Any]:
    """The ``distortion_budget_mm`` block of summary.json (see the module docstring for the method).

    ``solver``: the MechanicsSolver after the last step; ``before_mesh``: the annealed ("before") section
    (the solver's mesh scaled by 1 + annealed_free_strain); ``T_C``, ``fractions``: the final temperature
    and phase fractions at the quadrature points (they give the final moduli).  Lengths in mm, area in
    mm^2; ``total`` is the run's after - before, ``sum_minus_total`` the budget's closure error.
    """
    before = _measures(before_mesh, None)
    after = ring_dimensions(solver.mesh, solver.displacement_m)
    after["area_mm2"] = section_area_mm2(solver.mesh, solver.displacement_m)
    total = {k: after[k] - before[k] for k in MEASURES}
    parts = {}
    for name, u in eigenstrain_displacements(solver, T_C, fractions, annealed_free_strain).items():
        parts[name] = _linear_change(before_mesh, before, u)
    names = [*PARTS, *([RELAXATION_PART] if RELAXATION_PART in parts else [])]
    closure = {k: sum(parts[p][k] for p in names) - total[k] for k in MEASURES}
    return {"method": METHOD, "parts": {p: parts[p] for p in names}, "total": total, "sum_minus_total": closure}
