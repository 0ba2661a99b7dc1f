"""Axisymmetric kinematics and sparse assembly with a fixed sparsity pattern.

Quadratic vector triangles (scikit-fem ``ElementVector(ElementTriP2())``); strains in Mandel form
(rr, zz, tt, sqrt(2) rz) with eps_tt = u_r / r; integrals carry the weight r dr dz (per radian, the
factor 2 pi cancels between internal and external forces).  The global matrix structure is computed
once; every assembly only sums element values into the CSR data array (``np.bincount``).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
from skfem import Basis, ElementTriP2, ElementVector, MeshTri

from quenchsim.fem import INTORDER, FixedPatternAssembler, r_weights
from quenchsim.mechanics.constitutive import M_VEC, SQRT2, PointUpdate


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
        B_vol = B[:, :, 0] + B[:, :, 1] + B[:, :, 2]  # m^T B, (ne, nq, 12)
        B_dev = B - B_vol[:, :, None, :] / 3.0 * M_VEC[None, None, :, None]
        # flattened (ne, nq, 144) kernels b_v b_v^T and B^T P B side by side along the quadrature axis:
        # an element matrix is one weighted sum over 2 nq kernel rows
        self.kernel = np.concatenate([(B_vol[:, :, :, None] * B_vol[:, :, None, :]).reshape(ne, nq, -1),
                                      np.einsum("eqai,eqaj->eqij", B_dev, B_dev, optimize=True).reshape(ne, nq, -1)],
                                     axis=1)
        self.pattern = FixedPatternAssembler(self.basis.element_dofs, self.n_dofs)

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

    def stiffness(self, update: PointUpdate) -> sp.csr_matrix:
        """K = int B^T D B r dA on the fixed pattern, with the factored consistent tangent
        D = K m m + 2 mu [beta P + (c - beta) n n] (so B^T D B = K b_v b_v + 2 mu beta B^T P B
        + 2 mu (c - beta) b_n b_n with b_v = m^T B, b_n = n^T B)."""
        w = self.weights
        ne, n_local = self.element_dofs.shape
        coefficient = np.concatenate([update.bulk * w, 2.0 * update.shear * update.beta * w], axis=1)
        Ke = np.einsum("eq,eqk->ek", coefficient, self.kernel).reshape(ne, n_local, n_local)
        soft_weight = 2.0 * update.shear * (update.c - update.beta) * w  # zero at elastic points
        if soft_weight.any():
            # over all elements: cheaper than gathering the plastic ones (most are plastic during a quench)
            Bn = np.matmul(update.normal[:, :, None, :], self.B)[:, :, 0, :]  # n^T B, (ne, nq, 12)
            Ke += np.matmul(Bn.transpose(0, 2, 1) * soft_weight[:, None, :], Bn)
        return self.pattern.matrix(Ke)
