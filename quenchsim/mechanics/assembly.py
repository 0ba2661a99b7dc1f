"""Axisymmetric kinematics and sparse assembly with a fixed sparsity pattern.

Quadratic vector triangles (scikit-fem ``ElementVector(ElementTriP2())``); strains in Mandel form
(rr, zz, tt, sqrt(2) rz) with eps_tt = u_r / r; integrals carry the weight r dr dz (per radian, the
factor 2 pi cancels between internal and external forces).  The global matrix structure is computed
once; every assembly sums element values into the CSR data array (compiled loops: :mod:`.kernels`).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementTriP2, ElementVector, MeshTri

from quenchsim.fem import INTORDER, FixedPatternAssembler, r_weights
from quenchsim.mechanics import kernels
from quenchsim.mechanics.constitutive import SQRT2, YIELD_TOLERANCE, PointUpdate


class AxisymmetricAssembler:
    """Strain-displacement matrices at the quadrature points and a reusable CSR pattern."""

    def __init__(self, mesh: MeshTri, intorder: int = INTORDER) -> None:
        self.mesh = mesh
        self.basis = Basis(mesh, ElementVector(ElementTriP2()), intorder=intorder)
        self.n_dofs = self.basis.N
        self.element_dofs = self.basis.element_dofs.T.copy()  # (ne, 12)
        self.radius, self.weights = r_weights(self.basis)  # (ne, nq): r and r dA per quadrature point
        n_local = self.element_dofs.shape[1]
        ne, nq = self.radius.shape
        B = np.empty((ne, nq, 4, n_local))
        for j in range(n_local):  # loop over the 12 local shape functions, not over elements
            field = self.basis.basis[j][0]
            val, grad = np.asarray(field), field.grad
            B[:, :, 0, j] = grad[0, 0]
            B[:, :, 1, j] = grad[1, 1]
            B[:, :, 2, j] = val[0] / self.radius
            B[:, :, 3, j] = (grad[0, 1] + grad[1, 0]) / SQRT2
        self.B = B
        self._B_rows = B.reshape(ne, nq * 4, n_local)  # (ne, nq*4, 12) view: strains and forces are batched GEMVs
        self.pattern = FixedPatternAssembler(self.basis.element_dofs, self.n_dofs)
        self._positions = self.pattern.scatter.reshape(ne, n_local * n_local)

    def strain(self, u: np.ndarray) -> np.ndarray:
        """Mandel strain (ne, nq, 4) of the displacement vector u."""
        return np.matmul(self._B_rows, u[self.element_dofs][:, :, None]).reshape(self.radius.shape + (4,))

    def internal_force(self, stress: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """f_int = int B^T sigma r dA and the same sum of absolute values (a round-off scale)."""
        ne = self.radius.shape[0]
        fe = np.matmul((stress * self.weights[..., None]).reshape(ne, 1, -1), self._B_rows)[:, 0]
        dofs = self.element_dofs.ravel()
        return (np.bincount(dofs, weights=fe.ravel(), minlength=self.n_dofs),
                np.bincount(dofs, weights=np.abs(fe).ravel(), minlength=self.n_dofs))

    def evaluate(self, u: np.ndarray, base_strain: np.ndarray, bulk_Pa: np.ndarray, shear_Pa: np.ndarray,
                 yield_Pa: np.ndarray | None, hardening_Pa: np.ndarray | None,
                 d_trip_Phi_1_Pa: np.ndarray | None) -> tuple[PointUpdate, np.ndarray, np.ndarray]:
        """The return map (:func:`~quenchsim.mechanics.constitutive.return_map`) of the elastic trial strain
        strain(u) - ``base_strain`` at every point, and the internal force with its absolute sum (as
        :meth:`internal_force`), in one compiled pass over the elements."""
        shape = self.radius.shape
        ne, nq = shape

        def points(x: np.ndarray | None) -> np.ndarray:
            return np.ascontiguousarray(np.broadcast_to(0.0 if x is None else x, shape), dtype=float)

        stress, normal, d_plastic, d_trip = (np.empty((ne, nq, 4)) for _ in range(4))
        beta, c, dp = (np.empty(shape) for _ in range(3))
        f_int, f_abs = np.empty(self.n_dofs), np.empty(self.n_dofs)
        bulk, shear = points(bulk_Pa), points(shear_Pa)
        kernels.point_update(self.B, self.element_dofs, self.weights, np.ascontiguousarray(u, dtype=float),
                             np.ascontiguousarray(base_strain, dtype=float), bulk, shear, points(yield_Pa),
                             points(hardening_Pa), points(d_trip_Phi_1_Pa), yield_Pa is not None,
                             d_trip_Phi_1_Pa is not None, YIELD_TOLERANCE, stress, beta, c, normal, dp, d_plastic,
                             d_trip, f_int, f_abs)
        update = PointUpdate(stress=stress, bulk=bulk, shear=shear, beta=beta, c=c, normal=normal,
                             d_plastic_strain=d_plastic, d_trip_strain=d_trip, d_eq_plastic=dp)
        return update, f_int, f_abs

    def stiffness(self, update: PointUpdate) -> sp.csr_matrix:
        """K = int B^T D B r dA on the fixed pattern, with the factored consistent tangent
        D = K m m + 2 mu [beta P + (c - beta) n n] (so B^T D B = K b_v b_v + 2 mu beta B^T P B
        + 2 mu (c - beta) b_n b_n with b_v = m^T B, b_n = n^T B)."""
        shape = self.radius.shape

        def points(x: np.ndarray) -> np.ndarray:
            return np.ascontiguousarray(np.broadcast_to(x, shape), dtype=float)

        data = np.empty(self.pattern.nnz)
        kernels.stiffness_data(self.B, self.weights, points(update.bulk), points(update.shear), points(update.beta),
                               points(update.c), np.ascontiguousarray(np.broadcast_to(update.normal, shape + (4,))),
                               self._positions, data)
        return self.pattern.csr(data)
