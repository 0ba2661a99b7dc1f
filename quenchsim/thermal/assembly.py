"""Precomputed r-weighted element kernels and a fixed-sparsity assembler for P2 heat conduction.

For axisymmetric conduction the weak forms carry the factor r (x = r, y = z):

    mass        C_ij = int rho c_p phi_i phi_j r dA
    stiffness   K_ij = int k grad phi_i . grad phi_j r dA
    Robin       R_ij = int_Gamma h phi_i phi_j r ds,   F_i = int_Gamma h T_inf phi_i r ds

The shape-function products times ``r dA`` are computed once per mesh at every quadrature point;
a matrix is then the contraction of a coefficient array (elements, quadrature points) with a kernel,
summed into a CSR pattern that is also computed once (only the coefficients change in time).
:meth:`AxisymmetricP2.system` sums mass, conductivity and Robin terms in one pass into the element
pattern (a boundary facet couples only the DOFs of its element, so its entries are a subset).
"""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import skfem
from numba import njit

from quenchsim.fem import INTORDER, FixedPatternAssembler, r_weights


class AxisymmetricP2:
    """Element data of r-weighted P2 conduction on a triangle mesh (metres, x = r, y = z)."""

    def __init__(self, mesh: skfem.MeshTri, robin_facets: np.ndarray, intorder: int = INTORDER) -> None:
        element = skfem.ElementTriP2()
        self.mesh = mesh
        self.basis = skfem.Basis(mesh, element, intorder=intorder)
        b = self.basis
        self.n_dofs = b.N
        self.phi = np.stack([np.asarray(b.basis[i][0]) for i in range(b.Nbfun)])          # (nloc, ne, nq)
        grad = np.stack([np.asarray(b.basis[i][0].grad) for i in range(b.Nbfun)])               # (nloc, 2, ne, nq)
        self._phi_qp = np.ascontiguousarray(self.phi.transpose(1, 2, 0))                 # (ne, nq, nloc)
        self._grad_qp = np.ascontiguousarray(grad.transpose(2, 3, 0, 1))                 # (ne, nq, nloc, 2)
        self.r_qp, self.r_dx = r_weights(b)                                         # (ne, nq): r, r dA
        self.z_qp = np.asarray(b.global_coordinates())[1]
        self.mass_kernel = np.einsum("ieq,jeq,eq->eqij", self.phi, self.phi, self.r_dx, optimize=True)
        self.stiffness_kernel = np.einsum("ideq,jdeq,eq->eqij", grad, grad, self.r_dx, optimize=True)
        self.assembler = FixedPatternAssembler(b.element_dofs, b.N)

        self.facets = np.asarray(robin_facets)
        fb = skfem.FacetBasis(mesh, element, facets=self.facets, intorder=intorder)
        self.facet_basis = fb
        self.fphi = np.stack([np.asarray(fb.basis[i][0]) for i in range(fb.Nbfun)])       # (nloc, nf, nqf)
        self.facet_r, self.facet_r_ds = r_weights(fb)                               # (nf, nqf): r, r ds
        self.facet_z = np.asarray(fb.global_coordinates())[1]
        self.facet_normals = fb.normals                                             # (2, nf, nqf)
        self.robin_kernel = np.einsum("ifq,jfq,fq->fqij", self.fphi, self.fphi, self.facet_r_ds, optimize=True)
        self.facet_assembler = FixedPatternAssembler(fb.element_dofs, b.N)
        # one-pass system assembly: element and Robin facet entries summed into the data array of the element
        # pattern (a boundary facet couples only DOFs of its element, so its entries are a subset)
        ne, nloc = self.r_dx.shape[0], b.Nbfun
        cell, facet = self.assembler, self.facet_assembler
        self._cell_positions = cell.scatter.reshape(ne, nloc * nloc)
        robin_pos = np.searchsorted(cell.keys(), facet.keys())
        self._facet_positions = robin_pos[facet.scatter].reshape(len(self.facets), nloc * nloc)
        self._robin_kernel = np.ascontiguousarray(self.robin_kernel.reshape(self.robin_kernel.shape[0],
                                                                            self.robin_kernel.shape[1], -1))

    # -- fields at quadrature points ------------------------------------------------------------
    def at_qp(self, u: np.ndarray) -> np.ndarray:
        """Nodal P2 field -> values at the element quadrature points, shape (ne, nq)."""
        return np.einsum("ieq,ie->eq", self.phi, u[self.basis.element_dofs])

    def at_facet_qp(self, u: np.ndarray) -> np.ndarray:
        return np.einsum("ifq,if->fq", self.fphi, u[self.facet_basis.element_dofs])

    # -- forms ----------------------------------------------------------------------------------
    def mass(self, coefficient: np.ndarray) -> sp.csr_matrix:
        return self.assembler.matrix(np.einsum("eq,eqij->eij", coefficient, self.mass_kernel))

    def stiffness(self, coefficient: np.ndarray) -> sp.csr_matrix:
        return self.assembler.matrix(np.einsum("eq,eqij->eij", coefficient, self.stiffness_kernel))

    def system(self, mass_coefficient: np.ndarray, conductivity: np.ndarray, robin_coefficient: np.ndarray) -> sp.csr_matrix:
        """mass(mass_coefficient) + stiffness(conductivity) + robin(robin_coefficient), assembled in one
        compiled pass into the element pattern."""
        data = np.empty(self.assembler.nnz)
        _system_data(self._phi_qp, self._grad_qp, self.r_dx, np.ascontiguousarray(mass_coefficient, dtype=float),
                     np.ascontiguousarray(conductivity, dtype=float), self._cell_positions, self._robin_kernel,
                     np.ascontiguousarray(robin_coefficient, dtype=float), self._facet_positions, data)
        return self.assembler.csr(data)

    def load(self, source: np.ndarray) -> np.ndarray:
        """int source phi_i r dA for a source given at quadrature points (ne, nq)."""
        return self.assembler.vector(np.einsum("eq,ieq->ei", source * self.r_dx, self.phi))

    def robin(self, h: np.ndarray) -> sp.csr_matrix:
        return self.facet_assembler.matrix(np.einsum("fq,fqij->fij", h, self.robin_kernel))

    def robin_load(self, h_times_ambient: np.ndarray) -> np.ndarray:
        return self.facet_assembler.vector(np.einsum("fq,ifq->fi", h_times_ambient * self.facet_r_ds, self.fphi))

    def integrate(self, values_qp: np.ndarray) -> float:
        """int values r dA (times 2 pi gives the volume integral)."""
        return float(np.sum(values_qp * self.r_dx))

    def integrate_boundary(self, values_fqp: np.ndarray) -> float:
        return float(np.sum(values_fqp * self.facet_r_ds))


@njit(cache=True)
def _system_data(phi, grad, r_dx, mass_coefficient, conductivity, cell_positions, robin_kernel, robin_coefficient,
                 facet_positions, data):  # pragma: no cover (compiled)
    """data = sum over elements of int (m phi_i phi_j + k grad phi_i . grad phi_j) r dA, plus the Robin facet
    matrices int h phi_i phi_j r ds, on the element pattern (``*_positions[e, i * nloc + j]``)."""
    ne, nq, nloc = phi.shape
    data[:] = 0.0
    Ke = np.empty((nloc, nloc))
    for e in range(ne):
        Ke[:, :] = 0.0
        for q in range(nq):
            cm = mass_coefficient[e, q] * r_dx[e, q]
            ck = conductivity[e, q] * r_dx[e, q]
            for i in range(nloc):
                mi = cm * phi[e, q, i]
                gx, gz = ck * grad[e, q, i, 0], ck * grad[e, q, i, 1]
                for j in range(i, nloc):
                    Ke[i, j] += mi * phi[e, q, j] + gx * grad[e, q, j, 0] + gz * grad[e, q, j, 1]
        for i in range(nloc):
            data[cell_positions[e, i * nloc + i]] += Ke[i, i]
            for j in range(i + 1, nloc):
                data[cell_positions[e, i * nloc + j]] += Ke[i, j]
                data[cell_positions[e, j * nloc + i]] += Ke[i, j]
    nf, nqf, nk = robin_kernel.shape
    for f in range(nf):
        for k in range(nk):
            s = 0.0
            for q in range(nqf):
                s += robin_coefficient[f, q] * robin_kernel[f, q, k]
            data[facet_positions[f, k]] += s
