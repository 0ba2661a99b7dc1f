"""Quasi-static axisymmetric thermo-elastic-plastic solver driven by temperature and phase histories.

Unknown: the displacement (u_r, u_z) from the hot (austenitised, stress-free) geometry on quadratic
triangles.  Per step the material-point state (free strain, plastic and TRIP strain tensors,
equivalent plastic strain, stress) is advanced by :func:`~quenchsim.mechanics.constitutive.return_map`
inside a Newton iteration with the consistent tangent (inexact linear solves by Cholesky-preconditioned CG,
a predictor from the previous increment, residual line search); the state is committed only when
Newton converges, so the caller can cut the step and retry.

Rigid-body motion: u_r = 0 on nodes on the axis (r = 0, solid parts); axial rigid motion is removed by
fixing u_z of one node (``fixed_point``, or the node nearest the section centroid).  There is no
radial rigid motion in axisymmetry.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any, cast

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from skfem import Basis, ElementTriP1, ElementTriP2, MeshTri

from quenchsim.errors import InputError
from quenchsim.fem import INTORDER
from quenchsim.fem.linalg import norm as _norm
from quenchsim.fem.linalg import SparseCholesky, pcg
from quenchsim.materials import PHASES, Property
from quenchsim.mechanics.assembly import AxisymmetricAssembler
from quenchsim.mechanics.constitutive import M_VEC, SQRT2, PointUpdate, lame_bulk_shear, von_mises
from quenchsim.mechanics.model import MechanicsModel, free_strain, free_strain_increment, trip_saturation

LINEAR_RTOL = 1e-10
"""Relative residual of the linear solves of a linear (elastic/TRIP) step."""
FORCING_MAX = 1e-2
"""Largest relative residual of a linear solve inside a plastic Newton iteration (inexact Newton)."""
ROUND_OFF = 1e-12
"""Residuals below this fraction of the forces of D |eps| are round-off. Measured floors: ~7e-15 of it on a
cooled stress-free ring; 1.4-2.0e-13 on ring A (austenite only, 3000 W/m2K, steps of 5 K / 5 s), where from
t ~ 850 s the Newton iterations of near-zero loads wandered at 4-6e-5 N against a 2.8e-5 N tolerance and the run
was refused at 899.4 s; 1e-12 keeps a 5x margin (a force imbalance of 1e-12 of D |eps| moves the ring by
~1e-13 m)."""
LINE_SEARCH_CUTS = 4
"""Newton steps are halved up to this many times until the residual norm decreases."""
AXIS_TOLERANCE = 1e-9
"""Nodes with r below this fraction of the section size count as lying on the axis."""


@dataclass(frozen=True)
class StepInfo:
    """Outcome of one :meth:`MechanicsSolver.step`."""

    converged: bool
    newton_iterations: int
    residual_norm_N: float
    plastic_points: int
    max_d_eq_plastic: float
    residual_history_N: tuple[float, ...] = ()


class _LinearSolver:
    """Solves K x = b to a relative residual ``rtol``: conjugate gradients preconditioned by the LDL' factor of an
    earlier tangent (the tangent changes slowly between Newton iterations and steps).

    When to refactorise is a rent-or-buy choice: the next solve refactorises once the CG iterations since the last
    factorisation exceed ``budget``, and a solve that needs more than ``max_cg`` iterations refactorises at once.
    The tangents keep their pattern, so a refactorisation is numeric only (:meth:`SparseCholesky.refactorize`):
    measured on ring A, it costs as much as 12-14 preconditioned CG iterations at mesh factors 1 and 0.5 (7.5-8 ms
    against ~0.65 ms at 9882 DOFs, 63 ms against ~5.3 ms at 33,710). The budget is twice that: counted on ring A
    condition 1, budgets 12 / 24 / 48 take 170 / 112 / 69 refactorisations and 2730 / 3107 / 3629 factor solves at
    mesh factor 1 (~3.10 / 2.89 / 2.90 s at those costs), and budgets 6 / 12 / 24 take 287 / 220 / 139 and
    3196 / 3578 / 4052 at 0.5 (~35.0 / 32.9 / 30.2 s): the iterations per solve grow slowly as the factor ages, so
    buying later pays. (With CHOLMOD, which re-ordered at every factorisation, a factorisation was worth 92-113
    iterations and the budget was 100; docs/experiments/stress_preconditioner.md.) K is symmetric positive definite
    (associative J2 flow, H >= 0, rigid modes removed), so CG applies and the factor skips the definiteness check."""

    def __init__(self, max_cg: int = 60, budget: int = 24) -> None:
        self.max_cg = max_cg
        self.budget = budget
        self._stale = True
        self._since_factorisation = 0
        self._factor: SparseCholesky | None = None
        self._factored_matrix: sp.csr_matrix | None = None
        self.factorizations = 0
        self.cg_iterations = 0

    def checkpoint_state(self) -> dict[str, Any]:
        return {"stale": self._stale, "factored_matrix": self._factored_matrix,
                "since_factorisation": self._since_factorisation}

    def restore_state(self, state: Mapping[str, Any]) -> None:
        """Continue from :meth:`checkpoint_state` (refactorises the kept tangent: the same factor)."""
        self._stale = bool(state["stale"])
        self._since_factorisation = int(state["since_factorisation"])
        self._factored_matrix = state.get("factored_matrix")
        self._factor = (None if self._factored_matrix is None
                        else SparseCholesky(self._factored_matrix, check_definite=False))

    def solve(self, K: sp.csr_matrix, b: np.ndarray, rtol: float) -> np.ndarray:
        if not self._stale:
            x = np.zeros_like(b)
            # not stale: a factor exists (a solve without one refactorises and leaves it)
            done, its = pcg(K, b, x, rtol * _norm(b), cast(SparseCholesky, self._factor).solve, self.max_cg)
            self.cg_iterations += its
            self._since_factorisation += its
            self._stale = self._since_factorisation > self.budget  # the next solve refactorises
            if done:
                return x
        if self._factor is None:
            self._factor = SparseCholesky(K, check_definite=False)
        else:
            self._factor.refactorize(K)
        self._factored_matrix = K
        self._stale = False
        self._since_factorisation = 0
        self.factorizations += 1
        return self._factor.solve(b)


@dataclass
class _State:
    free: np.ndarray     # (ne, nq) isotropic free strain relative to austenite at T_aust
    plastic: np.ndarray  # (ne, nq, 4) Mandel plastic strain
    trip: np.ndarray     # (ne, nq, 4) Mandel TRIP strain
    eq_plastic: np.ndarray  # (ne, nq) equivalent plastic strain (hardening variable)
    stress: np.ndarray   # (ne, nq, 4) Mandel stress
    creep: np.ndarray | None = None   # (ne, nq, 4) Mandel relaxation (creep) strain of a temper; None before one


class MechanicsSolver:
    """Axisymmetric small-strain solver on ``mesh`` (MeshTri in metres, x = r >= 0, y = z)."""

    def __init__(self, mesh: MeshTri, model: MechanicsModel, fixed_point: tuple[float, float] | None = None,
                 *, dirichlet: Mapping[str, np.ndarray] | None = None) -> None:
        """``fixed_point`` (r_m, z_m): the vertex nearest to it has u_z = 0 (default: nearest the section
        centroid).  ``dirichlet`` optionally adds homogeneous constraints {"r" | "z": P2 node indices k}
        (node k has DOFs 2k, 2k+1 and sits at ``basis.doflocs[:, 2k]``), e.g. u_z = 0 on both ends."""
        if np.any(mesh.p[0] < -AXIS_TOLERANCE * np.ptp(mesh.p[0])):
            raise InputError("mesh", float(mesh.p[0].min()), "radial coordinates must be >= 0 (x = r)")
        self.mesh = mesh
        self.model = model
        self.asm = AxisymmetricAssembler(mesh, INTORDER)
        self.basis = self.asm.basis
        ne, nq = self.asm.radius.shape
        self._state = _State(free=np.zeros((ne, nq)), plastic=np.zeros((ne, nq, 4)), trip=np.zeros((ne, nq, 4)),
                             eq_plastic=np.zeros((ne, nq)), stress=np.zeros((ne, nq, 4)))
        self._started = False
        self.displacement_m = np.zeros(self.asm.n_dofs)
        self.fixed_dofs = self._constraints(fixed_point, dirichlet or {})
        self._zero_pos, self._diag_pos = self.asm.pattern.constrained_pattern(self.fixed_dofs)
        self._projector = self._vertex_projector()
        self.linear_solver = _LinearSolver()
        self._last_increment: np.ndarray | None = None
        self._last_load = 0.0

    # ------------------------------------------------------------------ setup
    def _constraints(self, fixed_point: tuple[float, float] | None, dirichlet: Mapping[str, np.ndarray]) -> np.ndarray:
        locs = self.basis.doflocs  # (2, n_dofs); dofs 2k, 2k+1 are (u_r, u_z) of node k
        r_nodes, z_nodes = locs[0, 0::2], locs[1, 0::2]
        size = max(np.ptp(self.mesh.p[0]), np.ptp(self.mesh.p[1]))
        fixed = [2 * np.flatnonzero(r_nodes <= AXIS_TOLERANCE * size)]
        if fixed_point is None:
            area = self.basis.dx
            xq = np.asarray(self.basis.global_coordinates())
            target = np.array([np.sum(xq[0] * area), np.sum(xq[1] * area)]) / np.sum(area)
        else:
            target = np.asarray(fixed_point, dtype=float)
            if target.shape != (2,):
                raise InputError("mechanics.fixed_point", fixed_point, "must be (r_m, z_m)")
        vertex_nodes = self.basis.nodal_dofs[1] // 2
        nearest = vertex_nodes[np.argmin((r_nodes[vertex_nodes] - target[0]) ** 2 + (z_nodes[vertex_nodes] - target[1]) ** 2)]
        fixed.append(np.array([2 * nearest + 1]))
        for comp, nodes in dirichlet.items():
            if comp not in ("r", "z"):
                raise InputError("mechanics.dirichlet", comp, "component must be 'r' or 'z'")
            fixed.append(2 * np.asarray(nodes, dtype=int) + (comp == "z"))
        return np.unique(np.concatenate(fixed))

    def _vertex_projector(self) -> tuple[sp.csr_matrix, spla.SuperLU]:
        """L2 projection (area weighted) of quadrature values onto the P1 vertex field: the matrix of
        int phi_i f dA and the factorised P1 mass matrix."""
        p1 = self._p1 = Basis(self.mesh, ElementTriP1(), intorder=INTORDER)
        ne, nq = self.asm.radius.shape
        phi = np.stack([np.asarray(p1.basis[j][0]) for j in range(3)])  # (3, ne, nq)
        rows = np.repeat(p1.element_dofs[:, :, None], nq, axis=2).ravel()
        cols = np.tile(np.arange(ne * nq).reshape(ne, nq), (3, 1, 1)).ravel()
        load = sp.csr_matrix(((phi * p1.dx).ravel(), (rows, cols)), shape=(self.mesh.p.shape[1], ne * nq))
        mass = np.einsum("ieq,jeq,eq->eij", phi, phi, p1.dx)
        r_idx = np.repeat(p1.element_dofs.T[:, :, None], 3, axis=2).ravel()
        c_idx = np.repeat(p1.element_dofs.T[:, None, :], 3, axis=1).ravel()
        M = sp.csc_matrix((mass.ravel(), (r_idx, c_idx)), shape=(self.mesh.p.shape[1],) * 2)
        return load, spla.splu(M)

    # ------------------------------------------------------------------ stepping
    def step(self, T_C: np.ndarray, fractions: Mapping[str, np.ndarray], T_prev_C: np.ndarray,
             fractions_prev: Mapping[str, np.ndarray], external_force_N: np.ndarray | None = None, *,
             extra_free_strain: np.ndarray | None = None, relaxation_increment: np.ndarray | None = None) -> StepInfo:
        """Advance from (T_prev, fractions_prev) to (T, fractions); commit the state if Newton converges.

        Arrays are shaped (n_elements, n_quadrature_points) of ``Basis(mesh, ElementTriP2(), intorder=4)``.
        ``external_force_N`` is a nodal load vector per radian (e.g. from
        :func:`quenchsim.mechanics.loads.surface_load`) at the end of the step. A temper adds
        ``extra_free_strain``, the step's isotropic free-strain increment of the tempering reactions, and
        ``relaxation_increment`` dr >= 0: a viscous (creep) strain d eps_cr = 3/2 dPhi s_{n+1} with
        3 mu dPhi = exp(dr) - 1, so that at a fixed strain the deviatoric stress falls by exp(-dr) exactly (the
        implicit update of the TRIP term, :mod:`quenchsim.mechanics.constitutive`, carries it).
        """
        model, asm, st = self.model, self.asm, self._state
        shape = asm.radius.shape
        X1 = {p: np.broadcast_to(np.asarray(fractions.get(p, 0.0), dtype=float), shape) for p in PHASES}
        X0 = {p: np.broadcast_to(np.asarray(fractions_prev.get(p, 0.0), dtype=float), shape) for p in PHASES}
        T1 = np.broadcast_to(np.asarray(T_C, dtype=float), shape)
        T0 = np.broadcast_to(np.asarray(T_prev_C, dtype=float), shape)
        free0 = st.free if self._started else free_strain(model, T0, X0)
        free1 = free0 + free_strain_increment(model, T0, T1, X0, X1)
        if extra_free_strain is not None:
            free1 = free1 + extra_free_strain

        bulk, shear = lame_bulk_shear(model.E_Pa(T1, X1), model.nu(T1, X1))
        eq_plastic, yield_now, hardening = self._hardening(T1, X0, X1)
        d_phi = self._trip_increment(T1, X0, X1)
        d_phi_creep = None
        if relaxation_increment is not None:
            d_phi_creep = np.expm1(np.maximum(relaxation_increment, 0.0)) / (3.0 * shear)
            d_phi = d_phi_creep if d_phi is None else d_phi + d_phi_creep

        f_ext = np.zeros(asm.n_dofs) if external_force_N is None else np.asarray(external_force_N, dtype=float)
        base = free1[..., None] * M_VEC + st.plastic + st.trip
        if st.creep is not None:
            base = base + st.creep

        def evaluate(u: np.ndarray):
            update, f_int, f_abs = asm.evaluate(u, base, bulk, shear, yield_now, hardening, d_phi)
            residual = f_int - f_ext
            residual[self.fixed_dofs] = 0.0
            return update, residual, _norm(residual), _norm(f_abs)

        u = self.displacement_m.copy()
        update, residual, norm, f_abs = evaluate(u)
        reference = max(_norm(f_ext), norm)  # the step's out-of-balance load
        # round-off scale of sigma = D (eps - eps_free): the forces of D |eps| (|f_abs| misses it when the
        # two strains cancel, e.g. a cooled, stress-free part, whose residual then stalls ~1e-14 below it)
        strain_scale = _norm(asm.internal_force((3.0 * bulk + 2.0 * shear)[..., None] * np.abs(asm.strain(u)))[1])
        load = float(np.sqrt(np.mean((free1 - free0) ** 2)))
        if self._last_increment is not None and self._last_load > 0.0:
            # predictor: the last displacement increment scaled by the ratio of free-strain increments
            guess = u + (load / self._last_load) * self._last_increment
            candidate = evaluate(guess)
            if candidate[2] < norm:
                u = guess
                update, residual, norm, f_abs = candidate
        history = [norm]
        for iteration in range(model.max_newton_iterations + 1):
            if norm <= model.newton_rtol * reference + max(1e-12 * f_abs, ROUND_OFF * strain_scale):
                self._last_increment, self._last_load = u - self.displacement_m, load
                self._commit(u, free1, update, eq_plastic, d_phi_creep, d_phi)
                return StepInfo(True, iteration, norm, int(np.count_nonzero(update.d_eq_plastic)),
                                float(update.d_eq_plastic.max(initial=0.0)), tuple(history))
            if iteration == model.max_newton_iterations or not np.isfinite(norm):
                break
            K = asm.stiffness(update)
            K.data[self._zero_pos] = 0.0
            K.data[self._diag_pos] = 1.0
            eta = self._forcing(iteration, yield_now is None, update, norm, reference, history)
            du = -self.linear_solver.solve(K, residual, eta)
            best = None
            for cut in range(LINE_SEARCH_CUTS + 1):  # backtrack until the residual decreases
                trial = evaluate(u + 0.5**cut * du)
                if best is None or trial[2] < best[1][2]:
                    best = (0.5**cut, trial)
                if trial[2] < norm:
                    break
            assert best is not None   # the first cut always sets it
            u = u + best[0] * du
            update, residual, norm, f_abs = best[1]
            history.append(norm)
        return StepInfo(False, model.max_newton_iterations, norm, 0, 0.0, tuple(history))

    def _hardening(self, T1: np.ndarray, X0: Mapping[str, np.ndarray], X1: Mapping[str, np.ndarray]
                   ) -> tuple[np.ndarray, np.ndarray | None, np.ndarray | None]:
        """The equivalent plastic strain carried into the step (the share of it the transformed austenite forgets,
        ``1 - hardening_memory``, removed), the yield stress and the hardening modulus at the step's end (None, None
        without plasticity)."""
        model, st = self.model, self._state
        if not model.plasticity:
            return st.eq_plastic, None, None
        transformed = np.clip(X0["austenite"] - X1["austenite"], 0.0, 1.0)
        eq_plastic = st.eq_plastic * (1.0 - (1.0 - model.hardening_memory) * transformed)
        # a plastic model carries yield_Pa and hardening_Pa
        hardening = cast(Property, model.hardening_Pa)(T1, X1)
        return eq_plastic, cast(Property, model.yield_Pa)(T1, X1) + hardening * eq_plastic, hardening

    def _trip_increment(self, T1: np.ndarray, X0: Mapping[str, np.ndarray], X1: Mapping[str, np.ndarray]
                        ) -> np.ndarray | None:
        """The step's transformation-plasticity increment, sum over the products of K_i(T) times the increase of
        their saturation function (None without TRIP)."""
        model = self.model
        if not model.trip:
            return None
        d_phi = np.zeros(self.asm.radius.shape)
        for phase in PHASES[1:]:
            d_phi += cast(Property, model.trip_K_1_Pa).for_phase(phase)(T1) * np.maximum(   # TRIP carries its K
                trip_saturation(model.trip_law, X1[phase]) - trip_saturation(model.trip_law, X0[phase]), 0.0)
        return d_phi

    def _forcing(self, iteration: int, linear: bool, update: PointUpdate, norm: float, reference: float,
                 history: list[float]) -> float:
        """The relative tolerance of the Newton iteration's linear solve."""
        rtol = self.model.newton_rtol
        if linear:  # linear step: one accurate solve
            return LINEAR_RTOL
        if not update.d_eq_plastic.any():
            # every point elastic: the residual is linear in u while they stay elastic, so one solve
            # to a tenth of the Newton tolerance ends the step (a point that yields continues Newton)
            return min(max(0.1 * rtol * reference / norm, LINEAR_RTOL), FORCING_MAX)
        # inexact Newton, Eisenstat & Walker (SIAM J. Sci. Comput. 17 (1996) 16) choice 2
        eta = FORCING_MAX if iteration == 0 else 0.9 * (norm / history[-2]) ** 2
        return min(max(eta, 0.1 * rtol * reference / norm, LINEAR_RTOL), FORCING_MAX)

    def _commit(self, u: np.ndarray, free1: np.ndarray, update: PointUpdate, eq_plastic: np.ndarray,
                d_phi_creep: np.ndarray | None = None, d_phi: np.ndarray | None = None) -> None:
        st = self._state
        self.displacement_m = u
        st.free = free1
        st.plastic = st.plastic + update.d_plastic_strain
        d_trip = update.d_trip_strain
        if d_phi_creep is not None and d_phi is not None:   # the viscous flow shares the TRIP term's direction:
            # split it by its dPhi
            share = np.divide(d_phi_creep, d_phi, out=np.zeros_like(d_phi_creep), where=d_phi > 0.0)[..., None]
            st.creep = (np.zeros_like(st.trip) if st.creep is None else st.creep) + share * d_trip
            d_trip = (1.0 - share) * d_trip
        st.trip = st.trip + d_trip
        st.eq_plastic = eq_plastic + update.d_eq_plastic
        st.stress = update.stress
        self._started = True

    # ------------------------------------------------------------------ checkpoints
    def checkpoint_state(self) -> dict[str, Any]:
        """Everything the next steps depend on: the committed material-point state (free, plastic and TRIP
        strains, hardening variable, stress), the displacement, the predictor and the linear solver's factor."""
        st = self._state
        points = {"free": st.free, "plastic": st.plastic, "trip": st.trip, "eq_plastic": st.eq_plastic,
                  "stress": st.stress}
        if st.creep is not None:
            points["creep"] = st.creep
        return {"points": points,
                "started": self._started, "displacement_m": self.displacement_m,
                "last_increment": self._last_increment, "last_load": self._last_load,
                "linear": self.linear_solver.checkpoint_state()}

    def restore_state(self, state: Mapping[str, Any]) -> None:
        """Continue from :meth:`checkpoint_state`."""
        points = state["points"]
        if np.shape(points["free"]) != self._state.free.shape:
            raise ValueError(f"checkpoint state of shape {np.shape(points['free'])} for a mesh of {self._state.free.shape}")
        self._state = _State(**{name: np.array(points[name]) for name in ("free", "plastic", "trip", "eq_plastic",
                                                                          "stress")},
                             creep=np.array(points["creep"]) if "creep" in points else None)
        self._started = bool(state["started"])
        self.displacement_m = np.array(state["displacement_m"])
        self._last_increment = None if state.get("last_increment") is None else np.array(state["last_increment"])
        self._last_load = float(state["last_load"])
        self.linear_solver.restore_state(state["linear"])

    # ------------------------------------------------------------------ results
    @property
    def stress_Pa(self) -> dict[str, np.ndarray]:
        """Stress components at the quadrature points (rr, zz, tt, rz) in Pa, each (ne, nq)."""
        s = self._state.stress
        return {"rr": s[..., 0], "zz": s[..., 1], "tt": s[..., 2], "rz": s[..., 3] / SQRT2}

    @property
    def quadrature_state(self) -> dict[str, np.ndarray]:
        """Committed material-point state: free strain, plastic and TRIP strains (tensor components
        rr, zz, tt, rz; after a temper also its relaxation strain ``creep_strain_*``), equivalent plastic strain and
        von Mises stress, at the quadrature points."""
        st = self._state
        out = {"free_strain": st.free, "equivalent_plastic_strain": st.eq_plastic,
               "von_mises_Pa": von_mises(st.stress)}
        tensors = [("plastic_strain", st.plastic), ("trip_strain", st.trip)]
        if st.creep is not None:   # a tempered part's relaxation strain
            tensors.append(("creep_strain", st.creep))
        for name, tensor in tensors:
            for k, comp in enumerate(("rr", "zz", "tt")):
                out[f"{name}_{comp}"] = tensor[..., k]
            out[f"{name}_rz"] = tensor[..., 3] / SQRT2
        return out

    def project_to_vertices(self, values: np.ndarray) -> np.ndarray:
        """L2 projection of a quadrature field (ne, nq) onto the mesh vertices (P1)."""
        load, mass = self._projector
        return mass.solve(load @ np.asarray(values, dtype=float).ravel())

    def vertex_displacement(self) -> np.ndarray:
        """Displacement (n_vertices, 2) of the mesh vertices."""
        return self.displacement_m[self.basis.nodal_dofs].T

    def sample(self, points_m: np.ndarray) -> dict[str, np.ndarray]:
        """Stress components (rr, zz, tt, rz, von_mises; Pa) and the displacement (u_r, u_z; m) at
        points (2, n) of the hot section (residual-stress probes, hoop traverses), interpolated from
        the vertex projection (displacement: from the quadratic field)."""
        probes = self._p1.probes(np.asarray(points_m, dtype=float))
        fields = self.nodal_fields()
        out = {comp: probes @ fields[f"stress_{comp}_Pa"] for comp in ("rr", "zz", "tt", "rz")}
        out["von_mises"] = probes @ fields["von_mises_Pa"]
        quadratic = Basis(self.mesh, ElementTriP2(), intorder=1).probes(np.asarray(points_m, dtype=float))
        out["u_r"] = quadratic @ self.displacement_m[0::2]  # node k of the vector basis = scalar P2 DOF k
        out["u_z"] = quadratic @ self.displacement_m[1::2]
        return out

    def nodal_fields(self) -> dict[str, np.ndarray]:
        """Fields on the mesh vertices (``mesh.p`` order) for VTK output: displacement_m (n, 3, with a
        zero hoop component), stress components and von Mises in Pa, equivalent plastic strain."""
        u = self.vertex_displacement()
        out = {"displacement_m": np.column_stack([u, np.zeros(len(u))])}
        for comp, values in self.stress_Pa.items():
            out[f"stress_{comp}_Pa"] = self.project_to_vertices(values)
        # quantities >= 0 at every quadrature point: the L2 projection overshoots below zero next to a steep
        # gradient (ParaView showed von Mises to -6.9 MPa, plastic strain to -3.5e-4): cut at zero
        out["von_mises_Pa"] = np.maximum(self.project_to_vertices(von_mises(self._state.stress)), 0.0)
        out["equivalent_plastic_strain"] = np.maximum(self.project_to_vertices(self._state.eq_plastic), 0.0)
        return out
