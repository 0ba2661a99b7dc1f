"""Finite-element check of the clutch's outer ring: a plane-stress annulus (scikit-fem, quadratic triangles on
a structured polar mesh graded toward the bore and the rollers) under the same bore tractions as the closed
forms of :mod:`quenchsim.bearings.roller_clutch.ring` (a uniform pressure, or n Hertz strips with a tangential
traction and the torque reacted by a uniform shear on the outer surface). The three rigid-body modes are
removed after the solve (zero mean displacement and rotation); displacement and stress are read at the
requested points in the element each lies in.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from skfem import Basis, ElementTriP2, ElementVector, FacetBasis, LinearForm, MeshTri, asm
from skfem.helpers import dot
from skfem.models.elasticity import lame_parameters, linear_elasticity

from quenchsim.errors import require
from quenchsim.fem.linalg import SparseCholesky
from quenchsim.fem.probes import gradient_at


@dataclass(frozen=True)
class RingFE:
    """FE solution sampled at (r, theta) points: radial displacement (m) and hoop stress (Pa); mesh size."""

    u_r: np.ndarray
    s_tt: np.ndarray
    nodes: int
    triangles: int


def polar_mesh(bore_radius_m: float, outer_radius_m: float, rollers: int, *, per_pitch: int = 48,
               layers: int = 20, first_layer_m: float | None = None, max_layer_m: float | None = None,
               growth: float = 1.15, focus: float = 0.0) -> MeshTri:
    """Triangles on an annulus: ``rollers * per_pitch`` angular divisions (clustered about each roller at
    theta = 2 pi j / n when ``focus`` > 0: theta = (pi/n) sinh(focus s)/sinh(focus)) and radial divisions:
    ``layers`` uniform ones, or, with ``first_layer_m``, layers growing by ``growth`` from ``first_layer_m``
    at the bore up to ``max_layer_m`` (scaled to fill the wall)."""
    a, b = bore_radius_m, outer_radius_m
    require(isinstance(per_pitch, int) and per_pitch >= 2 and per_pitch % 2 == 0, "per_pitch", per_pitch,
            "must be an even integer >= 2 (nodes under each roller and midway)")
    s = np.linspace(-1.0, 1.0, per_pitch + 1)[:-1]
    local = (math.pi / rollers) * (np.sinh(focus * s) / math.sinh(focus) if focus > 0.0 else s)
    theta = (local[None, :] + 2.0 * math.pi * np.arange(rollers)[:, None] / rollers).ravel()
    if first_layer_m is None:
        radii = np.linspace(a, b, layers + 1)
    else:
        cap = max_layer_m if max_layer_m is not None else b - a
        steps = [first_layer_m]
        while sum(steps) < b - a:
            steps.append(min(steps[-1] * growth, cap))
        steps_a = np.array(steps) * (b - a) / sum(steps)
        radii = a + np.concatenate([[0.0], np.cumsum(steps_a)])
        radii[-1] = b
    nt = theta.size
    R, T = np.meshgrid(radii, theta, indexing="ij")
    p = np.vstack([(R * np.cos(T)).ravel(), (R * np.sin(T)).ravel()])
    idx = np.arange(radii.size * nt).reshape(radii.size, nt)
    i0, i1 = idx[:-1, :], np.roll(idx[:-1, :], -1, axis=1)
    j0, j1 = idx[1:, :], np.roll(idx[1:, :], -1, axis=1)
    t = np.hstack([np.vstack([i0.ravel(), i1.ravel(), j1.ravel()]), np.vstack([i0.ravel(), j1.ravel(), j0.ravel()])])
    return MeshTri(p, t)


def solve_ring(mesh: MeshTri, bore_radius_m: float, outer_radius_m: float, E_Pa: float, nu: float,
               pressure, shear, outer_shear_Pa: float, points_r: np.ndarray, points_theta: np.ndarray) -> RingFE:
    """Solve the plane-stress annulus with the bore pressure ``pressure(theta)`` (Pa, pushing the ring
    outward), the bore shear ``shear(theta)`` (Pa, +theta on the ring) and a uniform outer shear
    ``outer_shear_Pa`` (+theta); sample u_r and sigma_tt at the points."""
    a, b = bore_radius_m, outer_radius_m
    require(math.isfinite(E_Pa) and E_Pa > 0.0, "E_Pa", E_Pa, "must be a positive modulus")
    element = ElementVector(ElementTriP2())
    basis = Basis(mesh, element, intorder=4)
    lam, mu = lame_parameters(E_Pa, nu)
    lam_ps = 2.0 * lam * mu / (lam + 2.0 * mu)  # plane stress
    K = asm(linear_elasticity(lam_ps, mu), basis)
    mid = 0.5 * (a + b)  # boundary facets (chords) split by the radius of their midpoints
    bore = FacetBasis(mesh, element, facets=mesh.facets_satisfying(
        lambda x: np.hypot(x[0], x[1]) < mid, boundaries_only=True), intorder=6)
    outer = FacetBasis(mesh, element, facets=mesh.facets_satisfying(
        lambda x: np.hypot(x[0], x[1]) > mid, boundaries_only=True), intorder=4)

    @LinearForm
    def bore_traction(v, w):
        x, y = w.x
        th = np.arctan2(y, x)
        q, t = pressure(th), shear(th)
        er, et = np.array([np.cos(th), np.sin(th)]), np.array([-np.sin(th), np.cos(th)])
        return dot(q * er + t * et, v)

    @LinearForm
    def outer_traction(v, w):
        x, y = w.x
        th = np.arctan2(y, x)
        return dot(outer_shear_Pa * np.array([-np.sin(th), np.cos(th)]), v)

    f = asm(bore_traction, bore) + asm(outer_traction, outer)
    # the loads are self-equilibrated: pin three dofs (two at the node on theta = 0 of the outer circle, the
    # y one at theta = pi), solve, then remove the rigid-body motion (zero mean displacement and rotation)
    outer_nodes = np.flatnonzero(np.hypot(*mesh.p) > b * (1.0 - 1e-9))
    angle = np.arctan2(mesh.p[1, outer_nodes], mesh.p[0, outer_nodes])
    n0, n1 = outer_nodes[np.argmin(np.abs(angle))], outer_nodes[np.argmin(np.abs(np.abs(angle) - math.pi))]
    pinned = np.array([basis.nodal_dofs[0, n0], basis.nodal_dofs[1, n0], basis.nodal_dofs[1, n1]])
    free = np.setdiff1d(np.arange(K.shape[0]), pinned)
    u = np.zeros(K.shape[0])
    u[free] = SparseCholesky(K[free][:, free], check_definite=False).solve(f[free])
    rigid = Basis(mesh, element, intorder=2)
    C = np.vstack([asm(_mean_x, rigid), asm(_mean_y, rigid), asm(_rotation, rigid)])
    modes = _rigid_modes(basis)
    u -= modes @ np.linalg.solve(C @ modes, C @ u)

    pts = np.vstack([np.maximum(points_r, a * (1.0 + 1e-12)), points_theta])
    pts[0] = np.minimum(pts[0], _outer_chord_radius(mesh, b, points_theta))
    xy = np.vstack([pts[0] * np.cos(pts[1]), pts[0] * np.sin(pts[1])])
    uxy = basis.probes(xy) @ u  # x components of every point, then y
    npt = xy.shape[1]
    u_x, u_y = uxy[:npt], uxy[npt:]
    grad = gradient_at(basis, u, xy)
    exx, eyy, exy = grad[0, 0], grad[1, 1], 0.5 * (grad[0, 1] + grad[1, 0])
    sxx = lam_ps * (exx + eyy) + 2.0 * mu * exx
    syy = lam_ps * (exx + eyy) + 2.0 * mu * eyy
    sxy = 2.0 * mu * exy
    c, s = np.cos(points_theta), np.sin(points_theta)
    s_tt = sxx * s * s + syy * c * c - 2.0 * sxy * s * c
    return RingFE(u_r=u_x * c + u_y * s, s_tt=s_tt, nodes=mesh.p.shape[1], triangles=mesh.t.shape[1])


@LinearForm
def _mean_x(v, w):
    return v[0]


@LinearForm
def _mean_y(v, w):
    return v[1]


@LinearForm
def _rotation(v, w):
    return w.x[0] * v[1] - w.x[1] * v[0]


def _rigid_modes(basis: Basis) -> np.ndarray:
    """The x translation, y translation and rotation about the origin as dof vectors (N, 3): the quadratic
    element interpolates linear fields exactly, so each dof takes the field's value at its location."""
    x, y = basis.doflocs
    comp = np.zeros(basis.N, dtype=int)
    comp[basis.nodal_dofs[1]] = 1
    comp[basis.facet_dofs[1]] = 1
    return np.column_stack([(comp == 0).astype(float), (comp == 1).astype(float), np.where(comp == 0, -y, x)])


def _outer_chord_radius(mesh: MeshTri, outer_radius_m: float, theta: np.ndarray) -> np.ndarray:
    """Radius of the polygonal outer boundary at the angles ``theta`` (a point on the outer circle between two
    boundary nodes lies outside the mesh; it is read on the chord), less 1e-12 relative."""
    radius = np.hypot(*mesh.p)
    nodes = np.sort(np.arctan2(*mesh.p[::-1, radius > outer_radius_m * (1.0 - 1e-9)]))
    nodes = np.concatenate([nodes, [nodes[0] + 2.0 * math.pi]])
    th = np.mod(theta - nodes[0], 2.0 * math.pi) + nodes[0]
    k = np.clip(np.searchsorted(nodes, th, side="right") - 1, 0, nodes.size - 2)
    half = 0.5 * (nodes[k + 1] - nodes[k])
    mid = nodes[k] + half
    return outer_radius_m * np.cos(half) / np.cos(th - mid) * (1.0 - 1e-12)
