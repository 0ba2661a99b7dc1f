"""2-D magnetostatic finite-element check of the encoder field (scikit-fem): one pole pair of the magnetised layer
in air (or on an ideal iron plate), vector potential A_z, quadratic triangles on a tensor mesh aligned with the
magnet faces and the pole boundaries.

With B = curl(A e_z) = (dA/dy, -dA/dx) and H = (B - B_r)/(mu0 mu_r) in the magnet (B_r = (0, +-B_r)), curl H = 0
reads, for every test function v vanishing on the Dirichlet boundary,

    int nu grad A . grad v = - int_magnet nu B_r(x) dv/dx,       nu = 1/(mu0 mu_r) (magnet), 1/mu0 (air).

A = 0 at the pole centres x = 0 and x = 2p (there B_x = 0, so A is constant along the line; by the antisymmetry of
the pole pattern it is the same constant at x = 0, p and 2p) and far above and below the layer; on an ideal iron
plate (infinite permeability) H_t = 0 is the natural condition of the weak form at its face.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from skfem import Basis, BilinearForm, ElementTriP2, LinearForm, MeshTri, asm, condense
from skfem.helpers import dot, grad

from quenchsim.bearings.encoder.field import Encoder
from quenchsim.errors import require
from quenchsim.fem.linalg import SparseCholesky
from quenchsim.fem.probes import gradient_at

MU0 = 4.0e-7 * math.pi
"""Vacuum permeability, H/m (the pre-2019 defined value; the SI 2019 value differs by 1e-10)."""


@dataclass(frozen=True)
class FieldFE:
    """FE pole-centre field B_y (T) at the requested gaps, with the mesh size."""

    gaps_m: np.ndarray
    pole_centre_T: np.ndarray
    nodes: int
    triangles: int


def _axis(lo: float, hi: float, step: float) -> np.ndarray:
    n = max(1, int(math.ceil((hi - lo) / step - 1e-9)))
    return np.linspace(lo, hi, n + 1)


def solve_pole_pair(encoder: Encoder, gaps_m: np.ndarray, *, step_m: float | None = None,
                    far_m: float | None = None) -> FieldFE:
    """B_y at the centre of the south pole (x = p) at the heights ``gaps_m`` above the magnet face, sign turned to
    that of a north pole. ``step_m``: element size over the magnet and the gaps (default p/60, with the gaps
    on mesh lines); ``far_m``: distance from the layer to the outer Dirichlet lines (default 4 pole pairs)."""
    e = encoder
    p, h = e.pole_width_m, e.thickness_m
    gaps = np.asarray(gaps_m, dtype=float)
    require(bool(np.all(gaps >= 0.0)), "gaps_m", gaps_m, "must be >= 0")
    step = p / 60.0 if step_m is None else step_m
    far = 8.0 * p if far_m is None else far_m
    top_fine = h + max(float(gaps.max()), p)
    x = _axis(0.0, 2.0 * p, step)
    for edge in (0.5 * p, p, 1.5 * p):
        require(np.min(np.abs(x - edge)) < 1e-12 * p, "step_m", step, "must divide p/2 (pole boundaries on mesh lines)")
    ys = [_axis(0.0, h, step), _axis(h, top_fine, step)[1:]]
    ys.append(top_fine + np.cumsum(_geometric_steps(step, far)))
    if e.backing == "air":
        ys.insert(0, -np.cumsum(_geometric_steps(step, far))[::-1])
    y = np.unique(np.concatenate(ys + [h + gaps]))
    mesh = MeshTri.init_tensor(x, y)
    basis = Basis(mesh, ElementTriP2())
    nu_air, nu_mag = 1.0 / MU0, 1.0 / (MU0 * e.recoil_permeability)

    def in_magnet(w) -> np.ndarray:
        return (w.x[1] > 0.0) & (w.x[1] < h)

    def remanence(w) -> np.ndarray:
        north = (w.x[0] < 0.5 * p) | (w.x[0] > 1.5 * p)
        return np.where(in_magnet(w), np.where(north, e.remanence_T, -e.remanence_T), 0.0)

    @BilinearForm
    def stiffness(u, v, w):
        return np.where(in_magnet(w), nu_mag, nu_air) * dot(grad(u), grad(v))

    @LinearForm
    def source(v, w):
        return -nu_mag * remanence(w) * grad(v)[0]

    K = asm(stiffness, basis)
    f = asm(source, basis)
    y_lo, y_hi = float(y[0]), float(y[-1])

    def dirichlet(xy: np.ndarray) -> np.ndarray:
        on = (np.abs(xy[0]) < 1e-9 * p) | (np.abs(xy[0] - 2.0 * p) < 1e-9 * p) | (np.abs(xy[1] - y_hi) < 1e-9 * p)
        return on | ((np.abs(xy[1] - y_lo) < 1e-9 * p) & (e.backing == "air"))

    fixed = basis.get_dofs(mesh.facets_satisfying(dirichlet, boundaries_only=True)).all()
    A = np.zeros(basis.N)
    Kc, fc, _, free = condense(K, f, D=fixed)
    A[free] = SparseCholesky(Kc, check_definite=False).solve(fc)
    pts = np.vstack([np.full(gaps.size, p), h + gaps])
    g = gradient_at(basis, A, pts)
    return FieldFE(gaps_m=gaps, pole_centre_T=g[0], nodes=mesh.p.shape[1], triangles=mesh.t.shape[1])


def _geometric_steps(first: float, length: float, growth: float = 1.25) -> np.ndarray:
    """Steps growing by ``growth`` from ``first`` until they cover ``length`` (the last one trimmed)."""
    steps = [first]
    while sum(steps) < length:
        steps.append(steps[-1] * growth)
    steps[-1] -= sum(steps) - length
    return np.array([s for s in steps if s > 1e-6 * first])
